#include "parametric/solvers/surface_auto.hpp"

#include "parametric/solvers/surface_search.hpp"

namespace footpoint::surface {

ProjectionResult project_auto(const SurfaceCells& cells, const SurfaceFormulas& formulas, const ParamBox& box,
                              const SurfaceClosure& closure, const Vec3& p, const Options& options) {
  SurfaceSearch search(cells, formulas, box, closure, p, options);
  search.run();
  return search.result();
}

}  // namespace footpoint::surface
