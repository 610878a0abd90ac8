// implicit/geometry/implicit_curve: the enclosures of the equations over boxes hold the point jets (values,
// gradients, Hessians) at points of the box; interval_gradient gives the same values and gradients
// without Hessians; planar curves carry f2 = z exactly; the tangent's enclosure and its
// derivatives hold those of T = ∇f1 × ∇f2 at points of the box.
#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "implicit/geometry/implicit_curve.hpp"
#include "implicit_fixtures.hpp"

using namespace footpoint;
using namespace footpoint::test;

namespace {

bool holds(const Interval& a, double v) { return a.lo <= v && v <= a.hi; }

// ∂T/∂x_k at x by central differences of the exact tangent (for a loose check only).
Vec3 tangent_derivative(const ImplicitEquations& eq, Vec3 x, int k) {
  const double h = 1e-6;
  Vec3 a = x, b = x;
  a[k] -= h;
  b[k] += h;
  return (eq.jet(b).tangent() - eq.jet(a).tangent()) / (2.0 * h);
}

}  // namespace

TEST_CASE("interval_jet and interval_gradient hold the point jets of a box's points") {
  const ImplicitEquations spatial = spatial_equations("x^2/9+y^2/16+z^2/9+4*x*y-1", "sin(x)*z+y^3");
  const ImplicitEquations planar = planar_equations("(x^2+y^2)^2-2*(x^2-y^2)");
  std::mt19937_64 rng(41);
  std::uniform_real_distribution<double> u(-2.0, 2.0), w(0.0, 0.5), t(0.0, 1.0);
  for (const ImplicitEquations* eq : {&spatial, &planar}) {
    for (int b = 0; b < 200; ++b) {
      Box3 box;
      for (int k = 0; k < (eq->planar() ? 2 : 3); ++k) {
        box.lo[k] = u(rng);
        box.hi[k] = box.lo[k] + w(rng);
      }
      const ImplicitIntervalJet j = eq->interval_jet(box);
      const ImplicitIntervalJet g = eq->interval_gradient(box);
      REQUIRE(j.smooth);
      CHECK(g.smooth);
      const IVec3 tangent = j.tangent();
      const IMat3 dt = j.tangent_derivatives();
      for (int s = 0; s < 10; ++s) {
        Vec3 x;
        for (int k = 0; k < 3; ++k) x[k] = box.lo[k] + t(rng) * (box.hi[k] - box.lo[k]);
        const ImplicitJet p = eq->jet(x);
        for (int i = 0; i < 2; ++i) {
          CHECK(holds(j.f[i], p.f[i]));
          CHECK(holds(g.f[i], p.f[i]));
          for (int r = 0; r < 3; ++r) {
            CHECK(holds(j.grad[i][r], p.grad[i][r]));
            CHECK(holds(g.grad[i][r], p.grad[i][r]));
            for (int c = 0; c < 3; ++c) CHECK(holds(j.hess[i][r][c], p.hess[i][r][c]));
          }
        }
        const Vec3 tp = p.tangent();
        for (int k = 0; k < 3; ++k) CHECK(holds(tangent[k], tp[k]));
        for (int k = 0; k < 3; ++k) {
          const Vec3 d = tangent_derivative(*eq, x, k);
          for (int c = 0; c < 3; ++c) {
            const Interval& e = dt[k][c];
            CHECK(e.lo - 1e-5 * (1.0 + std::fabs(d[c])) <= d[c]);
            CHECK(d[c] <= e.hi + 1e-5 * (1.0 + std::fabs(d[c])));
          }
        }
      }
    }
  }
  // Planar curves: f2 = z, its gradient e_z and Hessian 0, exactly.
  const ImplicitIntervalJet j = planar.interval_jet({{0.1, 0.2, 0.0}, {0.3, 0.4, 0.0}});
  CHECK(j.f[1].lo == 0.0);
  CHECK(j.f[1].hi == 0.0);
  CHECK(j.grad[1][2].lo == 1.0);
  CHECK(j.grad[1][0].hi == 0.0);
  CHECK(j.hess[1][2][2].hi == 0.0);
}

TEST_CASE("value_enclosure and may_vanish: the circle's cells") {
  const ImplicitEquations eq = planar_equations("x^2+y^2-1");
  CHECK(eq.may_vanish({{0.9, -0.1, 0.0}, {1.1, 0.1, 0.0}}));
  CHECK(!eq.may_vanish({{0.1, 0.1, 0.0}, {0.2, 0.2, 0.0}}));
  const auto f = eq.value_enclosure({{0.5, 0.5, 0.0}, {0.5, 0.5, 0.0}});
  CHECK(holds(f[0], -0.5));
  // A smooth formula that is not defined on part of the box has no derivative enclosures there.
  const ImplicitIntervalJet j =
      planar_equations("sqrt(x)-y").interval_jet({{-1.0, 0.0, 0.0}, {1.0, 1.0, 0.0}});
  CHECK(!j.lipschitz);
  CHECK(!j.smooth);
}
