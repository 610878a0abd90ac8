// Implicit curves written with a repeated factor ((x^2 + y^2 - 1)^2 = 0: every point singular,
// ∇f = 0 on the whole curve) are discovered, projected and certified through their square-free
// equations (formula::Program::square_free), against references computed independently: the
// circle's distance | |p| - 1 | in closed form, and Viviani's curve from its parametrisation
// (1 + cos t, sin t, 2 sin(t / 2)), t in [0, 4π), by a dense search and Newton in t. The papers'
// methods keep the equations as written.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "compiled/implicit_curve_geometry.hpp"
#include "implicit_fixtures.hpp"

using namespace footpoint;

namespace {

// The distance from p to Viviani's curve x^2 + y^2 + z^2 = 4, (x - 1)^2 + y^2 = 1.
double viviani_distance(const std::array<double, 3>& p) {
  auto point = [](double t) {
    return std::array<double, 3>{1 + std::cos(t), std::sin(t), 2 * std::sin(t / 2)};
  };
  auto phi = [&](double t) {
    const auto x = point(t);
    return std::pow(x[0] - p[0], 2) + std::pow(x[1] - p[1], 2) + std::pow(x[2] - p[2], 2);
  };
  const int n = 20000;
  double best_t = 0.0;
  for (int i = 0; i < n; ++i) {
    const double t = 4 * std::numbers::pi * i / n;
    if (phi(t) < phi(best_t)) best_t = t;
  }
  // Newton on φ'(t) = 0 with φ' = 2 (X - p)·X', φ'' = 2 (X'·X' + (X - p)·X'').
  double t = best_t;
  for (int k = 0; k < 30; ++k) {
    const auto x = point(t);
    const double d1[3] = {-std::sin(t), std::cos(t), std::cos(t / 2)};
    const double d2[3] = {-std::cos(t), -std::sin(t), -0.5 * std::sin(t / 2)};
    double g = 0.0, h = 0.0;
    for (int j = 0; j < 3; ++j) {
      g += (x[j] - p[j]) * d1[j];
      h += d1[j] * d1[j] + (x[j] - p[j]) * d2[j];
    }
    if (!(h > 0.0)) break;
    t -= g / h;
  }
  return std::sqrt(std::fmin(phi(t), phi(best_t)));
}

}  // namespace

TEST_CASE("a planar curve with a squared equation is the regular circle it is") {
  const auto g = test::implicit_curve({"-2*(x^2+y^2-1)^2"}, {{-2.0, 2.0}, {-2.0, 2.0}});
  const auto& curve = dynamic_cast<const ImplicitCurve&>(*g);
  CHECK_FALSE(curve.equations().program().same_tape(curve.written_equations().program()));
  CHECK(curve.discovery().stats.unproved_boxes == 0);
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  int certified = 0, n = 0;
  for (int i = 0; i < 300; ++i) {
    const std::array<double, 2> p{u(rng), u(rng)};
    const double exact = std::abs(std::hypot(p[0], p[1]) - 1.0);
    if (std::hypot(p[0], p[1]) < 0.05) continue;  // the centre: every point of the circle nearest
    ++n;
    const ProjectionResult r = g->project(p.data(), "auto", {}).value();
    CAPTURE(p[0]);
    CAPTURE(p[1]);
    CHECK(r.summary.converged());
    CHECK(std::abs(r.distance - exact) <= 1e-12 * std::fmax(1.0, exact));
    CHECK(r.summary.certificate.lower_bound <= exact * (1 + 1e-15));
    certified += r.summary.certificate.certified ? 1 : 0;
  }
  CHECK(certified >= n * 99 / 100);
  // The paper's planar iteration works on the equation as written (∇f = 0 on the curve): it runs
  // and says how it ended.
  const std::array<double, 2> q{1.5, 0.5};
  CHECK(g->project(q.data(), "tangent_foot", {}).has_value());
}

TEST_CASE("a spatial curve with a squared equation: Viviani's curve") {
  const auto g =
      test::implicit_curve({"(x^2+y^2+z^2-4)^2", "(x-1)^2+y^2-1"}, {{-3.0, 3.0}, {-3.0, 3.0}, {-3.0, 3.0}});
  std::mt19937_64 rng(19);
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  int certified = 0;
  const int n = 300;
  for (int i = 0; i < n; ++i) {
    const std::array<double, 3> p{u(rng), u(rng), u(rng)};
    const double exact = viviani_distance(p);
    const ProjectionResult r = g->project(p.data(), "auto", {}).value();
    CAPTURE(p[0]);
    CAPTURE(p[1]);
    CAPTURE(p[2]);
    CHECK(std::abs(r.distance - exact) <= 1e-12 * std::fmax(1.0, exact));
    CHECK(r.summary.certificate.lower_bound <= exact * (1 + 1e-15));
    certified += r.summary.certificate.certified ? 1 : 0;
  }
  CHECK(certified >= n * 99 / 100);
}
