#include "geometry/singular_point.hpp"

#include <cmath>

#include "geometry/dense_solve.hpp"

namespace footpoint::curve {

bool refine_singular_point(const ImplicitEquations& equations, Vec3& x) {
  ImplicitJet j = equations.jet(x);
  const double g22 = norm2(j.grad[1]);
  if (!(g22 > 0.0)) return false;
  double mu = dot(j.grad[0], j.grad[1]) / g22;
  bool converged = false;
  // Quadratic at a double point; linear at a degenerate one (a cusp, or the tacnode where two
  // branches touch, whose Jacobian is singular there), hence the generous budget, and the
  // Jacobian is accepted down to tiny pivots: its small singular values belong to the directions
  // in which the iterates still converge, with bounded steps.
  for (int n = 0; n < 100 && !converged; ++n) {
    Matrix<4> a{};
    Vector<4> b{};
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) a[r][c] = j.hess[0][r][c] - mu * j.hess[1][r][c];
      a[r][3] = -j.grad[1][r];
      a[3][r] = j.grad[1][r];
      b[r] = -(j.grad[0][r] - mu * j.grad[1][r]);
    }
    b[3] = -j.f[1];
    if (!dense_solve<4>(a, b, 1e-300)) return false;
    const Vec3 dx{b[0], b[1], b[2]};
    x += dx;
    mu += b[3];
    if (!is_finite(x) || !std::isfinite(mu)) return false;
    converged = norm(dx) <= 1e-14 * std::max(1.0, norm(x));
    j = equations.jet(x);
  }
  if (!converged) return false;
  const double n1 = norm(j.grad[0]);
  const double scale = std::max(1.0, norm(x));
  // On the curve: f1 vanishes (relative to its gradient, or absolutely if grad f1 = 0 too).
  return std::fabs(j.f[0]) <= 1e-10 * scale * std::max(n1, 1.0) &&
         std::fabs(j.f[1]) <= 1e-10 * scale * std::sqrt(g22);
}

}  // namespace footpoint::curve
