// Meshes of B-spline and NURBS curves and surfaces (compiled/bspline_geometry.hpp): parameter grids
// whose lines include every knot (so a C0 joint is an edge of the mesh), the remaining lines spread
// over the spans in proportion to their lengths in parameter; positions, normals and tangents from
// the NURBS itself (de Boor, parametric/geometry/nurbs.hpp). A closed direction's first and last
// grid lines share their vertices; quads split along the shorter diagonal; triangles of (nearly)
// zero area (at a pole) are left out, and so are vertices no triangle uses.
#pragma once
#include "compiled/bspline_geometry.hpp"
#include "mesh/mesh.hpp"

namespace footpoint {

// `resolution` cells along each parameter (at least one per knot span).
Mesh mesh_bspline_surface(const BSplineSurface& surface, int resolution);
// `resolution` segments (at least one per knot span); a closed curve gives a closed polyline.
Mesh mesh_bspline_curve(const BSplineCurve& curve, int resolution);

}  // namespace footpoint
