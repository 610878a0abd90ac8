// The local solver of `auto` for implicit curves: Newton's method on the Lagrange (KKT) system of
// min |p - X|^2 / 2 subject to f1(X) = f2(X) = 0,
//   X - p + l1 grad f1(X) + l2 grad f2(X) = 0,   f1(X) = 0,   f2(X) = 0,
// with the 5 x 5 Jacobian [[I + l1 F2 + l2 G2, grad f1, grad f2], [grad f1^T, 0, 0],
// [grad f2^T, 0, 0]] (F2, G2 the exact Hessians), each step solved by the null-space method
// (implicit/geometry/lagrange_step.hpp). Quadratic convergence from a nearby curve point; the multipliers
// start at the least-squares solution of p - X = l1 grad f1 + l2 grad f2.
#pragma once
#include "implicit/geometry/implicit_curve.hpp"
#include "solvers/iteration_control.hpp"

namespace footpoint::curve {

struct LocalMinimum {
  Vec3 x;
  int iterations = 0;
  double step = 0.0;
  bool converged = false;
  // Second variation of |p - X|^2 / 2 along the unit tangent, T^T (I + l1 F2 + l2 G2) T: a
  // minimum along the curve needs it >= 0.
  double second_variation = 0.0;
  ImplicitJet jet;  // at x, when converged: the last evaluation, for the residuals and what follows
};

// From the curve point x0; each step is shortened to at most max_step (the sample spacing: the
// start is that close to the minimum it belongs to).
LocalMinimum lagrange_newton(const ImplicitEquations& equations, Vec3 p, Vec3 x0, double max_step,
                             const IterationControl& control);

}  // namespace footpoint::curve
