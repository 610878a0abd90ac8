#include "implicit/geometry/singular_point.hpp"

#include <cmath>

#include "geometry/dense_solve.hpp"
#include "geometry/krawczyk.hpp"

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

namespace {

namespace iv = formula::interval;

// Krawczyk on grad f = 0 (planar) over the box x ± r: the box when it holds exactly one zero.
std::optional<Box3> isolate_planar(const ImplicitEquations& eq, Vec3 x, double r) {
  const Box3 box{{x.x - r, x.y - r, 0.0}, {x.x + r, x.y + r, 0.0}};
  const ImplicitIntervalJet j = eq.interval_jet(box);
  const ImplicitIntervalJet jx = eq.interval_gradient({x, x});
  if (!j.smooth || !jx.smooth) return std::nullopt;
  IntervalMatrix<2> a{};
  IntervalVector<2> g{}, xb{};
  for (int i = 0; i < 2; ++i) {
    g[i] = jx.grad[0][i];
    xb[i] = {box.lo[i], box.hi[i]};
    for (int k = 0; k < 2; ++k) a[i][k] = j.hess[0][i][k];
  }
  const KrawczykResult<2> k = krawczyk<2>(xb, {x.x, x.y}, g, a);
  if (k.verdict != KrawczykVerdict::unique_zero) return std::nullopt;
  return Box3{{k.image[0].lo, k.image[1].lo, 0.0}, {k.image[0].hi, k.image[1].hi, 0.0}};
}

// Krawczyk on grad f1 - mu grad f2 = 0, f2 = 0 over (x ± r, mu ± r (1 + |mu|)).
std::optional<Box3> isolate_spatial(const ImplicitEquations& eq, Vec3 x, double mu, double r) {
  const Box3 box{{x.x - r, x.y - r, x.z - r}, {x.x + r, x.y + r, x.z + r}};
  const double rm = r * (1.0 + std::fabs(mu));
  const formula::Interval m{mu - rm, mu + rm};
  const ImplicitIntervalJet j = eq.interval_jet(box);
  const ImplicitIntervalJet jx = eq.interval_gradient({x, x});
  if (!j.smooth || !jx.smooth) return std::nullopt;
  IntervalMatrix<4> a{};
  IntervalVector<4> g{}, xb{};
  for (int r3 = 0; r3 < 3; ++r3) {
    g[r3] = iv::sub(jx.grad[0][r3], iv::mul(mu, jx.grad[1][r3]));
    xb[r3] = {box.lo[r3], box.hi[r3]};
    for (int c = 0; c < 3; ++c) a[r3][c] = iv::sub(j.hess[0][r3][c], iv::mul(m, j.hess[1][r3][c]));
    a[r3][3] = iv::neg(j.grad[1][r3]);
    a[3][r3] = j.grad[1][r3];
  }
  a[3][3] = {0.0, 0.0};
  g[3] = jx.f[1];
  xb[3] = m;
  const KrawczykResult<4> k = krawczyk<4>(xb, {x.x, x.y, x.z, mu}, g, a);
  if (k.verdict != KrawczykVerdict::unique_zero) return std::nullopt;
  return Box3{{k.image[0].lo, k.image[1].lo, k.image[2].lo}, {k.image[0].hi, k.image[1].hi, k.image[2].hi}};
}

}  // namespace

std::optional<Box3> isolate_singular_point(const ImplicitEquations& equations, Vec3 x, double radius) {
  double mu = 0.0;
  if (!equations.planar()) {
    const ImplicitJet j = equations.jet(x);
    const double g22 = norm2(j.grad[1]);
    if (!(g22 > 0.0)) return std::nullopt;
    mu = dot(j.grad[0], j.grad[1]) / g22;
  }
  for (double r = radius; r >= 1e-6 * radius; r *= 0.125) {
    const std::optional<Box3> b =
        equations.planar() ? isolate_planar(equations, x, r) : isolate_spatial(equations, x, mu, r);
    if (b) return b;
  }
  return std::nullopt;
}

}  // namespace footpoint::curve
