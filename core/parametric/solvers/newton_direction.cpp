#include "parametric/solvers/newton_direction.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace footpoint::surface {

NewtonDirection newton_direction(const double (&H)[2][2], const double (&g)[2], const bool (&free_)[2]) {
  NewtonDirection n;
  double* d = n.step.data();
  const double a = H[0][0], b = H[0][1], c = H[1][1];
  const double hs = std::max({std::abs(a), std::abs(b), std::abs(c)});
  n.det = a * c - b * b;
  // H positive definite with λ1 = det / λ2 >= det / (a + c) >= kSemidefinite hs: the Newton
  // step itself (what the eigen-decomposition below gives there, without its square roots)
  n.definite = free_[0] && free_[1] && a > 0.0 && n.det >= kSemidefinite * hs * (a + c);
  if (n.definite) {
    d[0] = -(c * g[0] - b * g[1]) / n.det;
    d[1] = -(a * g[1] - b * g[0]) / n.det;
  } else if (free_[0] && free_[1]) {
    // H = λ1 e1 e1^T + λ2 e2 e2^T; the step uses |λ_i| (bounded away from 0): the Newton step
    // where H is positive definite, and a descent step of natural length along negative
    // curvature where it is not
    const double mid = 0.5 * (a + c), rad = std::sqrt(0.25 * (a - c) * (a - c) + b * b);
    const double l1 = mid - rad, l2 = mid + rad;  // l1 <= l2
    n.convex = l1 >= -kSemidefinite * hs;
    // unit eigenvector of l1: (b, l1 - a) or (l1 - c, b), whichever is better conditioned
    double e0 = b, e1 = l1 - a;
    if (std::abs(e0) + std::abs(e1) < std::abs(l1 - c) + std::abs(b)) e0 = l1 - c, e1 = b;
    double en = std::sqrt(e0 * e0 + e1 * e1);
    if (!(en > 0.0)) e0 = 1.0, e1 = 0.0, en = 1.0;  // H = λ I
    e0 /= en;
    e1 /= en;
    const double floor_l = std::max(kSemidefinite * hs, std::numeric_limits<double>::min());
    const double g1 = e0 * g[0] + e1 * g[1], g2 = -e1 * g[0] + e0 * g[1];
    const double s1 = g1 / std::max(std::abs(l1), floor_l), s2 = g2 / std::max(std::abs(l2), floor_l);
    d[0] = -(s1 * e0 - s2 * e1);
    d[1] = -(s1 * e1 + s2 * e0);
    if (!n.convex) n.negative_curvature = {e0, e1};
  } else {
    const int i = free_[0] ? 0 : 1;
    const double h = H[i][i];
    n.convex = h >= -kSemidefinite * std::abs(h);
    d[i] = -g[i] / std::max(std::abs(h), std::numeric_limits<double>::min());
    if (!n.convex) n.negative_curvature[static_cast<std::size_t>(i)] = 1.0;
  }
  return n;
}

}  // namespace footpoint::surface
