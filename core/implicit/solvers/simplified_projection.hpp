// [Curve] Algorithm 5, the simplified algorithm: Algorithm 1 from the start,
// then eq. (20),
//   Y_n     = X_n - f1(X_n) / |grad f1(X_n)|^2 grad f1(X_n),
//   Z_n     = Y_n - f2(Y_n) / |grad f2(Y_n)|^2 grad f2(Y_n),
//   X_{n+1} = Z_n - F(Z_n) / |grad F(Z_n)|^2 grad F(Z_n),      F = <T, P - X> (eq. (7)),
// (eq. (19) without the correction vector) until the iterates stop moving.
#pragma once
#include "implicit/geometry/implicit_curve.hpp"
#include "projection/projection_result.hpp"

namespace footpoint::curve {

ProjectionResult simplified_projection(const ImplicitEquations& equations, const Box3& box, Vec3 p,
                                       const Options& options);

}  // namespace footpoint::curve
