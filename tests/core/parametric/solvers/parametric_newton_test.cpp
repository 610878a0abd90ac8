// parametric/solvers/parametric_newton and parametric_iteration: Newton on <c - p, c'> = 0, the shared
// loop's stopping rules, and the bracketed Newton of `auto`, against roots known in closed form or
// computed with mpmath (50 digits).
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "formula/program.hpp"
#include "geometry/compile_budget.hpp"
#include "parametric/seeding/curve_parametric_samples.hpp"
#include "parametric/solvers/parametric_iteration.hpp"
#include "parametric/solvers/parametric_newton.hpp"

using namespace footpoint;

namespace {

CurveFormulas formulas(const std::string& x, const std::string& y) {
  return CurveFormulas(formula::Program::compile({{"x", x}, {"y", y}}, {"t"}, {}));
}

}  // namespace

TEST_CASE("bracketed_newton: the parabola's foot point for p = (1, 0), root of 2t^3 + t - 1") {
  // phi'(t) = t - 1 + 2 t^3 for c = (t, t^2): its root by mpmath.findroot (50 digits).
  const double root = 0.58975451230145838427880174709607136;
  const curve::IterationControl c = curve::make_control(Options{}, 100, nullptr);
  for (double t0 : {0.0, 0.3, 1.0}) {
    int iterations = 0;
    double step = 0.0;
    const double t =
        curve::bracketed_newton(formulas("t", "t^2"), {1, 0, 0}, 0.0, 1.0, t0, c, iterations, step);
    CAPTURE(t0);
    CHECK(std::fabs(t - root) <= 2e-16);
    CHECK(iterations <= 10);
  }
}

TEST_CASE("bracketed_newton: where Newton's step leaves the bracket or g' < 0, it bisects and stays inside") {
  // The unit circle and p = (2, 0): g = <c - p, c'> = 2 sin t, the minimum at t = 0; from t0 = 1.9,
  // where g' = 2 cos t < 0, plain Newton would climb towards the maximum at pi.
  std::vector<std::array<double, 3>> trace;
  curve::IterationControl c = curve::make_control(Options{}, 100, nullptr);
  c.trace = &trace;
  int iterations = 0;
  double step = 0.0;
  const double t =
      curve::bracketed_newton(formulas("cos(t)", "sin(t)"), {2, 0, 0}, -1.0, 2.0, 1.9, c, iterations, step);
  CHECK(std::fabs(t) <= 1e-16);
  double x = 1.9;
  for (const auto& s : trace) {
    x += s[0];
    CHECK(x >= -1.0);
    CHECK(x <= 2.0);
  }
}

TEST_CASE(
    "parametric_newton: from the nearest sample or a start; outside_domain when it leaves [tmin, tmax]") {
  const CurveFormulas f = formulas("t", "t^2");
  const ParamInterval domain{-1.0, 2.0};
  CompileBudget budget;
  const CurveSamples samples = sample_parametric_curve(f, domain, budget);
  const CurveSampleIndex index(samples);
  const ProjectionResult r = curve::parametric_newton(f, domain, index, {1, 0, 0}, Options{});
  CHECK(r.summary.status == Status::converged);
  CHECK(std::fabs(r.params[0] - 0.58975451230145838) <= 2e-16);
  // From t0 = 5 on the domain [-1, 0.5] Newton converges to the root outside it.
  Options from5;
  from5.initial = std::array<double, 3>{5.0, 0.0, 0.0};
  const ParamInterval short_domain{-1.0, 0.5};
  const ProjectionResult out = curve::parametric_newton(f, short_domain, index, {1, 0, 0}, from5);
  CHECK(out.summary.status == Status::outside_domain);
  CHECK(std::fabs(out.params[0] - 0.58975451230145838) <= 2e-16);
}

TEST_CASE("iterate_parametric: failures, the budget, and what a step at the rounding floor concludes") {
  const CurveFormulas f = formulas("t", "t^2");
  const ParamInterval domain{-1.0, 2.0};
  CompileBudget budget;
  const CurveSamples samples = sample_parametric_curve(f, domain, budget);
  const CurveSampleIndex index(samples);
  Options o;
  o.initial = std::array<double, 3>{0.25, 0, 0};
  const Vec3 p{1, 0, 0};
  auto fails = [](const CurveJet&) { return curve::ParamStep{0.0, Status::degenerate}; };
  const ProjectionResult d =
      curve::iterate_parametric("m", f, domain, index, p, o, 10, curve::AtFloor::converged, fails);
  CHECK(d.summary.status == Status::degenerate);
  CHECK(d.summary.iterations == 0);
  CHECK(d.params[0] == 0.25);
  // A constant step of 1e-14 sits at the rounding floor (within 100 x 1e-15 and not shrinking):
  // a quadratic method has converged there, a linear one only if the point is orthogonal (it is
  // not: t = 0.25 is no foot point of p), and runs on to its budget.
  auto creep = [](const CurveJet&) { return curve::ParamStep{1e-14, Status::converged}; };
  const ProjectionResult q =
      curve::iterate_parametric("m", f, domain, index, p, o, 50, curve::AtFloor::converged, creep);
  CHECK(q.summary.iterations == 2);               // the first step has no predecessor to compare with
  CHECK(q.summary.status == Status::degenerate);  // settled, but not orthogonal: a stall
  const ProjectionResult l = curve::iterate_parametric("m", f, domain, index, p, o, 50,
                                                       curve::AtFloor::converged_if_orthogonal, creep);
  CHECK(l.summary.status == Status::max_iterations);
  CHECK(l.summary.iterations == 50);
  auto overflow = [](const CurveJet&) { return curve::ParamStep{1e308, Status::converged}; };
  Options big;
  big.initial = std::array<double, 3>{1e308, 0, 0};
  const ProjectionResult n =
      curve::iterate_parametric("m", f, domain, index, p, big, 10, curve::AtFloor::converged, overflow);
  CHECK(n.summary.status == Status::non_finite);
}
