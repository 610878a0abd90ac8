// What compiling a geometry may take: time and memory. Building what `auto` precomputes
// (subdivision, tracing, adaptive sampling) can be slow and large for wild formulas over large
// domains, so compile_geometry installs the request's budget for the compiling thread:
//   - the deadline: the seeding loops call CompileBudget::check() every so often; past the
//     deadline it throws GeometryError "compile_timeout";
//   - the bytes: where the search structures grow (the samples, cells and chains of
//     core/parametric/seeding and core/implicit/seeding), the loops call CompileBudget::grow()
//     with the bytes each new element commits the compiled geometry to; past the bound it throws
//     GeometryError "geometry_too_large" naming the bytes reached, so that a definition whose
//     structure would be over the bound is refused while it is built, not after. What grow()
//     counts is a lower bound of the compiled geometry's memory_bytes(), so a geometry stopped
//     here would have been over the bound once built too.
// Either way the request gets a clear 422 instead of holding a thread and its memory.
#pragma once
#include <chrono>
#include <cstddef>

namespace footpoint {

class CompileBudget {
 public:
  using clock = std::chrono::steady_clock;
  // Installs the deadline and the bound on bytes (0: none) for this thread, with nothing grown yet.
  explicit CompileBudget(clock::time_point deadline, std::size_t max_bytes = 0);
  ~CompileBudget();  // restores the previous budget
  CompileBudget(const CompileBudget&) = delete;
  CompileBudget& operator=(const CompileBudget&) = delete;

  // Cheap: reads the clock once every 64 calls. Throws GeometryError when the deadline has passed.
  static void check();
  // Counts `bytes` more of the structure being built. Throws GeometryError geometry_too_large when
  // the count passes the bound.
  static void grow(std::size_t bytes);
  // What has been counted by grow() since this thread's budget was installed.
  static std::size_t grown();

 private:
  clock::time_point previous_deadline_;
  std::size_t previous_max_bytes_, previous_bytes_;
};

}  // namespace footpoint
