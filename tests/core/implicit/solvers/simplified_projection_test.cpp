// implicit/solvers/simplified_projection: [Curve] Algorithm 5, Algorithm 1 then eq. (20). From a point X
// on the curve (f1 = f2 = 0) the first two rows of eq. (20) do nothing and the third is one Newton
// step on F = <T, P - X>, T = grad f1 x grad f2 (eq. (7)): X1 = X - F / |grad F|^2 grad F, the point
// nearest X where the linearisation F(X) + <grad F(X), X1 - X> vanishes. F and grad F are worked out
// by hand below; the step is invariant under a constant scaling of F, so under T's sign or scale.
// Full runs are checked against closed forms (circle, ellipse, a line as two planes) and a
// brute-force nearest point on Viviani's curve.
#include <doctest/doctest.h>

#include <cmath>

#include "closed_form_curves.hpp"
#include "implicit/solvers/simplified_projection.hpp"
#include "implicit_fixtures.hpp"

using namespace footpoint;
using namespace footpoint::test;

namespace simplified_projection_test {

const Box3 kBox{{-4, -4, -4}, {4, 4, 4}};

Vec3 foot_of(const ProjectionResult& r) { return {r.foot[0], r.foot[1], r.foot[2]}; }
Vec3 increment(const std::array<double, 3>& t) { return {t[0], t[1], t[2]}; }

// One eq. (20) step from `x0` on the curve, alone: Algorithm 1 takes no step there, one iteration.
ProjectionResult one_step(const ImplicitEquations& eq, Vec3 p, Vec3 x0) {
  Options o;
  o.initial = std::array<double, 3>{x0.x, x0.y, x0.z};
  o.trace = true;
  o.max_iterations = 1;
  return curve::simplified_projection(eq, kBox, p, o);
}

TEST_CASE("simplified_projection: one eq. (20) step on the unit circle projects X onto the plane through p") {
  // Sphere x^2 + y^2 + z^2 = 1 and plane z = 0: T = 2 (y, -x, 0) and F = 2 (px y - py x), linear, so
  // the step is the orthogonal projection of X onto the plane F = 0 (the z-axis and p): from
  // X = (1, 0, 0) and p = (3, 4, 2), X1 = <X, u> u with u = (3, 4, 0) / 5, = (9, 12, 0) / 25.
  const ImplicitEquations eq = spatial_equations("x^2+y^2+z^2-1", "z");
  const Vec3 p{3, 4, 2};
  const ProjectionResult one = one_step(eq, p, {1, 0, 0});
  CHECK(one.summary.status == Status::max_iterations);
  REQUIRE(one.trace.size() == 1);
  CHECK(norm(increment(one.trace[0]) - Vec3{-16.0 / 25, 12.0 / 25, 0.0}) <= 1e-15);
  CHECK(norm(foot_of(one) - Vec3{9.0 / 25, 12.0 / 25, 0.0}) <= 1e-15);
  // Iterated to the end: the nearest point p / |p| in the plane, at distance sqrt((5 - 1)^2 + 2^2).
  Options o;
  o.initial = std::array<double, 3>{1, 0, 0};
  const ProjectionResult r = curve::simplified_projection(eq, kBox, p, o);
  CHECK(r.summary.status == Status::converged);
  CHECK(r.summary.method == "simplified");
  CHECK(norm(foot_of(r) - Vec3{0.6, 0.8, 0.0}) <= 1e-15);
  CHECK(r.distance == doctest::Approx(std::sqrt(20.0)).epsilon(1e-15));
}

TEST_CASE("simplified_projection: one eq. (20) step on an ellipse solves the linearised orthogonality") {
  // f1 = x^2/4 + y^2 - 1, f2 = z: T = (x/2, 2y, 0) x (0, 0, 1) = (2y, -x/2, 0),
  // F = 2y (px - x) - x/2 (py - y), grad F = (-2y - (py - y)/2, 2 (px - x) + x/2, 0).
  // At X = (2, 0, 0), p = (3, 2, 0.5): F = -2, grad F = (-1, 3, 0), X1 = X + 0.2 (-1, 3, 0) = (1.8, 0.6, 0).
  const ImplicitEquations eq = spatial_equations("x^2/4+y^2-1", "z");
  const Vec3 p{3, 2, 0.5}, x0{2, 0, 0};
  const auto F = [&](Vec3 x) { return 2 * x.y * (p.x - x.x) - x.x / 2 * (p.y - x.y); };
  const auto grad_F = [&](Vec3 x) {
    return Vec3{-2 * x.y - (p.y - x.y) / 2, 2 * (p.x - x.x) + x.x / 2, 0.0};
  };
  const ProjectionResult one = one_step(eq, p, x0);
  REQUIRE(one.trace.size() == 1);
  const Vec3 x1 = foot_of(one);
  CHECK(norm(x1 - Vec3{1.8, 0.6, 0.0}) <= 1e-15);
  CHECK(std::fabs(F(x0) + dot(grad_F(x0), x1 - x0)) <= 1e-15);  // the linearised condition
  CHECK(norm(cross(x1 - x0, grad_F(x0))) <= 1e-15);             // a step along grad F
  // From the paper's start, the nearest point: by brute force over (2 cos t, sin t, 0).
  const ProjectionResult r = curve::simplified_projection(eq, kBox, p, Options{});
  REQUIRE(r.summary.status == Status::converged);
  const CurveNearest ref = nearest_on(ellipse_curve(2.0, 1.0), p);
  CHECK(norm(foot_of(r) - ref.x) <= 1e-12);
  CHECK(r.distance == doctest::Approx(ref.distance).epsilon(1e-13));
  CHECK(std::fabs(F(foot_of(r))) <= 1e-13);
}

TEST_CASE("simplified_projection: a line as two planes, F linear: one eq. (20) step lands on the foot") {
  // x = y, z = 1: Algorithm 1 projects onto the line in one step (the planes are orthogonal), eq. (20)
  // moves along grad F = (1, 1, 0), along the line, onto the foot ((px + py) / 2, (px + py) / 2, 1).
  const ImplicitEquations eq = spatial_equations("x-y", "z-1");
  const Vec3 p{3, 1, 2};
  Options o;
  o.trace = true;
  const ProjectionResult r = curve::simplified_projection(eq, kBox, p, o);
  CHECK(r.summary.status == Status::converged);
  CHECK(norm(foot_of(r) - Vec3{2, 2, 1}) <= 1e-15);
  CHECK(r.distance == doctest::Approx(std::sqrt(3.0)).epsilon(1e-15));
  // Algorithm 1's step from (2.9, 0.9, 1.9) to (1.9, 1.9, 1), eq. (20)'s to (2, 2, 1), then steps of
  // rounding size only.
  REQUIRE(r.trace.size() >= 2);
  CHECK(norm(increment(r.trace[0]) - Vec3{-1.0, 1.0, -0.9}) <= 1e-15);
  CHECK(norm(increment(r.trace[1]) - Vec3{0.1, 0.1, 0.0}) <= 1e-15);
  for (std::size_t i = 2; i < r.trace.size(); ++i) CHECK(norm(increment(r.trace[i])) <= 1e-15);
  // The same foot outside a box that stops at x = 1: outside_domain.
  const Box3 small{{-1, -1, -4}, {1, 1, 4}};
  CHECK(curve::simplified_projection(eq, small, p, Options{}).summary.status == Status::outside_domain);
}

TEST_CASE("simplified_projection: Viviani's curve, the brute-force nearest point") {
  // Points 0.3 off the curve at t = 2 and t = 5 (away from the double point (2, 0, 0)), off along
  // the cylinder's radius: the nearest point is near that curve point, and the paper's start,
  // p - (0.1, 0.1, 0.1), is near enough for Algorithm 5 to reach it.
  const ImplicitEquations eq = spatial_equations("x^2+y^2+z^2-4", "(x-1)^2+y^2-1");
  const ParamCurve viviani = viviani_curve();
  for (const double t : {2.0, 5.0}) {
    CAPTURE(t);
    const Vec3 p = viviani.c(t) + 0.3 * Vec3{std::cos(t), std::sin(t), 0.0};
    const ProjectionResult r = curve::simplified_projection(eq, kBox, p, Options{});
    REQUIRE(r.summary.status == Status::converged);
    const CurveNearest ref = nearest_on(viviani, p);
    CHECK(norm(foot_of(r) - ref.x) <= 1e-12);
    CHECK(r.distance == doctest::Approx(ref.distance).epsilon(1e-13));
  }
}

}  // namespace simplified_projection_test
