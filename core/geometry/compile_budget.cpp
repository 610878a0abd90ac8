#include "geometry/compile_budget.hpp"

#include <string>

#include "geometry/geometry_error.hpp"

namespace footpoint {

void CompileBudget::throw_if_past_deadline() const {
  if (clock::now() >= deadline_)
    throw GeometryError(
        "compile_timeout", "", -1,
        "building the geometry's search structure did not finish within the request deadline; "
        "simplify the formulas or shrink the domain");
}

void CompileBudget::throw_too_large() const {
  throw GeometryError("geometry_too_large", "", -1,
                      "building the geometry's search structure reached " + std::to_string(bytes_) +
                          " bytes, over the limit of " + std::to_string(max_bytes_) +
                          " per geometry, and was stopped there: narrow the domain or simplify the formulas");
}

}  // namespace footpoint
