// implicit/solvers/complete_projection: [Curve] Algorithm 4, Algorithm 1, five rounds of Algorithm 2
// (the foot point Q, eqs. (11)-(13)) and Algorithm 1, then Algorithm 3. On a line as two orthogonal
// planes every step is worked out by hand; on a circle (sphere ∩ plane), a plane curve, Algorithm 3's
// correction is undetermined at the foot point; on Viviani's curve the brute-force nearest point is the
// reference.
#include <doctest/doctest.h>

#include <cmath>

#include "closed_form_curves.hpp"
#include "implicit/solvers/complete_projection.hpp"
#include "implicit_fixtures.hpp"

using namespace footpoint;
using namespace footpoint::test;

namespace complete_projection_test {

const Box3 kBox{{-4, -4, -4}, {4, 4, 4}};

Vec3 foot_of(const ProjectionResult& r) { return {r.foot[0], r.foot[1], r.foot[2]}; }
Vec3 increment(const std::array<double, 3>& t) { return {t[0], t[1], t[2]}; }

TEST_CASE("complete_projection: the steps of Algorithm 4 on a line as two planes, by hand") {
  // x = y, z = 1 and p = (3, 1, 2), foot (2, 2, 1). Step 1, Algorithm 1 from X0 = (2.9, 0.9, 1.9):
  // Newton onto x = y, then onto z = 1 (orthogonal planes): P_I = (1.9, 1.9, 1).
  // Step 2, Algorithm 2: T = (1, -1, 0) x (0, 0, 1) = (-1, -1, 0), t0 = <p - P_I, T> / |T|^2 = -0.1,
  // Q0 = P_I + t0 T = (2, 2, 1), d1 = |P_I Q0| / 2 = 0.1 / sqrt 2, d2 = |Q0 p| = sqrt 3,
  // Q = Q0 + d1 / d2 (p - Q0). Step 3, Algorithm 1 from Q: back to Q0, an increment
  // -(d1 / d2) (1, -1, 1). The later rounds start on the foot (d1 = 0) and Algorithm 3 stays there.
  const ImplicitEquations eq = spatial_equations("x-y", "z-1");
  const Vec3 p{3, 1, 2};
  Options o;
  o.trace = true;
  const ProjectionResult r = curve::complete_projection(eq, kBox, p, o);
  CHECK(r.summary.status == Status::converged);
  CHECK(r.summary.method == "complete");
  CHECK(norm(foot_of(r) - Vec3{2, 2, 1}) <= 1e-15);
  CHECK(r.distance == doctest::Approx(std::sqrt(3.0)).epsilon(1e-15));
  REQUIRE(r.trace.size() >= 2);
  CHECK(norm(increment(r.trace[0]) - Vec3{-1.0, 1.0, -0.9}) <= 1e-15);
  const double d = (0.1 / std::sqrt(2.0)) / std::sqrt(3.0);
  CHECK(norm(increment(r.trace[1]) + d * Vec3{1.0, -1.0, 1.0}) <= 1e-15);
  for (std::size_t i = 2; i < r.trace.size(); ++i) CHECK(norm(increment(r.trace[i])) <= 1e-15);
}

TEST_CASE("complete_projection: on a plane circle Algorithm 3 cannot settle and no foot is claimed") {
  // {x^2 + y^2 + z^2 = 4} ∩ {z = 1}, whose nearest point of p is (sqrt 3 (px, py) / r, 1),
  // r = |(px, py)|. The curve lies in a plane, so T x c is the plane's normal and the third row of
  // eq. (18), <(T x c) x DV, dV> = 0, is the curve's normal in the plane, a combination of grad f1
  // and grad f2, once DV is tangent at the foot: the correction is undetermined there and Step 4
  // wanders near the foot until its budget is spent. The result says so (max_iterations), near the
  // closed-form foot that the five rounds of Steps 2-3 brought it to.
  Options o;
  o.max_iterations = 400;
  for (const Vec3 p : {Vec3{3.0, 1.0, 2.0}, Vec3{0.5, 0.2, -1.0}}) {
    CAPTURE(p);
    const ProjectionResult r = curve::complete_projection(circle(), kBox, p, o);
    CHECK(r.summary.status == Status::max_iterations);
    CHECK(norm(foot_of(r) - circle_foot(p)) < 0.1);
    CHECK(r.distance >= std::hypot(std::hypot(p.x, p.y) - kCircleRadius, p.z - 1.0));
  }
}

TEST_CASE("complete_projection: Viviani's curve, the brute-force nearest point on both lobes") {
  // 0.3 off the curve along the cylinder's radius at t = 2 (z > 0) and t = 9 (z < 0), away from the
  // double point (2, 0, 0).
  const ImplicitEquations eq = spatial_equations("x^2+y^2+z^2-4", "(x-1)^2+y^2-1");
  const ParamCurve viviani = viviani_curve();
  for (const double t : {2.0, 9.0}) {
    CAPTURE(t);
    const Vec3 p = viviani.c(t) + 0.3 * Vec3{std::cos(t), std::sin(t), 0.0};
    const ProjectionResult r = curve::complete_projection(eq, kBox, p, Options{});
    REQUIRE(r.summary.status == Status::converged);
    const CurveNearest ref = nearest_on(viviani, p);
    CHECK(norm(foot_of(r) - ref.x) <= 1e-12);
    CHECK(r.distance == doctest::Approx(ref.distance).epsilon(1e-13));
  }
}

TEST_CASE("complete_projection: Algorithm 2 at the double point of Viviani's curve: degenerate") {
  // From (2, 0, 0), on the curve, grad f1 = (4, 0, 0) and grad f2 = (2, 0, 0) are parallel: T = 0,
  // the tangent line of eq. (10) is undefined.
  const ImplicitEquations eq = spatial_equations("x^2+y^2+z^2-4", "(x-1)^2+y^2-1");
  Options o;
  o.initial = std::array<double, 3>{2.0, 0.0, 0.0};
  const ProjectionResult r = curve::complete_projection(eq, kBox, {3.0, 0.5, 0.5}, o);
  CHECK(r.summary.status == Status::degenerate);
  CHECK(norm(foot_of(r) - Vec3{2, 0, 0}) == 0.0);
}

}  // namespace complete_projection_test
