#include "geometry/compile_budget.hpp"

#include <string>

#include "geometry/geometry_error.hpp"

namespace footpoint {

namespace {
thread_local CompileBudget::clock::time_point t_deadline = CompileBudget::clock::time_point::max();
thread_local unsigned t_calls = 0;
thread_local std::size_t t_max_bytes = 0;
thread_local std::size_t t_bytes = 0;
}  // namespace

CompileBudget::CompileBudget(clock::time_point deadline, std::size_t max_bytes)
    : previous_deadline_(t_deadline), previous_max_bytes_(t_max_bytes), previous_bytes_(t_bytes) {
  t_deadline = deadline;
  t_max_bytes = max_bytes;
  t_bytes = 0;
}

CompileBudget::~CompileBudget() {
  t_deadline = previous_deadline_;
  t_max_bytes = previous_max_bytes_;
  t_bytes = previous_bytes_;
}

void CompileBudget::check() {
  if (t_deadline == clock::time_point::max() || (++t_calls & 63u) != 0) return;
  if (clock::now() >= t_deadline)
    throw GeometryError(
        "compile_timeout", "", -1,
        "building the geometry's search structure did not finish within the request deadline; "
        "simplify the formulas or shrink the domain");
}

void CompileBudget::grow(std::size_t bytes) {
  t_bytes += bytes;
  if (t_max_bytes == 0 || t_bytes <= t_max_bytes) return;
  throw GeometryError("geometry_too_large", "", -1,
                      "building the geometry's search structure reached " + std::to_string(t_bytes) +
                          " bytes, over the limit of " + std::to_string(t_max_bytes) +
                          " per geometry, and was stopped there: narrow the domain or simplify the formulas");
}

std::size_t CompileBudget::grown() { return t_bytes; }

}  // namespace footpoint
