// implicit/solvers/lagrange_newton, the local solver of implicit `auto`, on a circle whose foot points
// are known in closed form: Newton on the Lagrange system converges to the stationary point next to
// its start (the nearest point, or the farthest with a negative second variation).
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "implicit/solvers/lagrange_newton.hpp"
#include "implicit_fixtures.hpp"

using namespace footpoint;
using namespace footpoint::test;

namespace {

const Vec3 kPoint{3.0, 1.0, 2.0};

curve::IterationControl control() { return curve::make_control(Options{}, 60, nullptr); }

}  // namespace

TEST_CASE("lagrange_newton: from a curve point near the nearest point, to it, quadratically") {
  const double a = std::atan2(kPoint.y, kPoint.x);
  for (double offset : {0.15, -0.1, 0.02}) {
    const curve::LocalMinimum m =
        curve::lagrange_newton(circle(), kPoint, circle_point(a + offset), 0.2, control());
    CAPTURE(offset);
    REQUIRE(m.converged);
    CHECK(norm(m.x - circle_foot(kPoint)) <= 1e-15 * 4);
    CHECK(m.iterations <= 7);
    // T^T (I + l1 F2 + l2 G2) T = 1 + <X - p, c> with c = (centre - X) / r^2: R / r, where R is p's
    // distance from the circle's axis; positive, a minimum.
    CHECK(m.second_variation ==
          doctest::Approx(std::hypot(kPoint.x, kPoint.y) / kCircleRadius).epsilon(1e-12));
  }
}

TEST_CASE(
    "lagrange_newton: next to the farthest point it finds that (a maximum: negative second variation)") {
  const double a = std::atan2(kPoint.y, kPoint.x) + M_PI;
  const curve::LocalMinimum m =
      curve::lagrange_newton(circle(), kPoint, circle_point(a + 0.05), 0.2, control());
  REQUIRE(m.converged);
  CHECK(norm(m.x + circle_foot(kPoint) - Vec3{0, 0, 2}) <= 1e-14);  // the antipode, (-fx, -fy, 1)
  CHECK(m.second_variation ==
        doctest::Approx(-std::hypot(kPoint.x, kPoint.y) / kCircleRadius).epsilon(1e-12));
}

TEST_CASE("lagrange_newton: steps longer than max_step are cut, and a solve that keeps cutting gives up") {
  const double a = std::atan2(kPoint.y, kPoint.x);
  const curve::LocalMinimum m =
      curve::lagrange_newton(circle(), kPoint, circle_point(a + 1.0), 1e-3, control());
  CHECK(!m.converged);
  CHECK(m.step <= 1e-3 * (1 + 1e-12));
}
