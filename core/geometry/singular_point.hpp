// Singular points of an implicit curve: points of f1 = f2 = 0 where grad f1 x grad f2 = 0 (the
// surfaces touch; e.g. the double point of Viviani's curve). There T = 0 and every formula of the
// [Curve] divides by zero (its Remark 4). They are found as the critical points of f1
// on the surface f2 = 0, Newton on
//   grad f1 - mu grad f2 = 0,  f2 = 0          (unknowns x, y, z, mu; 4 x 4 Jacobian
//   [[F2 - mu G2, -grad f2], [grad f2^T, 0]]) followed by the check f1 = 0. For planar curves
// (f2 = z) this is grad f = 0 in the plane.
#pragma once
#include "geometry/implicit_curve.hpp"

namespace footpoint::curve {

// Refines x (a point near a singular point) in place. True when Newton converged to a point with
// |f1| / |grad f2|-scaled residual below 1e-10 max(1, |x|) (a singular point of the curve).
bool refine_singular_point(const ImplicitEquations& equations, Vec3& x);

}  // namespace footpoint::curve
