// The planar iteration of [Curve]'s introduction (Hartmann's tangent foot point
// method) for f(x, y) = 0: Newton's steepest descent, eq. (2),
//   X_{n+1} = X_n - f(X_n) / <grad f(X_n), grad f(X_n)> grad f(X_n),
// until the point Y lies on the curve; then the foot point of p on the tangent line at Y, eq. (4),
//   Q = P - <P - Y, grad f(Y)> / <grad f(Y), grad f(Y)> grad f(Y),
// is the next start; repeated until the curve points Y stop moving. Start: P - (0.1, 0.1) (as the
// paper's Algorithm 1) or options.initial.
#pragma once
#include "implicit/geometry/implicit_curve.hpp"
#include "projection/projection_result.hpp"

namespace footpoint::curve {

ProjectionResult tangent_foot(const ImplicitEquations& equations, const Box3& box, Vec3 p,
                              const Options& options);

}  // namespace footpoint::curve
