// parametric/solvers/curvature_circle: Hu and Wallner's second-order method ([GSA] Section 3, eqs.
// (21)-(22)). On a circle the step is sin(a - t) in closed form (a the angle of p): the error maps
// to e - sin e, cubic convergence to the foot at the parameter of p's angle; on a straight line (curvature 0)
// the step is the first-order one, exact for a line; a foot beyond the domain is outside_domain. Feet in
// closed form throughout.
#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include "formula/program.hpp"
#include "geometry/compile_budget.hpp"
#include "parametric/seeding/curve_parametric_samples.hpp"
#include "parametric/solvers/curvature_circle.hpp"

using namespace footpoint;

namespace {

CurveFormulas curvature_circle_curve(const std::string& x, const std::string& y) {
  return CurveFormulas(formula::Program::compile({{"x", x}, {"y", y}}, {"t"}, {}));
}

Options curvature_circle_start(double t) {
  Options o;
  o.initial = std::array<double, 3>{t, 0.0, 0.0};
  o.trace = true;
  return o;
}

}  // namespace

TEST_CASE("curvature circle: on a circle each step is sin(a - t), cubic convergence to the foot") {
  const CurveFormulas circle = curvature_circle_curve("2*cos(t)", "2*sin(t)");
  const ParamInterval domain{-3.0, 3.0};
  CompileBudget sampling_budget;
  const CurveSamples samples = sample_parametric_curve(circle, domain, sampling_budget);
  const CurveSampleIndex index(samples);
  for (const double a : {-2.5, -0.4, 0.3, 1.0, 2.2}) {
    for (const double radius : {0.5, 3.0, 7.0}) {
      const Vec3 p{radius * std::cos(a), radius * std::sin(a), 0.0};
      const ProjectionResult r =
          curve::curvature_circle(circle, domain, index, p, curvature_circle_start(a + 0.4));
      CHECK(r.summary.status == Status::converged);
      CHECK(r.params[0] == doctest::Approx(a).epsilon(1e-13));
      CHECK(r.distance == doctest::Approx(std::fabs(radius - 2.0)).epsilon(1e-13));
      CHECK(r.foot[0] == doctest::Approx(2 * std::cos(a)).epsilon(1e-13));
      CHECK(r.foot[1] == doctest::Approx(2 * std::sin(a)).epsilon(1e-13));
      // The step is exact in closed form here: with q the foot on the circle at angle a, eq. (22)
      // gives dt = det(q - c, c'') / det(c', c'') = R^2 sin(a - t) / R^2, so the parameter's error
      // e = a - t maps to e - sin e ≈ e^3 / 6: cubic convergence, whatever p's distance.
      double error = -0.4;
      for (std::size_t k = 0; k < r.trace.size() && std::fabs(error) > 1e-5; ++k) {
        CHECK(r.trace[k][0] == doctest::Approx(std::sin(error)).epsilon(1e-9));
        error -= std::sin(error);
      }
      CHECK(r.trace.size() >= 3);  // 0.4 -> 1.1e-2 -> 2.0e-7 -> 1e-21, then a step at rounding level
      CHECK(r.summary.iterations <= 6);
    }
  }
}

TEST_CASE("curvature circle: a straight line takes the first-order step, exact in one") {
  // c = (t, 2t): the foot of p is at t = <p, (1, 2)> / 5; p = (3, 1) gives t = 1, foot (1, 2),
  // distance |(2, -1)| = √5.
  const CurveFormulas line = curvature_circle_curve("t", "2*t");
  const ParamInterval domain{-4.0, 4.0};
  CompileBudget sampling_budget;
  const CurveSamples samples = sample_parametric_curve(line, domain, sampling_budget);
  const CurveSampleIndex index(samples);
  const ProjectionResult r =
      curve::curvature_circle(line, domain, index, {3, 1, 0}, curvature_circle_start(-3.0));
  CHECK(r.summary.status == Status::converged);
  CHECK(r.params[0] == doctest::Approx(1.0).epsilon(1e-14));
  CHECK(r.distance == doctest::Approx(std::sqrt(5.0)).epsilon(1e-14));
  REQUIRE(!r.trace.empty());
  CHECK(r.trace[0][0] == doctest::Approx(4.0).epsilon(1e-15));
  for (std::size_t k = 1; k < r.trace.size(); ++k) CHECK(std::fabs(r.trace[k][0]) <= 1e-15);
}

TEST_CASE("curvature circle: a foot beyond the domain is outside_domain") {
  // The unit circle over [0, 1]; p at angle 2 has its foot at t = 2, beyond tmax.
  const CurveFormulas circle = curvature_circle_curve("cos(t)", "sin(t)");
  const ParamInterval domain{0.0, 1.0};
  CompileBudget sampling_budget;
  const CurveSamples samples = sample_parametric_curve(circle, domain, sampling_budget);
  const CurveSampleIndex index(samples);
  const Vec3 p{3 * std::cos(2.0), 3 * std::sin(2.0), 0.0};
  const ProjectionResult r = curve::curvature_circle(circle, domain, index, p, curvature_circle_start(0.9));
  CHECK(r.summary.status == Status::outside_domain);
  CHECK(r.params[0] == doctest::Approx(2.0).epsilon(1e-12));
  // Without a start it begins at the nearest sample (t = 1 here) and ends the same way.
  const ProjectionResult from_sample = curve::curvature_circle(circle, domain, index, p, Options{});
  CHECK(from_sample.summary.status == Status::outside_domain);
}
