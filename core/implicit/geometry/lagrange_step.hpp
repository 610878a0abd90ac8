// The Newton step of the Lagrange (KKT) system of min |p - X|^2 / 2 subject to f1(X) = f2(X) = 0
// (implicit/solvers/lagrange_newton.hpp):
//   [A  J^T] [dx]   [-r]      A = I + l1 H1 + l2 H2 (symmetric), J = [g1^T; g2^T] (the gradients),
//   [J   0 ] [dl] = [-f],     r = X - p + l1 g1 + l2 g2,  f = (f1, f2),
// by the null-space method (J. Nocedal, S. J. Wright, Numerical Optimization, 2nd ed., Springer
// 2006, Section 16.2), whose null space of J is spanned by the tangent t = g1 x g2. The reciprocal
// basis of (g1, g2, t),
//   u1 = (g2 x t) / |t|^2,   u2 = (t x g1) / |t|^2   (g_i . u_j = delta_ij, t . u_j = 0),
// gives the step in three parts:
//   the normal part      n = -f1 u1 - f2 u2                 (J n = -f, n orthogonal to t);
//   the tangential part  dx = n + s t,  s = -t.(r + A n) / t.A t   (the first block row along t,
//                        where J^T dl has no component);
//   the multipliers      dl_j = -u_j . (r + A dx)           (the first block row in the normal plane).
// Three cross products, two matrix-vector products and a few dot products, with no pivot search:
// a 5 x 5 Gaussian elimination (geometry/dense_solve.hpp) costs several times more, most of it in
// its data-dependent branches. The system is singular exactly where t = 0 (parallel gradients:
// a singular point of the curve) or t.A t = 0 (a degenerate second variation along the curve);
// the step is refused where either is below 64 eps of its scale (|t| against |g1| |g2|, t.A t
// against max |A_ij| |t|^2: the tolerance dense_solve uses for its pivots, taken relative to
// each) or the result is not finite.
#pragma once
#include <algorithm>
#include <cmath>
#include <limits>

#include "implicit/geometry/implicit_curve.hpp"

namespace footpoint {

struct LagrangeStep {
  Vec3 dx;
  double dl1 = 0.0, dl2 = 0.0;
};

inline bool lagrange_step(const Mat3& a, Vec3 g1, Vec3 g2, Vec3 r, double f1, double f2, LagrangeStep& step) {
  constexpr double kTiny = 64.0 * std::numeric_limits<double>::epsilon();
  const Vec3 t = cross(g1, g2);
  const double tt = dot(t, t);
  if (!(tt > kTiny * kTiny * norm2(g1) * norm2(g2))) return false;
  const Vec3 u1 = cross(g2, t) / tt, u2 = cross(t, g1) / tt;
  const Vec3 n = -f1 * u1 - f2 * u2;
  const Vec3 at = a * t;
  const double tat = dot(t, at);
  double scale = 0.0;
  for (const Vec3& row : a) scale = std::max({scale, std::fabs(row.x), std::fabs(row.y), std::fabs(row.z)});
  if (!(std::fabs(tat) > kTiny * scale * tt)) return false;
  const Vec3 an = a * n;
  const double s = -(dot(t, r) + dot(t, an)) / tat;
  step.dx = n + s * t;
  const Vec3 residual = r + an + s * at;
  step.dl1 = -dot(u1, residual);
  step.dl2 = -dot(u2, residual);
  return is_finite(step.dx) && std::isfinite(step.dl1) && std::isfinite(step.dl2);
}

}  // namespace footpoint
