// implicit/solvers/curve_descent, implicit `auto`'s fallback: a monotone descent of the distance along
// the circle of implicit_fixtures.hpp, from the far side of the circle to its nearest point.
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "implicit/solvers/curve_descent.hpp"
#include "implicit_fixtures.hpp"

using namespace footpoint;
using namespace footpoint::test;

namespace {

const Vec3 kP{3.0, 1.0, 2.0};

}  // namespace

TEST_CASE(
    "curve_descent: from near the farthest point down to the nearest, every step decreasing the distance") {
  const double a = std::atan2(kP.y, kP.x) + M_PI - 0.3;
  std::vector<std::array<double, 3>> trace;
  curve::IterationControl c = curve::make_control(Options{}, 200, nullptr);
  c.trace = &trace;
  const curve::LocalMinimum m = curve::curve_descent(circle(), kP, circle_point(a), 0.25, c);
  REQUIRE(m.converged);
  CHECK(norm(m.x - circle_foot(kP)) <= 1e-12);
  CHECK(m.second_variation > 0.0);
  // The trace holds the increments; replaying them from the start decreases |p - X| every time.
  Vec3 x = circle_point(a);
  double d = norm(kP - x);
  REQUIRE(!trace.empty());
  for (const auto& t : trace) {
    x += Vec3{t[0], t[1], t[2]};
    CHECK(norm(kP - x) <= d + 1e-15);
    d = norm(kP - x);
    CHECK(norm(Vec3{t[0], t[1], t[2]}) <= 0.25 * 1.01 + 1e-12);  // at most max_step along the arc
  }
}
