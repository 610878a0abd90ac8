#include "mesh/mesh.hpp"

#include <stdexcept>

#include "compiled/bspline_geometry.hpp"
#include "compiled/implicit_curve_geometry.hpp"
#include "compiled/parametric_curve_geometry.hpp"
#include "compiled/parametric_surface_geometry.hpp"
#include "mesh/bspline_mesh.hpp"
#include "mesh/curve_mesh.hpp"
#include "mesh/implicit_surface_mesh.hpp"
#include "mesh/surface_mesh.hpp"

namespace footpoint {

Mesh mesh_geometry(const CompiledGeometry& geometry, const MeshOptions& options) {
  if (options.resolution < 2) throw std::invalid_argument("a mesh needs a resolution of at least 2");
  if (const auto* s = dynamic_cast<const ParametricSurface*>(&geometry))
    return mesh_parametric_surface(*s, options.resolution);
  if (const auto* c = dynamic_cast<const ParametricCurve*>(&geometry))
    return mesh_parametric_curve(*c, options.resolution);
  if (const auto* c = dynamic_cast<const ImplicitCurve*>(&geometry))
    return mesh_implicit_curve(*c, options.resolution);
  if (const auto* s = dynamic_cast<const ImplicitSurface*>(&geometry))
    return mesh_implicit_surface(*s, options.resolution);
  if (const auto* s = dynamic_cast<const BSplineSurface*>(&geometry))
    return mesh_bspline_surface(*s, options.resolution);
  if (const auto* c = dynamic_cast<const BSplineCurve*>(&geometry))
    return mesh_bspline_curve(*c, options.resolution);
  throw std::invalid_argument("no mesh for this kind of geometry");
}

}  // namespace footpoint
