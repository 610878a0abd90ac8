// How long compiling a geometry may take. Building what `auto` precomputes (subdivision, tracing,
// adaptive sampling) can be slow for wild formulas over large domains, so compile_geometry installs
// the request's deadline for the compiling thread and the seeding loops call
// CompileBudget::check() every so often; past the deadline it throws GeometryError
// "compile_timeout", and the request gets a clear 422 instead of holding a thread.
#pragma once
#include <chrono>

namespace footpoint {

class CompileBudget {
 public:
  using clock = std::chrono::steady_clock;
  explicit CompileBudget(clock::time_point deadline);  // installs the deadline for this thread
  ~CompileBudget();                                    // restores the previous one
  CompileBudget(const CompileBudget&) = delete;
  CompileBudget& operator=(const CompileBudget&) = delete;

  // Cheap: reads the clock once every 64 calls. Throws GeometryError when the deadline has passed.
  static void check();

 private:
  clock::time_point previous_;
};

}  // namespace footpoint
