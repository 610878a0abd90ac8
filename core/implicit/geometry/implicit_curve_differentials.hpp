// Differential geometry of the implicit curve C: {f1 = 0} ∩ {f2 = 0} at a point, from the exact
// jets ([Curve] Section 2): the tangent T = grad f1 x grad f2, the curvature
// vector c of eqs. (15)-(16), and the orthogonality function F(X) = <T(X), P - X> of eq. (7) with
// its gradient.
#pragma once
#include "implicit/geometry/implicit_curve.hpp"

namespace footpoint::curve {

// Unit tangent T / |T| (zero at a singular point, where T = 0).
Vec3 unit_tangent(const ImplicitJet& j);

// The curvature vector c = d^2 X / ds^2 of eq. (16): differentiating eq. (14) <T, grad f_i> = 0
// along the arc length s gives eq. (15),
//   <grad f1, c> = -T^T F2 T,  <grad f2, c> = -T^T G2 T,  <T, c> = 0,
// with T the unit tangent and F2, G2 the Hessians; c = W2^{-1} [-T F2 T^T, -T G2 T^T, 0]^T where
// W2 has the rows grad f1, grad f2, T. Returns false at a singular point (W2 singular).
bool curvature_vector(const ImplicitJet& j, Vec3& c);

// F(X) = <T(X), P - X> (eq. (7)) and its gradient
//   dF/dx_k = <dT/dx_k, P - X> - T_k,   dT/dx_k = (F2 e_k) x grad f2 + grad f1 x (G2 e_k).
struct OrthogonalityFunction {
  double value = 0.0;
  Vec3 gradient;
};
OrthogonalityFunction orthogonality_function(const ImplicitJet& j, Vec3 x, Vec3 p);

// Newton's step δ on G(X) = (f1(X), f2(X), F(X)), whose zeros are the curve's critical points of
// the distance from P ([Curve] eqs. (5), (7)): the rows ∇f1, ∇f2, ∇F of G' at x times δ equal
// -(f[0], f[1], F(x)), with f the values of f1 and f2 at x to use (the jet's own, or more
// accurate ones). False when G' is singular there.
bool critical_point_step(const ImplicitJet& j, Vec3 x, Vec3 p, const std::array<double, 2>& f, Vec3& step);

}  // namespace footpoint::curve
