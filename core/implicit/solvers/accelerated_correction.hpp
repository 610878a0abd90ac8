// [Curve] Algorithm 3, the accelerating and geometric correcting method, eq. (19):
//   Y_n     = X_n - f1(X_n) / |grad f1(X_n)|^2 grad f1(X_n),
//   Z_n     = Y_n - f2(Y_n) / |grad f2(Y_n)|^2 grad f2(Y_n),
//   U_n     = Z_n - F(Z_n) / |grad F(Z_n)|^2 grad F(Z_n),          F = <T, P - X>  (eq. (7))
//   X_{n+1} = U_n + dV,
// with the correction vector dV of eqs. (17)-(18): <grad f1, dV> = -err1, <grad f2, dV> = -err2,
// <(T x c) x DV, dV> = 0, where err_i = f_i(Z_n), grad f_i, T and the curvature vector c (eq. (16))
// are taken at Z_n and DV = U_n - Z_n. (Eq. (17) prints 0 on the right of its first two rows; eq.
// (18) has -err1, -err2, which is what makes dV a correction; we follow eq. (18).)
#pragma once
#include "implicit/geometry/implicit_curve.hpp"
#include "implicit/solvers/paper_iteration.hpp"
#include "projection/projection_result.hpp"
#include "solvers/iteration_control.hpp"

namespace footpoint::curve {

// Algorithm 3 from the curve point x0 (the output of Algorithm 1): iterate eq. (19) until the step
// stops moving. When the third row of eq. (18) vanishes (DV = 0 at convergence, or DV parallel to
// T x c) dV is the minimum-norm solution of its first two rows.
// Known limit: on a curve that lies in a plane, T x c is the plane's normal and, at the foot point,
// the third row of eq. (18) is the curve's normal in the plane, a combination of grad f1 and
// grad f2: dV is not determined there, and the iterates wander near the foot point until the
// budget ends them (max_iterations).
Landing accelerate_onto_foot(const ImplicitEquations& equations, Vec3 p, Vec3 x0,
                             const IterationControl& control);

// The method `accelerated`: Algorithm 1 from the paper's start (Algorithm 3 needs a point on the
// curve), then Algorithm 3.
ProjectionResult accelerated(const ImplicitEquations& equations, const Box3& box, Vec3 p,
                             const Options& options);

// One step Z = Y - f_i(Y) / |grad f_i|^2 grad f_i of eqs. (19), (20) (newton_onto_surface at the jet
// of Y); false if grad f_i = 0.
bool newton_onto_equation(const ImplicitEquations& equations, int i, Vec3 y, Vec3& z);

// The step U = Z - F(Z) / |grad F(Z)|^2 grad F(Z) of eqs. (19), (20); false if grad F = 0.
bool newton_onto_orthogonality(const ImplicitJet& jz, Vec3 z, Vec3 p, Vec3& u);

}  // namespace footpoint::curve
