// parametric/solvers/parametric_curve_auto: `auto` on parametric curves, called with its own parts
// (samples, their k-d tree, the certificate's cells, the closure), against closed forms:
//  - the unit circle: from p != 0 the foot is p/|p| at distance ||p| - 1| (interior, the seam
//    t = 0 = 2π included: the circle closes smoothly); from its centre every point is nearest
//    (a continuum);
//  - the helix (cos t, sin t, t/5), t in [0, 4π]: from p = (R cos θ, R sin θ, θ/5) the distance
//    squared is R^2 + 1 - 2R cos(t - θ) + (t - θ)^2/25, least at t = θ only (both terms are), so
//    the foot is c(θ) at |R - 1|; from the axis point (0, 0, z) it is 1 + (t/5 - z)^2, foot
//    c(5z) at 1; from (2, 0, -1) it is 5 - 4 cos t + (t/5 + 1)^2 >= 1 + (t/5 + 1)^2 > 2 for t > 0,
//    the end c(0) at √2;
//  - the parabola (t, t^2) from (0, 2): t^4 - 3t^2 + 4 is least at t = ±√(3/2), two feet tied at
//    √7/2;
//  - the cubic (t, t^3 - t) on [-3/2, 3/2]: brute force over 300,001 uniform samples.
// Every answer's certificate has its lower bound <= the true distance and is certified.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "closed_form_answer.hpp"
#include "parametric/seeding/curve_parametric_samples.hpp"
#include "parametric/solvers/parametric_curve_auto.hpp"

using namespace footpoint;

namespace parametric_curve_auto_test {

constexpr double kPi = std::numbers::pi;

formula::Program program(const std::string& x, const std::string& y, const std::string& z) {
  std::vector<formula::NamedFormula> f = {{"x", x}, {"y", y}};
  if (!z.empty()) f.push_back({"z", z});
  return formula::Program::compile(f, {"t"}, {});
}

// What a compiled parametric curve holds, built from its parts as the compiler does.
struct Curve {
  CurveFormulas formulas;
  ParamInterval domain;
  CompileBudget budget;
  CurveSamples samples;
  CurveSampleIndex index;
  ParametricCurveCells cells;
  CurveClosure closure;
  Curve(const std::string& x, const std::string& y, const std::string& z, double t0, double t1)
      : formulas(program(x, y, z)),
        domain{t0, t1},
        samples(sample_parametric_curve(formulas, domain, budget)),
        index(samples),
        cells(formulas, domain, samples.params, budget),
        closure(detect_curve_closure(formulas, domain)) {}
  ProjectionResult project(Vec3 p, const Options& o = {}) const {
    return curve::parametric_curve_auto(formulas, domain, index, cells, closure, p, o);
  }
};

// The answer against the closed form, the curve evaluated at its parameter.
void check_answer(const Curve& c, const ProjectionResult& r, Vec3 p, double d, Vec3 foot, Location where) {
  test::check_closed_form_answer(r, p, d, foot, c.formulas.point(r.params[0]), where);
  CHECK(c.domain.contains(r.params[0]));
}

TEST_CASE(
    "parametric_curve_auto: the circle's foot is p/|p|, across the seam too; its centre sees a continuum") {
  const Curve circle("cos(t)", "sin(t)", "", 0, 2 * kPi);
  REQUIRE(circle.closure.smooth);
  for (const Vec3 p :
       {Vec3{3, 4, 0}, Vec3{0.3, 0.4, 0}, Vec3{-0.1, -0.05, 0}, Vec3{2, 0, 0}, Vec3{1.5, -1e-9, 0}}) {
    const double r = norm(p);
    const ProjectionResult a = circle.project(p);
    check_answer(circle, a, p, std::abs(r - 1), p / r, Location::interior);
    CHECK(a.summary.multiplicity.kind == Multiplicity::unique);
  }
  test::check_continuum(circle.project({0, 0, 0}), 1.0);
}

TEST_CASE("parametric_curve_auto: the helix, off the axis, on it, and past its end") {
  const Curve helix("cos(t)", "sin(t)", "0.2*t", 0, 4 * kPi);
  const auto c = [](double t) { return Vec3{std::cos(t), std::sin(t), 0.2 * t}; };
  for (const double theta : {0.7, 5.0, 9.1, 12.0}) {
    for (const double radius : {0.4, 3.0}) {
      const Vec3 p{radius * std::cos(theta), radius * std::sin(theta), 0.2 * theta};
      check_answer(helix, helix.project(p), p, std::abs(radius - 1), c(theta), Location::interior);
    }
  }
  const Vec3 axis{0, 0, 1.3};
  check_answer(helix, helix.project(axis), axis, 1.0, c(6.5), Location::interior);
  const Vec3 below{2, 0, -1};
  check_answer(helix, helix.project(below), below, std::sqrt(2.0), c(0.0), Location::endpoint);
  // and beyond the far end, by the same argument mirrored: from c(4π) + (1, 0, 1) the end c(4π)
  const Vec3 above = c(4 * kPi) + Vec3{1, 0, 1};
  check_answer(helix, helix.project(above), above, std::sqrt(2.0), c(4 * kPi), Location::endpoint);
}

TEST_CASE("parametric_curve_auto: the parabola's two tied feet") {
  const Curve parabola("t", "t^2", "", -2, 2);
  const double t = std::sqrt(1.5);
  const Vec3 p{0, 2, 0};
  Options all;
  all.all_minima = true;
  const ProjectionResult r = parabola.project(p, all);
  REQUIRE(r.summary.status == Status::converged);
  CHECK(r.distance == doctest::Approx(std::sqrt(7.0) / 2).epsilon(1e-12));
  CHECK(std::abs(std::abs(r.params[0]) - t) <= 1e-9);
  CHECK(r.summary.multiplicity.kind == Multiplicity::tied);
  CHECK(r.summary.multiplicity.count == 2);
  CHECK(r.summary.certificate.certified);
  CHECK(r.summary.certificate.lower_bound <= std::sqrt(7.0) / 2 * (1.0 + 0x1p-51));
  // all_minima: both feet, nothing else (t = 0 is a local maximum of the distance)
  REQUIRE(r.minima.size() == 2);
  for (const Minimum& m : r.minima) {
    CHECK(m.distance == doctest::Approx(std::sqrt(7.0) / 2).epsilon(1e-12));
    CHECK(std::abs(std::abs(m.foot[0]) - t) <= 1e-9);
  }
  CHECK(r.minima[0].foot[0] * r.minima[1].foot[0] < 0.0);
}

TEST_CASE("parametric_curve_auto: the cubic against brute force") {
  const Curve cubic("t", "t^3-t", "", -1.5, 1.5);
  // 300,001 samples, Δt = 1e-5: the sampled minimum is above the true one by at most
  // ½ max|d''| (Δt/2)^2 <= ½ (|c'|^2 + |c - p| |c''|) / d (Δt/2)^2 < 2e-8 for d >= 0.1 here
  // (|c'|^2 <= 34, |c''| <= 9, |c - p| <= 10)
  for (const Vec3 p :
       {Vec3{0.2, 0.9, 0}, Vec3{-0.4, -1.2, 0}, Vec3{1.3, 0.2, 0}, Vec3{0, 3, 0}, Vec3{-2, 0.5, 0}}) {
    CAPTURE(p.x);
    CAPTURE(p.y);
    double best = std::numeric_limits<double>::infinity();
    for (int i = 0; i <= 300000; ++i) {
      const double t = -1.5 + 3.0 * i / 300000;
      best = std::min(best, std::hypot(t - p.x, t * t * t - t - p.y));
    }
    REQUIRE(best >= 0.1);
    const ProjectionResult r = cubic.project(p);
    REQUIRE(r.summary.status == Status::converged);
    CHECK(r.distance <= best + 1e-13);
    CHECK(r.distance >= best - 2e-8);
    const double t = r.params[0];
    CHECK(norm(test::foot_vec(r) - Vec3{t, t * t * t - t, 0}) <= 1e-15);
    CHECK(std::abs(norm(p - test::foot_vec(r)) - r.distance) <= 1e-15);
    CHECK(r.summary.certificate.certified);
    CHECK(r.summary.certificate.lower_bound <= best);
  }
}

TEST_CASE("parametric_curve_auto: a point on the curve, max_distance, and certify off") {
  const Curve circle("cos(t)", "sin(t)", "", 0, 2 * kPi);
  // on the curve: distance 0 to rounding, certified within the absolute gap
  const Vec3 on{0.6, 0.8, 0};
  const ProjectionResult r = circle.project(on);
  REQUIRE(r.summary.status == Status::converged);
  CHECK(r.distance <= 1e-15);
  CHECK(r.summary.certificate.certified);
  // max_distance and certify off, from (3, 4) at 4
  test::check_max_distance_and_certify([&](const Options& o) { return circle.project({3, 4, 0}, o); }, 4.0);
}

}  // namespace parametric_curve_auto_test
