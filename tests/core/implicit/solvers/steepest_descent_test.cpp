// implicit/solvers/steepest_descent: [Curve] Algorithm 1, eq. (9), lands a point near the curve on it
// (it does not look for the foot point), and stops where the formulas stop being finite.
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "implicit/solvers/steepest_descent.hpp"
#include "implicit_fixtures.hpp"

using namespace footpoint;
using namespace footpoint::test;

TEST_CASE(
    "land_on_curve: from near the circle onto it, with eq. (9)'s first step as the trace's first entry") {
  const ImplicitEquations eq = circle();
  const Vec3 x0{1.2, 1.0, 1.3};
  std::vector<std::array<double, 3>> trace;
  curve::IterationControl c = curve::make_control(Options{}, curve::kPaperIterations, nullptr);
  c.trace = &trace;
  const curve::Landing l = curve::land_on_curve(eq, x0, c);
  REQUIRE(l.status == Status::converged);
  CHECK(std::fabs(norm2(l.x) - 4.0) <= 1e-14);
  CHECK(std::fabs(l.x.z - 1.0) <= 1e-15);
  CHECK(l.iterations == static_cast<int>(trace.size()));
  // Eq. (9) by hand: Y = X - f1 / |grad f1|^2 grad f1 with f1 = |X|^2 - 4, grad f1 = 2X; then
  // X1 = Y - (Y_z - 1) e_z.
  const double f1 = norm2(x0) - 4.0;
  Vec3 y = x0 - (f1 / norm2(2.0 * x0)) * (2.0 * x0);
  const Vec3 x1{y.x, y.y, 1.0};
  CHECK(norm(Vec3{trace[0][0], trace[0][1], trace[0][2]} - (x1 - x0)) <= 1e-15);
}

TEST_CASE("land_on_curve: a start already on the curve is taken as it is; NaN formulas stop it") {
  const curve::IterationControl c = curve::make_control(Options{}, curve::kPaperIterations, nullptr);
  const curve::Landing on = curve::land_on_curve(circle(), {kCircleRadius, 0.0, 1.0}, c);
  CHECK(on.status == Status::converged);
  CHECK(on.iterations == 0);
  // sqrt(x) is not defined left of 0.
  const curve::Landing nan = curve::land_on_curve(spatial_equations("sqrt(x)-1", "z"), {-1.0, 0.0, 0.0}, c);
  CHECK(nan.status == Status::non_finite);
}

TEST_CASE("steepest_descent: on the curve, but orthogonal only by chance: not_orthogonal") {
  const Box3 box{{-3, -3, -3}, {3, 3, 3}};
  const ProjectionResult r = curve::steepest_descent(circle(), box, {3.0, 1.0, 2.0}, Options{});
  CHECK(r.summary.status == Status::not_orthogonal);
  CHECK(r.summary.equation_residual[0] <= 1e-15);
  CHECK(r.summary.orthogonality[0] > 1e-3);
}
