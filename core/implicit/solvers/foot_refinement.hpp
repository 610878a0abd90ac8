// Iterative refinement of a foot point on a curve cut by two nearly tangent surfaces.
//
// Where ∇f1 and ∇f2 meet at a small angle θ, the curve's points are ill-determined: a change δ
// of f1 or f2 moves the curve by about δ / (|∇f_i| sin θ). A foot point x solved in double
// precision has residuals f_i(x) as large as the rounding of their evaluation, u times the
// magnitudes of the terms, so its position is off by that over sin θ: for two unit spheres
// meeting at 0.01 rad, ~1e-13, more than the certificate's gap (projection/certificate.hpp).
// Refinement (Wilkinson's iterative refinement: the residual in higher precision, the
// correction in working precision; N. J. Higham, Accuracy and Stability of Numerical Algorithms,
// 2nd ed., SIAM 2002, Chapter 12) takes Newton steps on G = (f1, f2, F), F = <T, p - x>
// ([Curve] eq. (7)), with f1, f2 evaluated to the rounding of their values
// (ImplicitEquations::accurate_values), which leaves x about as accurate as its coordinates'
// own rounding. Only where sin θ < kRefineSine, and for polynomial equations.
#pragma once
#include "implicit/geometry/implicit_curve.hpp"

namespace footpoint::curve {

inline constexpr double kRefineSine = 0.1;

// Refines x in place (at most two steps, each kept only if it lowers the accurate residuals
// max_i |f_i| / |∇f_i|); true when x moved.
bool refine_foot(const ImplicitEquations& equations, Vec3 p, Vec3& x);

}  // namespace footpoint::curve
