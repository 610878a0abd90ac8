// Foot points on a curve cut by two nearly tangent surfaces (implicit/solvers/foot_refinement.hpp,
// the certificate's accurate values at the foot): two unit spheres whose centres are 1.9999
// apart meet at ~0.01 rad in a circle of radius ~0.01. Within 0.05 of it, `auto`'s distance
// against the closed form (the circle in the plane x = 1.9999 / 2, long double), to 1e-15 where
// double-precision residuals alone leave the foot ~1e-13 off; L <= exact; >= 99 % certified.
#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "implicit/solvers/foot_refinement.hpp"
#include "implicit_fixtures.hpp"

using namespace footpoint;

TEST_CASE("nearly tangent spheres: feet to the rounding of their coordinates, certified") {
  const auto g = test::implicit_curve({"x^2+y^2+z^2-1", "(x-1.9999)^2+y^2+z^2-1"},
                                      {{-1.5, 3.5}, {-1.5, 1.5}, {-1.5, 1.5}});
  const long double c0 = static_cast<long double>(1.9999) / 2;
  const long double radius = std::sqrt(1.0L - c0 * c0);
  std::mt19937_64 rng(41);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int n = 0, certified = 0;
  double worst = 0.0;
  for (int i = 0; i < 400; ++i) {
    const double t = 2 * 3.141592653589793 * u(rng), s = 0.05 * u(rng) * u(rng);
    const double dir[3] = {u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5};
    const double nd = std::sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
    const double p[3] = {static_cast<double>(c0) + s * dir[0] / nd,
                         static_cast<double>(radius) * std::cos(t) + s * dir[1] / nd,
                         static_cast<double>(radius) * std::sin(t) + s * dir[2] / nd};
    const long double rho = std::hypot(static_cast<long double>(p[1]), static_cast<long double>(p[2]));
    if (rho < 0.2L * radius) continue;  // near the circle's axis every point of it is nearly nearest
    ++n;
    CAPTURE(i);
    const double exact = static_cast<double>(std::hypot(p[0] - c0, rho - radius));
    const ProjectionResult r = g->project(p, "auto", {}).value();
    CHECK(r.summary.status == Status::converged);
    worst = std::fmax(worst, std::abs(r.distance - exact));
    CHECK(std::abs(r.distance - exact) <= 1e-15);
    CHECK(r.summary.certificate.lower_bound <= exact * (1.0 + 0x1p-50));
    certified += r.summary.certificate.certified ? 1 : 0;
  }
  MESSAGE("largest |d - exact| " << worst);
  CHECK(certified >= 0.99 * n);
}

TEST_CASE("refine_foot: only where the surfaces meet at a small angle") {
  // A sphere and a plane through its centre meet at a right angle: nothing to refine.
  const ImplicitEquations eq = test::spatial_equations("x^2+y^2+z^2-1", "z");
  Vec3 x{0.6, 0.8, 0.0};
  CHECK_FALSE(curve::refine_foot(eq, {1.2, 1.6, 0.0}, x));
  // Formulas that are not polynomials have no accurate values: nothing to refine either.
  const ImplicitEquations trig = test::spatial_equations("sin(x)^2+y^2+z^2-1", "(x-1.9999)^2+y^2+z^2-1");
  Vec3 y{0.99995, 0.01, 0.0};
  CHECK_FALSE(curve::refine_foot(trig, {0.99995, 0.02, 0.0}, y));
}
