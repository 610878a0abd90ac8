#include "geometry/compile_budget.hpp"
#include "geometry/geometry.hpp"

namespace footpoint {

std::shared_ptr<const CompiledGeometry> compile_geometry(const GeometryDefinition& def,
                                                         const formula::CompileLimits& limits) {
  const CompileBudget budget(limits.deadline);
  switch (def.type) {
    case GeometryType::parametric_surface:
      return compile_parametric_surface(def, limits);
    case GeometryType::parametric_curve:
      return compile_parametric_curve(def, limits);
    case GeometryType::implicit_curve:
      return compile_implicit_curve(def, limits);
  }
  throw GeometryError("bad_type", "type", -1, "unknown geometry type");
}

}  // namespace footpoint
