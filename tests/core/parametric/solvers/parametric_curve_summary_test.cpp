// parametric/solvers/parametric_curve_summary: the residuals and location of a foot point on a
// parametric curve, the first-order conditions at the ends of the interval, and the local methods'
// start.
#include <doctest/doctest.h>

#include <cmath>

#include "formula/program.hpp"
#include "geometry/compile_budget.hpp"
#include "parametric/seeding/curve_parametric_samples.hpp"
#include "parametric/solvers/parametric_curve_summary.hpp"

using namespace footpoint;

namespace {

// The unit circle c(t) = (cos t, sin t) on [0, pi].
CurveFormulas unit_circle() {
  return CurveFormulas(formula::Program::compile({{"x", "cos(t)"}, {"y", "sin(t)"}}, {"t"}, {}));
}
const ParamInterval kHalf{0.0, M_PI};

}  // namespace

TEST_CASE(
    "parametric_result: inside the interval the orthogonality residual |<p - c, c'>| / (|p - c| |c'|)") {
  const ProjectionResult r = curve::parametric_result(unit_circle(), kHalf, {2, 1, 0}, 0.5, "newton");
  CHECK(r.dim == 2);
  CHECK(r.num_params == 1);
  CHECK(r.params[0] == 0.5);
  const Vec3 c{std::cos(0.5), std::sin(0.5), 0}, d1{-std::sin(0.5), std::cos(0.5), 0};
  const Vec3 d = Vec3{2, 1, 0} - c;
  CHECK(r.distance == doctest::Approx(norm(d)).epsilon(1e-15));
  CHECK(r.summary.orthogonality[0] == doctest::Approx(std::fabs(dot(d, d1)) / norm(d)).epsilon(1e-14));
  CHECK(r.summary.location == Location::interior);
  CHECK(!r.summary.on_boundary);
}

TEST_CASE("parametric_result: at an end only a violated first-order condition is a residual") {
  // p = (2, -1) below the half circle: at t = 0 the distance grows inwards (<p - c, c'> = -1 <= 0),
  // a minimum there; p = (-1, -2) at t = 0 would have the distance fall inwards.
  const ProjectionResult end = curve::parametric_result(unit_circle(), kHalf, {2, -1, 0}, 0.0, "auto");
  CHECK(end.summary.location == Location::endpoint);
  CHECK(end.summary.on_boundary);
  CHECK(end.summary.orthogonality[0] == 0.0);
  const ProjectionResult wrong = curve::parametric_result(unit_circle(), kHalf, {0, 2, 0}, 0.0, "auto");
  CHECK(wrong.summary.orthogonality[0] > 0.5);  // <p - c, c'> = 2: moving inwards approaches p
  const ProjectionResult top = curve::parametric_result(unit_circle(), kHalf, {-2, -1, 0}, M_PI, "auto");
  CHECK(top.summary.orthogonality[0] == 0.0);
}

TEST_CASE("finish_parametric_result: converged only inside the domain and orthogonal; max_distance") {
  const CurveFormulas f = unit_circle();
  const curve::IterationControl c = curve::make_control(Options{}, 10, nullptr);
  const Vec3 p{2.0 * std::cos(1.0), 2.0 * std::sin(1.0), 0.0};  // foot at t = 1
  CHECK(curve::finish_parametric_result(f, kHalf, p, 1.0, "newton", Status::converged, 4, 1e-17, c, {})
            .summary.status == Status::converged);
  CHECK(curve::finish_parametric_result(f, kHalf, p, 1.2, "newton", Status::converged, 4, 1e-17, c, {})
            .summary.status == Status::degenerate);
  const ParamInterval narrow{0.0, 0.5};
  CHECK(curve::finish_parametric_result(f, narrow, p, 1.0, "newton", Status::converged, 4, 1e-17, c, {})
            .summary.status == Status::outside_domain);
  curve::IterationControl near = c;
  near.max_distance = 0.5;
  CHECK(curve::finish_parametric_result(f, kHalf, p, 1.0, "newton", Status::converged, 4, 1e-17, near, {})
            .summary.status == Status::beyond_max_distance);
}

TEST_CASE("parametric_start: options.initial, else the nearest sample's t") {
  const CurveFormulas f = unit_circle();
  CompileBudget budget;
  const CurveSamples samples = sample_parametric_curve(f, kHalf, budget);
  const CurveSampleIndex index(samples);
  const double t =
      curve::parametric_start(kHalf, index, {2.0 * std::cos(2.0), 2.0 * std::sin(2.0), 0}, Options{});
  CHECK(std::fabs(t - 2.0) <= samples.spacing);
  Options o;
  o.initial = std::array<double, 3>{0.3, 0, 0};
  CHECK(curve::parametric_start(kHalf, index, {1, 1, 0}, o) == 0.3);
  const CurveSamples none;
  const CurveSampleIndex empty(none);
  CHECK(curve::parametric_start(kHalf, empty, {1, 1, 0}, Options{}) == 0.5 * M_PI);
}
