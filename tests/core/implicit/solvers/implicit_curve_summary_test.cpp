// implicit/solvers/implicit_curve_summary: the residuals and location of a foot point on an implicit
// curve, at an interior point, where the curve crosses a face of the box, and at a singular point.
#include <doctest/doctest.h>

#include <cmath>

#include "implicit/solvers/implicit_curve_summary.hpp"
#include "implicit_fixtures.hpp"

using namespace footpoint;
using namespace footpoint::test;

TEST_CASE("fill_implicit_residuals: equation residuals |f_i| / |grad f_i|, orthogonality of eq. (7)") {
  const ImplicitEquations eq = circle();
  const Box3 box{{-3, -3, -3}, {3, 3, 3}};
  const Vec3 p{3, 1, 2};
  Summary s;
  const Vec3 off{1.0, 1.0, 1.25};  // |X|^2 - 4 = -0.4375, |grad f1| = 2 |X|; f2 = 0.25
  curve::fill_implicit_residuals(eq, box, p, off, s);
  CHECK(s.equation_residual[0] == doctest::Approx(0.4375 / (2.0 * norm(off))).epsilon(1e-15));
  CHECK(s.equation_residual[1] == 0.25);
  // At a circle point: F = <T, p - X> relative to |T| |p - X|, T = (2y, -2x, 0).
  const Vec3 x = circle_point(0.4);
  curve::fill_implicit_residuals(eq, box, p, x, s);
  const Vec3 t{2 * x.y, -2 * x.x, 0};
  CHECK(s.orthogonality[0] ==
        doctest::Approx(std::fabs(dot(t, p - x)) / (norm(t) * norm(p - x))).epsilon(1e-14));
  CHECK(s.location == Location::interior);
  curve::fill_implicit_residuals(eq, box, p, circle_foot(p), s);
  CHECK(s.orthogonality[0] <= 1e-16);
  const curve::IterationControl c = curve::make_control(Options{}, 10, nullptr);
  CHECK(curve::implicit_residuals_met(s, circle_foot(p), c));
  CHECK(curve::foot_residuals_met(eq, p, circle_foot(p), c, true));
  CHECK(!curve::foot_residuals_met(eq, p, x, c, true));
  CHECK(curve::foot_residuals_met(eq, p, x, c, false));  // on the curve, not orthogonal
}

TEST_CASE("fill_implicit_residuals: at a face crossing only a step into the box that approaches p counts") {
  const ImplicitEquations eq = circle();
  const Box3 box{{-2, -1, 0}, {2, 1, 2}};
  const Vec3 crossing{std::sqrt(2.0), 1.0, 1.0};  // the circle leaves through y = 1
  Summary s;
  // p beyond the face: moving into the box (decreasing y) leads away from it: a minimum, residual 0.
  curve::fill_implicit_residuals(eq, box, {1.5, 2.0, 1.0}, crossing, s);
  CHECK(s.location == Location::box_face);
  CHECK(s.on_boundary);
  CHECK(s.orthogonality[0] == 0.0);
  // p inside, below the crossing: the curve inside the box comes nearer: a violated condition.
  curve::fill_implicit_residuals(eq, box, {1.8, 0.0, 1.0}, crossing, s);
  CHECK(s.orthogonality[0] > 0.1);
}

TEST_CASE("fill_implicit_residuals: a singular point, where T = 0, has no orthogonality residual") {
  const ImplicitEquations eq = spatial_equations("x^2+y^2+z^2-4", "(x-1)^2+y^2-1");
  const Box3 box{{-3, -3, -3}, {3, 3, 3}};
  Summary s;
  curve::fill_implicit_residuals(eq, box, {3, 0.5, 0.2}, {2, 0, 0}, s);
  CHECK(s.location == Location::singular_point);
  CHECK(s.orthogonality[0] == 0.0);
  const ProjectionResult r = curve::implicit_result(eq, box, {3, 0.5, 0.2}, {2, 0, 0}, "auto");
  CHECK(r.num_params == 0);
  CHECK(r.distance == doctest::Approx(std::sqrt(1.0 + 0.25 + 0.04)).epsilon(1e-15));
}
