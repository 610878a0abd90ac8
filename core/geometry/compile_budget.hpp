// What compiling a geometry may take: time and memory. Building what `auto` precomputes
// (subdivision, tracing, adaptive sampling) can be slow and large for wild formulas over large
// domains, so compile_geometry makes one budget from the request's limits and hands it to every
// loop that builds a search structure:
//   - the deadline: the loops call check() every so often; past the deadline it throws
//     GeometryError "compile_timeout";
//   - the bytes: where the search structures grow (the samples, cells and chains of
//     core/parametric/seeding and core/implicit/seeding), the loops call grow() with the bytes each
//     new element commits the compiled geometry to; past the bound it throws GeometryError
//     "geometry_too_large" naming the bytes reached, so that a definition whose structure would be
//     over the bound is refused while it is built, not after. What grow() counts is a lower bound
//     of the compiled geometry's memory_bytes(), so a geometry stopped here would have been over
//     the bound once built too.
// Either way the request gets a clear 422 instead of holding a thread and its memory.
//
// A budget belongs to one compile on one thread (no locking). Code that builds a structure outside
// a compile (tests, benches, a structure filled while projecting) passes a budget of its own;
// `CompileBudget{}` has no deadline and no bound and only counts.
#pragma once
#include <chrono>
#include <cstddef>

namespace footpoint {

class CompileBudget {
 public:
  using clock = std::chrono::steady_clock;
  // The deadline and the bound on bytes (0: none), with nothing grown yet.
  explicit CompileBudget(clock::time_point deadline = clock::time_point::max(), std::size_t max_bytes = 0)
      : deadline_(deadline), max_bytes_(max_bytes) {}
  CompileBudget(const CompileBudget&) = delete;
  CompileBudget& operator=(const CompileBudget&) = delete;

  // Cheap: reads the clock once every 64 calls. Throws GeometryError when the deadline has passed.
  void check() {
    if (deadline_ == clock::time_point::max() || (++calls_ & 63u) != 0) return;
    throw_if_past_deadline();
  }
  // Counts `bytes` more of the structure being built. Throws GeometryError geometry_too_large when
  // the count passes the bound.
  void grow(std::size_t bytes) {
    bytes_ += bytes;
    if (max_bytes_ != 0 && bytes_ > max_bytes_) throw_too_large();
  }
  // What has been counted by grow().
  std::size_t grown() const { return bytes_; }

 private:
  void throw_if_past_deadline() const;
  [[noreturn]] void throw_too_large() const;

  clock::time_point deadline_;
  std::size_t max_bytes_;
  std::size_t bytes_ = 0;
  unsigned calls_ = 0;
};

}  // namespace footpoint
