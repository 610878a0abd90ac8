#include "implicit/solvers/lagrange_newton.hpp"

#include <cmath>

#include "geometry/dense_solve.hpp"
#include "implicit/geometry/implicit_curve_differentials.hpp"
#include "implicit/geometry/lagrange_step.hpp"

namespace footpoint::curve {
namespace {

// Least-squares multipliers: p - X = l1 g1 + l2 g2 in the normal plane.
bool multipliers(const ImplicitJet& j, Vec3 r, double& l1, double& l2) {
  Matrix<2> g{{{dot(j.grad[0], j.grad[0]), dot(j.grad[0], j.grad[1])},
               {dot(j.grad[1], j.grad[0]), dot(j.grad[1], j.grad[1])}}};
  Vector<2> b{dot(j.grad[0], r), dot(j.grad[1], r)};
  if (!dense_solve<2>(g, b)) return false;
  l1 = b[0];
  l2 = b[1];
  return true;
}

}  // namespace

LocalMinimum lagrange_newton(const ImplicitEquations& equations, Vec3 p, Vec3 x0, double max_step,
                             const IterationControl& control) {
  LocalMinimum out;
  out.x = x0;
  ImplicitJet j = equations.jet(out.x);
  double l1 = 0.0, l2 = 0.0;
  if (!multipliers(j, p - out.x, l1, l2)) return out;
  double previous = kInfinity;
  int shortened = 0;
  for (int n = 0; n < control.max_iterations; ++n) {
    Mat3 a;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c)
        a[r][c] = (r == c ? 1.0 : 0.0) + l1 * j.hess[0][r][c] + l2 * j.hess[1][r][c];
    LagrangeStep step;
    if (!lagrange_step(a, j.grad[0], j.grad[1], out.x - p + l1 * j.grad[0] + l2 * j.grad[1], j.f[0], j.f[1],
                       step))
      return out;
    Vec3 dx = step.dx;
    double dl1 = step.dl1, dl2 = step.dl2;
    const double length = norm(dx);
    if (length > max_step) {
      // A long step leaves the neighbourhood the sample vouches for: shorten it, and give up
      // when that keeps happening (the start was not near a minimum).
      const double s = max_step / length;
      dx = s * dx;
      dl1 *= s;
      dl2 *= s;
      if (++shortened > 8) return out;
    }
    out.x += dx;
    l1 += dl1;
    l2 += dl2;
    out.step = norm(dx);
    out.iterations = n + 1;
    control.record(dx.x, dx.y, dx.z);
    if (!is_finite(out.x)) return out;
    j = equations.jet(out.x);
    if (control.stop(out.step, norm(out.x), previous)) {
      out.converged = true;
      break;
    }
  }
  if (out.converged) {
    out.jet = j;
    const Vec3 t = unit_tangent(j);
    // Multipliers at the solution, for the second variation.
    multipliers(j, p - out.x, l1, l2);
    out.second_variation = dot(t, t) + l1 * dot(t, j.hess[0] * t) + l2 * dot(t, j.hess[1] * t);
  }
  return out;
}

}  // namespace footpoint::curve
