// The mesh of a parametric surface: a tensor grid of parameter lines, each direction's lines
// equidistributed (equidistribution.hpp) by the chord length and the normal's turn averaged over
// 9 cross lines, each quad split along its shorter diagonal. Positions and normals come from the
// formula tape's exact jets (n = s_u x s_v / |s_u x s_v|); where s_u x s_v vanishes (a pole, a
// cone's apex) the normal is the area-weighted mean of the incident triangles' normals.
// Triangles of (nearly) zero area - a quad at a pole collapses to one triangle - and triangles
// with a vertex that is not finite are left out, and so are vertices no triangle uses.
#pragma once
#include "compiled/parametric_surface_geometry.hpp"
#include "mesh/mesh.hpp"

namespace footpoint {

// Cells along the direction with the larger share of the measure: `resolution`; along the other
// its share of it, at least 2. Seams and poles are stitched as the surface's closure (found at
// compile time, parametric/geometry/surface_closure.hpp) names them: the grid lines of a periodic
// direction's two edges share their vertices, a pole is one vertex with a fan of triangles around
// it, so a closed surface gives a closed mesh (a torus V - E + F = 0, a sphere 2). A reversed seam
// (a Möbius band) is left open: no consistent normals could cross it.
Mesh mesh_parametric_surface(const ParametricSurface& surface, int resolution);
// The same with the seams and poles `closure` names instead (SurfaceClosure{}: a plain grid).
Mesh mesh_parametric_surface(const ParametricSurface& surface, int resolution, const SurfaceClosure& closure);

}  // namespace footpoint
