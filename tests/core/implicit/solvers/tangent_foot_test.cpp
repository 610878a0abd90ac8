// implicit/solvers/tangent_foot: Hartmann's planar iteration of [Curve]'s introduction, eq. (2) onto
// the curve and eq. (4), the foot point of p on the tangent line, as the next start. On the unit
// circle eq. (2) is a radial Newton iteration (x - (|x|^2 - 1) / (2 |x|^2) x keeps the direction
// of x), so one round from the curve point y lands at q / |q| exactly; the nearest points are
// known in closed form (circle) or by brute force over a parametrisation (ellipse).
#include <doctest/doctest.h>

#include <cmath>

#include "closed_form_curves.hpp"
#include "implicit/solvers/tangent_foot.hpp"
#include "implicit_fixtures.hpp"

using namespace footpoint;
using namespace footpoint::test;

namespace tangent_foot_test {

const Box3 kBox{{-3, -3, 0}, {3, 3, 0}};

Vec3 sum_of(const std::vector<std::array<double, 3>>& trace) {
  Vec3 s{};
  for (const auto& t : trace) s += Vec3{t[0], t[1], t[2]};
  return s;
}

TEST_CASE("tangent_foot: one round on the unit circle lands at the tangent foot point's direction") {
  // From y = (1, 0) (exactly on x^2 + y^2 = 1, so eq. (2) takes no step), p = (0.9, 1.2):
  // grad f = (2, 0), eq. (4) gives Q = p - <p - y, grad f> / |grad f|^2 grad f = p + (0.1, 0) = (1, 1.2),
  // and eq. (2) takes Q radially onto the circle, to (1, 1.2) / |(1, 1.2)|. The march then ends at
  // p / |p| = (0.6, 0.8), at distance |p| - 1 = 0.5.
  Options o;
  o.initial = std::array<double, 3>{1.0, 0.0, 0.0};
  o.trace = true;
  const ProjectionResult r = curve::tangent_foot(planar_equations("x^2+y^2-1"), kBox, {0.9, 1.2, 0}, o);
  CHECK(r.summary.status == Status::converged);
  CHECK(r.summary.method == "tangent_foot");
  REQUIRE(!r.trace.empty());
  const Vec3 first = Vec3{1.0, 1.2, 0.0} / std::sqrt(2.44) - Vec3{1.0, 0.0, 0.0};
  CHECK(norm(Vec3{r.trace[0][0], r.trace[0][1], r.trace[0][2]} - first) <= 4e-16);
  // One increment per round, and they add up to the foot's displacement from the start.
  CHECK(r.summary.iterations == static_cast<int>(r.trace.size()));
  const Vec3 foot{r.foot[0], r.foot[1], r.foot[2]};
  CHECK(norm(foot - Vec3{0.6, 0.8, 0.0}) <= 1e-15);
  CHECK(norm(sum_of(r.trace) - (foot - Vec3{1.0, 0.0, 0.0})) <= 1e-14);
  CHECK(r.distance == doctest::Approx(0.5).epsilon(1e-14));
}

TEST_CASE("tangent_foot: beyond the centre of curvature the rounds overshoot and never settle") {
  // On the unit circle, from the curve point at angle theta, p = R (cos phi, sin phi): Q's component
  // along y is 1 and across it R sin(phi - theta), so the next angle error is
  // e' = e - atan(R sin e) ~ (1 - R) e: it converges for R < 2 and grows for R > 2 (p farther
  // outside than the radius of curvature). p = (3, 4), R = 5: the budget is spent, no foot claimed.
  Options o;
  o.max_iterations = 500;
  const ProjectionResult r = curve::tangent_foot(planar_equations("x^2+y^2-1"), kBox, {3, 4, 0}, o);
  CHECK(r.summary.status == Status::max_iterations);
  CHECK(r.summary.iterations == 500);
}

TEST_CASE("tangent_foot: on an ellipse from the paper's start, the brute-force nearest point") {
  // f = x^2/4 + y^2 - 1; p outside in the first quadrant, nearer to the curve than its radius of
  // curvature there (so that the rounds contract, as on the circle below), whose nearest point is
  // unique and is the foot point nearest the start p - (0.1, 0.1).
  const ImplicitEquations eq = planar_equations("x^2/4+y^2-1");
  for (const Vec3 p : {Vec3{1.6, 0.9, 0.0}, Vec3{0.5, 1.5, 0.0}, Vec3{2.2, 0.2, 0.0}}) {
    CAPTURE(p);
    const ProjectionResult r = curve::tangent_foot(eq, kBox, p, Options{});
    REQUIRE(r.summary.status == Status::converged);
    const CurveNearest ref = nearest_on(ellipse_curve(2.0, 1.0), p);
    const Vec3 x{r.foot[0], r.foot[1], r.foot[2]};
    CHECK(norm(x - ref.x) <= 1e-12);
    CHECK(r.distance == doctest::Approx(ref.distance).epsilon(1e-13));
    // The defining conditions by hand: f(x) = 0 and p - x parallel to grad f = (x/2, 2y).
    CHECK(std::fabs(x.x * x.x / 4 + x.y * x.y - 1) <= 4e-15);  // the rounding of this sum
    const Vec3 g{x.x / 2, 2 * x.y, 0.0};
    CHECK(std::fabs(cross(p - x, g).z) <= 1e-14 * norm(p - x) * norm(g));
  }
}

TEST_CASE("tangent_foot: options.initial decides which foot point; the farthest is one too") {
  // p = (0.5, 0) inside the unit circle: from (-1, 0) eq. (4) gives Q = (-1, 0) itself (p - y is
  // along grad f there), a foot point at the maximum of the distance, where the march stays.
  const ImplicitEquations eq = planar_equations("x^2+y^2-1");
  Options o;
  o.initial = std::array<double, 3>{-1.0, 0.0, 0.0};
  const ProjectionResult far = curve::tangent_foot(eq, kBox, {0.5, 0.0, 0.0}, o);
  CHECK(far.summary.status == Status::converged);
  CHECK(norm(Vec3{far.foot[0], far.foot[1], far.foot[2]} - Vec3{-1.0, 0.0, 0.0}) <= 1e-15);
  CHECK(far.distance == doctest::Approx(1.5).epsilon(1e-15));
  // From the paper's start (0.4, -0.1) the nearest, (1, 0).
  const ProjectionResult near = curve::tangent_foot(eq, kBox, {0.5, 0.0, 0.0}, Options{});
  CHECK(near.summary.status == Status::converged);
  CHECK(norm(Vec3{near.foot[0], near.foot[1], near.foot[2]} - Vec3{1.0, 0.0, 0.0}) <= 1e-14);
  CHECK(near.distance == doctest::Approx(0.5).epsilon(1e-14));
}

TEST_CASE("tangent_foot: a singular point has no tangent line; a foot outside the box is reported") {
  // x^2 - y^2 = 0 from p = (0.1, 0.1): the start p - (0.1, 0.1) = (0, 0) is on the curve, where
  // grad f = 0 and eq. (4) is undefined.
  const ProjectionResult s =
      curve::tangent_foot(planar_equations("x^2-y^2"), kBox, {0.1, 0.1, 0.0}, Options{});
  CHECK(s.summary.status == Status::degenerate);
  CHECK(norm(Vec3{s.foot[0], s.foot[1], s.foot[2]}) == 0.0);
  // The unit circle's foot (0.6, 0.8) of p = (0.9, 1.2) lies outside x <= 0.5.
  const Box3 left{{-3, -3, 0}, {0.5, 3, 0}};
  const ProjectionResult out =
      curve::tangent_foot(planar_equations("x^2+y^2-1"), left, {0.9, 1.2, 0}, Options{});
  CHECK(out.summary.status == Status::outside_domain);
  CHECK(norm(Vec3{out.foot[0], out.foot[1], out.foot[2]} - Vec3{0.6, 0.8, 0.0}) <= 1e-14);
}

}  // namespace tangent_foot_test
