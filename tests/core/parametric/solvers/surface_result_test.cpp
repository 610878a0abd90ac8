// parametric/solvers/surface_result: an answer on a surface from its parameters, point and
// tangents. Where (u, v) lies (interior, edge, corner, pole; a seam is no edge), the seam's
// parameters named once, and the Karush-Kuhn-Tucker residuals of min |p - s|^2 over the box: the
// orthogonality inside, only its sign's violation on a bound. On the plane (u, v, 0) and the
// cylinder (cos u, sin u, v) every value is worked out by hand.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "formula/program.hpp"
#include "parametric/solvers/surface_result.hpp"

using namespace footpoint;
using namespace footpoint::surface;

namespace {

constexpr ParamBox kUnitSquare{0, 1, 0, 1};
const Vec3 kPlaneSu{1, 0, 0}, kPlaneSv{0, 1, 0};

ProjectionResult plane_result(const Vec3& p, double u, double v) {
  return surface_result("test", p, u, v, {u, v, 0}, kPlaneSu, kPlaneSv, kUnitSquare);
}

}  // namespace

TEST_CASE("surface result: interior, edge and corner answers on a plane") {
  const ProjectionResult inside = plane_result({0.5, 0.25, 2}, 0.5, 0.25);
  CHECK(inside.summary.method == "test");
  CHECK(inside.summary.location == Location::interior);
  CHECK_FALSE(inside.summary.on_boundary);
  CHECK(inside.distance == 2.0);
  CHECK(inside.foot == std::array<double, 3>{0.5, 0.25, 0});
  CHECK(inside.params == std::array<double, 2>{0.5, 0.25});
  CHECK(inside.summary.orthogonality == std::array<double, 2>{0, 0});
  // p beyond u = 0: the foot on the edge, <p - s, s_u> = -1 <= 0 as a minimum there needs: 0.
  const ProjectionResult edge = plane_result({-1, 0.5, 1}, 0, 0.5);
  CHECK(edge.summary.location == Location::edge);
  CHECK(edge.summary.on_boundary);
  CHECK(edge.distance == doctest::Approx(std::sqrt(2.0)).epsilon(1e-15));
  CHECK(edge.summary.orthogonality == std::array<double, 2>{0, 0});
  // The same edge claimed for p inside the range of u: moving inwards comes nearer, the
  // violation is |<p - s, s_u>| / (|p - s| |s_u|) = 0.5 / √1.25.
  const ProjectionResult wrong = plane_result({0.5, 0.5, 1}, 0, 0.5);
  CHECK(wrong.summary.orthogonality[0] == doctest::Approx(0.5 / std::sqrt(1.25)).epsilon(1e-15));
  CHECK(wrong.summary.residual() > 0.4);
  // At u = umax the sign is the other way: <p - s, s_u> = 1 >= 0 is right.
  CHECK(plane_result({2, 0.5, 0}, 1, 0.5).summary.orthogonality[0] == 0.0);
  CHECK(plane_result({0, 0.5, 1}, 1, 0.5).summary.orthogonality[0] > 0.0);
  // A corner, both bounds right.
  const ProjectionResult corner = plane_result({2, 3, 0}, 1, 1);
  CHECK(corner.summary.location == Location::corner);
  CHECK(corner.summary.on_boundary);
  CHECK(corner.summary.residual() == 0.0);
  // Outside the domain: no location.
  CHECK(location_in(kUnitSquare, 1.5, 0.5) == Location::unknown);
}

TEST_CASE("surface result: non-finite residuals are the largest double, never NaN") {
  const ProjectionResult r =
      surface_result("test", {0.5, 0.5, 1}, 0.5, 0.5, {0.5, 0.5, 0}, {NAN, 0, 0}, kPlaneSv, kUnitSquare);
  CHECK(r.summary.orthogonality[0] == std::numeric_limits<double>::max());
  CHECK(r.summary.orthogonality[1] == 0.0);
}

TEST_CASE("surface result: a cylinder's seam is no edge, and is named by its lower bound") {
  const SurfaceFormulas cylinder(
      formula::Program::compile({{"x", "cos(u)"}, {"y", "sin(u)"}, {"z", "v"}}, {"u", "v"}, {}));
  const double two_pi = 2 * std::numbers::pi;
  const ParamBox box{0, two_pi, 0, 1};
  const SurfaceClosure closure = detect_surface_closure(cylinder, box);
  REQUIRE(closure.periodic(0));
  REQUIRE_FALSE(closure.periodic(1));
  CHECK(location_in(box, two_pi, 0.5, &closure) == Location::interior);
  CHECK(location_in(box, two_pi, 0.5) == Location::edge);     // without the closure, an edge
  CHECK(location_in(box, 0, 0, &closure) == Location::edge);  // the rim v = 0 is one
  CHECK(seam_representative(box, two_pi, 0.5, &closure) == std::array<double, 2>{0, 0.5});
  CHECK(seam_representative(box, two_pi, 0.5, nullptr) == std::array<double, 2>{two_pi, 0.5});
  // p = (2, 0, 0.5) outside the cylinder at u = 0: foot (1, 0, 0.5) on the seam, answered at
  // u = 0 whichever side found it, with the orthogonality itself (0) as its residual.
  const ProjectionResult r = surface_result("test", {2, 0, 0.5}, two_pi, 0.5, cylinder.point(two_pi, 0.5),
                                            {0, 1, 0}, {0, 0, 1}, box, &closure);
  CHECK(r.params == std::array<double, 2>{0, 0.5});
  CHECK(r.summary.location == Location::interior);
  CHECK(r.distance == doctest::Approx(1.0).epsilon(1e-15));
  CHECK(r.summary.residual() <= 1e-15);
}
