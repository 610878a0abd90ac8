// implicit/geometry/curve_correction: Newton onto an implicit curve (minimum norm, in a normal plane, onto a
// face of the box), on a circle whose points in closed form are the references.
#include <doctest/doctest.h>

#include <cmath>

#include "implicit/geometry/curve_correction.hpp"
#include "implicit_fixtures.hpp"

using namespace footpoint;
using namespace footpoint::test;

namespace {

// |f1| and |f2| of the circle at x.
double off_curve(Vec3 x) { return std::fabs(dot(x, x) - 4.0) + std::fabs(x.z - 1.0); }

}  // namespace

TEST_CASE("newton_onto_curve: a point near the circle lands on it, next to where it started") {
  const ImplicitEquations eq = circle();
  for (double a : {0.0, 1.3, -2.9}) {
    const Vec3 start = circle_point(a) + Vec3{0.05, -0.03, 0.04};
    Vec3 x = start;
    REQUIRE(curve::newton_onto_curve(eq, x));
    CHECK(off_curve(x) <= 1e-15 * 8);
    // The minimum-norm step of the linearised curve moves across it, not along it: the landing is
    // within the start's distance of the circle's point at the same angle, and far from any other.
    CHECK(norm(x - circle_point(std::atan2(start.y, start.x))) <= 0.01);
  }
  // No curve to land on: the sphere x^2 + y^2 + z^2 = 4 and the plane z = 3 do not meet.
  const ImplicitEquations apart = spatial_equations("x^2+y^2+z^2-4", "z-3");
  Vec3 x{0.5, 0.5, 2.5};
  CHECK(!curve::newton_onto_curve(apart, x));
}

TEST_CASE("correct_in_normal_plane: the circle's point in the plane through y orthogonal to t") {
  const ImplicitEquations eq = circle();
  // The plane y = 0.3 (t = e_y) cuts the circle at x = sqrt(3 - 0.09), z = 1 near y.
  const Vec3 y{1.7, 0.3, 1.05};
  Vec3 z;
  int iterations = 0;
  REQUIRE(curve::correct_in_normal_plane(eq, y, {0, 1, 0}, z, iterations));
  CHECK(norm(z - Vec3{std::sqrt(3.0 - 0.09), 0.3, 1.0}) <= 1e-15 * 4);
  CHECK(iterations >= 1);
  CHECK(iterations <= 6);
  // A plane that misses the circle: y = 2 > sqrt(3).
  CHECK(!curve::correct_in_normal_plane(eq, {0.1, 2.0, 1.0}, {0, 1, 0}, z, iterations));
}

TEST_CASE("locate_face_crossing: where the circle leaves the box through the face y = 1") {
  const ImplicitEquations eq = circle();
  const Box3 box{{-2, -1, 0}, {2, 1, 2}};
  // From angle 0.5 (y = 0.83, inside) to 0.7 (y = 1.12, outside): the crossing is (sqrt(2), 1, 1).
  Vec3 crossing;
  REQUIRE(curve::locate_face_crossing(eq, box, circle_point(0.5), circle_point(0.7), crossing));
  CHECK(norm(crossing - Vec3{std::sqrt(2.0), 1.0, 1.0}) <= 1e-15 * 4);
  CHECK(crossing.y == 1.0);
  // Both points inside: no face is crossed.
  CHECK(!curve::locate_face_crossing(eq, box, circle_point(0.1), circle_point(0.3), crossing));
}
