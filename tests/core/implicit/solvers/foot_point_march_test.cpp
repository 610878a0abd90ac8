// implicit/solvers/foot_point_march: [Curve] Algorithm 2's foot point Q in closed form, and the march
// that alternates it with Algorithm 1, on the circle of implicit_fixtures.hpp.
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "implicit/solvers/foot_point_march.hpp"
#include "implicit_fixtures.hpp"

using namespace footpoint;
using namespace footpoint::test;

TEST_CASE("foot_point: eqs. (11)-(13) at the circle's point (sqrt 3, 0, 1)") {
  // The tangent line there is x = sqrt 3, z = 1; P = (3, 2, 1) projects onto it at Q0 = (sqrt 3, 2, 1),
  // d1 = |P_I Q0| / 2 = 1, d2 = |Q0 P| = 3 - sqrt 3, Q = Q0 + (d1 / d2) (P - Q0) = (sqrt 3 + 1, 2, 1).
  Vec3 q;
  REQUIRE(curve::foot_point(circle(), {3, 2, 1}, {kCircleRadius, 0, 1}, q));
  CHECK(norm(q - Vec3{kCircleRadius + 1.0, 2.0, 1.0}) <= 1e-15 * 4);
  // P on the tangent line: Q = Q0.
  REQUIRE(curve::foot_point(circle(), {kCircleRadius, 0.5, 1}, {kCircleRadius, 0, 1}, q));
  CHECK(norm(q - Vec3{kCircleRadius, 0.5, 1.0}) <= 1e-15);
  // A singular point has no tangent line.
  CHECK(!curve::foot_point(spatial_equations("x^2+y^2+z^2-4", "(x-1)^2+y^2-1"), {3, 0, 0}, {2, 0, 0}, q));
}

TEST_CASE("march_on_curve: rounds of a foot point and Algorithm 1 until the curve point stops moving") {
  const ImplicitEquations eq = circle();
  const Vec3 p{3.0, 1.0, 2.0};
  std::vector<std::array<double, 3>> trace;
  curve::IterationControl control = curve::make_control(Options{}, 10000, nullptr);
  control.trace = &trace;
  curve::IterationControl landing = control;
  landing.trace = nullptr;
  const curve::Landing start{circle_point(0.9), 5, 0.0, Status::converged};
  // The foot point of p on the tangent line (the planar iteration's eq. (4) in space): on a circle
  // the march converges linearly to the nearest point.
  auto on_tangent = [&](Vec3 x, Vec3& q) {
    const Vec3 t = eq.jet(x).tangent();
    q = x + (dot(p - x, t) / norm2(t)) * t;
    return true;
  };
  const curve::Landing end = curve::march_on_curve(eq, p, start, control, landing, on_tangent);
  CHECK(end.status == Status::converged);
  CHECK(norm(end.x - circle_foot(p)) <= 1e-14);
  CHECK(end.iterations == static_cast<int>(trace.size()));
  // A failed landing before the march is passed on, with no rounds.
  const curve::Landing failed{circle_point(0.9), 7, 0.5, Status::non_finite};
  const curve::Landing same = curve::march_on_curve(eq, p, failed, control, landing, on_tangent);
  CHECK(same.status == Status::non_finite);
  CHECK(same.iterations == 0);
  // A foot point that cannot be computed: degenerate, at the last curve point.
  const curve::Landing none =
      curve::march_on_curve(eq, p, start, control, landing, [](Vec3, Vec3&) { return false; });
  CHECK(none.status == Status::degenerate);
  CHECK(norm(none.x - start.x) == 0.0);
}
