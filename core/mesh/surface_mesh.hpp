// The mesh of a parametric surface: a tensor grid of parameter lines, each direction's lines
// equidistributed (equidistribution.hpp) by the chord length and the normal's turn averaged over
// 9 cross lines, each quad split along its shorter diagonal. Positions and normals come from the
// formula tape's exact jets (n = s_u x s_v / |s_u x s_v|); where s_u x s_v vanishes (a pole, a
// cone's apex) the normal is the area-weighted mean of the incident triangles' normals.
// Triangles of (nearly) zero area - a quad at a pole collapses to one triangle - and triangles
// with a vertex that is not finite are left out, and so are vertices no triangle uses.
#pragma once
#include <array>

#include "compiled/parametric_surface_geometry.hpp"
#include "mesh/mesh.hpp"

namespace footpoint {

// Where a surface's parameter domain meets itself. A closed direction: the edges u = umin and
// u = umax are the same curve, traversed the same way (s(umin, v) = s(umax, v) for every v; a
// torus, a sphere's longitude); a pole: a whole edge maps to one point (a sphere's poles). The
// mesh stitches them: the grid lines of the two edges share their vertices, a pole is one vertex
// with a fan of triangles around it, so a closed surface gives a closed mesh.
struct SurfaceClosure {
  bool u_closed = false;
  bool v_closed = false;
  // The edges u = umin, u = umax, v = vmin, v = vmax, in that order: true when it is one point.
  std::array<bool, 4> pole{};
};

// Cells along the direction with the larger share of the measure: `resolution`; along the other
// its share of it, at least 2. Compiled surfaces do not know their seams and poles, so the API's
// meshes are plain grids (closure = {}); a closure names them.
Mesh mesh_parametric_surface(const ParametricSurface& surface, int resolution,
                             const SurfaceClosure& closure = {});

}  // namespace footpoint
