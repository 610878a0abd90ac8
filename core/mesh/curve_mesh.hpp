// Meshes of curves: polylines with a unit tangent per vertex.
#pragma once
#include "compiled/implicit_curve_geometry.hpp"
#include "compiled/parametric_curve_geometry.hpp"
#include "mesh/mesh.hpp"

namespace footpoint {

// `resolution` segments over [tmin, tmax], their ends equidistributed (equidistribution.hpp) by
// chord length and the tangent's turn; vertices c(t_i), tangents c'(t_i) / |c'(t_i)| from the
// formula tape's exact jets (the chord's direction where c' = 0, a cusp). A vertex that is not
// finite breaks the polyline; pieces of a single vertex are left out. A closed curve (its closure,
// parametric/geometry/curve_closure.hpp) gives a closed polyline, without a second vertex at c(tmax) =
// c(tmin).
Mesh mesh_parametric_curve(const ParametricCurve& curve, int resolution);

// The pieces the `auto` seeding traced (implicit/seeding/curve_discovery.hpp), followed along their links:
// a loop is a closed polyline; a piece ends at a box face, at a singular point or where its walk
// stopped. When the pieces hold more than `resolution` + 1 samples, every k-th sample is kept
// (k = ceil(samples / resolution)), and so are each piece's ends and face crossings. Each
// singular point is a vertex (Mesh::singular_points, tangent 0: there is none), and an open
// piece whose end is within two sample spacings of one is joined to it. Tangents are
// grad f1 x grad f2 / |.| oriented along the polyline (the chord's direction where it vanishes).
Mesh mesh_implicit_curve(const ImplicitCurve& curve, int resolution);

}  // namespace footpoint
