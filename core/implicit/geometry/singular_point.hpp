// Singular points of an implicit curve: points of f1 = f2 = 0 where grad f1 x grad f2 = 0 (the
// surfaces touch; e.g. the double point of Viviani's curve). There T = 0 and every formula of the
// [Curve] divides by zero (its Remark 4). They are found as the critical points of f1
// on the surface f2 = 0, Newton on
//   grad f1 - mu grad f2 = 0,  f2 = 0          (unknowns x, y, z, mu; 4 x 4 Jacobian
//   [[F2 - mu G2, -grad f2], [grad f2^T, 0]]) followed by the check f1 = 0. For planar curves
// (f2 = z) this is grad f = 0 in the plane.
//
// Where the singular point is a regular zero of that system (a node, such as the lemniscate's
// crossing or Viviani's double point: the 4 x 4 Jacobian, or the Hessian of f for planar curves,
// is nonsingular there), Krawczyk's test ([Krawczyk], [Moore77]; geometry/krawczyk.hpp) on a small
// box around the refined point proves it the only one in the box and gives a tight enclosure.
// Where it is not (a cusp y^2 = x^3, a tacnode y^2 = x^4: the Jacobian is singular there) the test
// cannot succeed; such points are bounded by the unproved boxes of the subdivision instead.
#pragma once
#include <optional>

#include "geometry/box3.hpp"
#include "implicit/geometry/implicit_curve.hpp"

namespace footpoint::curve {

// Refines x (a point near a singular point) in place. True when Newton converged to a point with
// |f1| / |grad f2|-scaled residual below 1e-10 max(1, |x|) (a singular point of the curve).
bool refine_singular_point(const ImplicitEquations& equations, Vec3& x);

// A box around x (a refined singular point) holding exactly one zero of the singular system, the
// only critical point of f1 on f2 = 0 (planar: of f) there; nothing when Krawczyk's test fails on
// every radius tried (a degenerate singular point, or x not near one). The radii tried start at
// `radius` and shrink.
std::optional<Box3> isolate_singular_point(const ImplicitEquations& equations, Vec3 x, double radius);

}  // namespace footpoint::curve
