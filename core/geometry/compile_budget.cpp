#include "geometry/compile_budget.hpp"

#include "geometry/geometry_error.hpp"

namespace footpoint {

namespace {
thread_local CompileBudget::clock::time_point t_deadline = CompileBudget::clock::time_point::max();
thread_local unsigned t_calls = 0;
}  // namespace

CompileBudget::CompileBudget(clock::time_point deadline) : previous_(t_deadline) { t_deadline = deadline; }

CompileBudget::~CompileBudget() { t_deadline = previous_; }

void CompileBudget::check() {
  if (t_deadline == clock::time_point::max() || (++t_calls & 63u) != 0) return;
  if (clock::now() >= t_deadline)
    throw GeometryError(
        "compile_timeout", "", -1,
        "building the geometry's search structure did not finish within the request deadline; "
        "simplify the formulas or shrink the domain");
}

}  // namespace footpoint
