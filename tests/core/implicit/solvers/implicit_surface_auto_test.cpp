// implicit/solvers/implicit_surface_auto: `auto` on an equation and its cells (no compiled
// geometry), against closed forms:
//  - an ellipsoid wholly inside its box: Eberly's distance (bisection on the secular equation),
//    the certificate's lower bound at most that distance and certified, one foot;
//  - answers on the box: a cylinder cut by the faces z = 0, 1 (the foot on the face circle,
//    distance hypot(r - 1, z - 1)), the triangle x + y + z = 1 in the unit cube (a corner, a
//    point of a face's line), a sphere of radius 2 in [0, 1]^2 x [-3, 3] (the box edge's point
//    (1, 1, sqrt 2), where the concave 3x + 3y + 2 sqrt(4 - x^2 - y^2) is largest over the square);
//  - multiplicity: the elliptic cylinder x^2/4 + y^2 = 1 from its axis plane x = 0 has two feet
//    (0, ±1, z) (curvature radius 4 there, beyond the distance 1: no continuum); a circular
//    cylinder from its axis a continuum;
//  - all_minima on the elliptic cylinder (the two local minima, the answer first), a cone's apex
//    as a singular point, certify = false, max_distance.
#include <doctest/doctest.h>

#include <cmath>
#include <random>
#include <string>

#include "implicit/solvers/implicit_surface_auto.hpp"
#include "implicit_surface_truths.hpp"

using namespace footpoint;
using namespace footpoint::surface_implicit;

namespace implicit_surface_auto_test {

Vec3 foot_of(const ProjectionResult& r) { return {r.foot[0], r.foot[1], r.foot[2]}; }

// `auto` from p is at the closed-form foot, converged, certified with a lower bound at most the
// true distance.
ProjectionResult check_auto(const ImplicitSurfaceEquation& f, const ImplicitSurfaceCells& cells, Vec3 p,
                            Vec3 foot, Location location) {
  const ProjectionResult r = implicit_surface_auto(f, cells, p, {});
  const double d = norm(p - foot);
  CHECK(r.summary.method == "auto");
  CHECK(r.summary.status == Status::converged);
  CHECK(std::fabs(r.distance - d) <= 1e-12 * (1.0 + d));
  CHECK(norm(foot_of(r) - foot) <= 1e-9);
  CHECK(r.summary.location == location);
  CHECK(r.summary.certificate.computed);
  CHECK(r.summary.certificate.certified);
  CHECK(r.summary.certificate.lower_bound <= d * (1.0 + 1e-15));
  return r;
}

TEST_CASE("implicit surface auto: an ellipsoid against Eberly's distance, certified") {
  const ImplicitSurfaceEquation f = test::surface_equation("x^2/4+y^2+4*z^2-1");
  const ImplicitSurfaceCells cells = test::surface_cells(f, {{-3, -2, -1}, {3, 2, 1}});
  std::mt19937 rng(47);
  std::uniform_real_distribution<double> x(-3.0, 3.0), y(-2.0, 2.0), z(-1.0, 1.0);
  for (int i = 0; i < 25; ++i) {
    const Vec3 p{x(rng), y(rng), z(rng)};
    CAPTURE(i);
    const ProjectionResult r =
        check_auto(f, cells, p, test::ellipsoid_foot({2, 1, 0.5}, p), Location::interior);
    CHECK(r.summary.multiplicity.kind == Multiplicity::unique);
    CHECK(r.summary.equation_residual[0] <= 1e-15);
  }
}

TEST_CASE("implicit surface auto: feet on the box's faces, edges and corners") {
  // The cylinder x^2 + y^2 = 1 for 0 <= z <= 1: above the box the foot is on the face z = 1.
  const ImplicitSurfaceEquation cylinder = test::surface_equation("x^2+y^2-1");
  const ImplicitSurfaceCells short_cylinder = test::surface_cells(cylinder, {{-2, -2, 0}, {2, 2, 1}});
  for (const Vec3 p : {Vec3{1.5, 0.5, 1.8}, Vec3{-0.2, 0.3, -0.6}, Vec3{0.3, -1.9, 0.4}}) {
    CAPTURE(p.x);
    const double r = std::hypot(p.x, p.y), z = std::clamp(p.z, 0.0, 1.0);
    check_auto(cylinder, short_cylinder, p, {p.x / r, p.y / r, z},
               z == p.z ? Location::interior : Location::box_face);
  }
  // The triangle x + y + z = 1 in the unit cube. (3, -1, -1) lies in its plane beyond the corner
  // (1, 0, 0) (both edges from it point away from p); (1, 1, -1) lies in it beyond the edge z = 0,
  // whose point nearest p, (1/2, 1/2, 0), has one coordinate at a bound: a face of the box.
  const ImplicitSurfaceEquation plane = test::surface_equation("x+y+z-1");
  const ImplicitSurfaceCells triangle = test::surface_cells(plane, {{0, 0, 0}, {1, 1, 1}});
  check_auto(plane, triangle, {3, -1, -1}, {1, 0, 0}, Location::box_corner);
  check_auto(plane, triangle, {1, 1, -1}, {0.5, 0.5, 0}, Location::box_face);
  // The sphere |X| = 2 in [0, 1]^2 x [-3, 3], from (3, 3, 2): the corner of the patch on the box
  // edge x = y = 1.
  const ImplicitSurfaceEquation sphere = test::surface_equation("x^2+y^2+z^2-4");
  const ImplicitSurfaceCells patch = test::surface_cells(sphere, {{0, 0, -3}, {1, 1, 3}});
  check_auto(sphere, patch, {3, 3, 2}, {1, 1, std::sqrt(2.0)}, Location::box_edge);
}

TEST_CASE("implicit surface auto: two feet on an elliptic cylinder, a continuum on a circular one") {
  // x^2/4 + y^2 = 1 from (0, 0, 0.2): the feet (0, ±1, 0.2) at distance 1.
  const ImplicitSurfaceEquation elliptic = test::surface_equation("x^2/4+y^2-1");
  const ImplicitSurfaceCells cells = test::surface_cells(elliptic, {{-3, -2, -1}, {3, 2, 1}});
  const ProjectionResult r = implicit_surface_auto(elliptic, cells, {0.0, 0.0, 0.2}, {});
  CHECK(r.summary.status == Status::converged);
  CHECK(std::fabs(r.distance - 1.0) <= 1e-15);
  CHECK(r.summary.certificate.certified);
  CHECK(r.summary.certificate.lower_bound <= 1.0);
  const AnswerMultiplicity& m = r.summary.multiplicity;
  CHECK(m.kind == Multiplicity::tied);
  REQUIRE(m.count == 2);
  REQUIRE(m.feet.size() == 2);
  for (const auto& foot : m.feet) {
    CHECK(std::fabs(foot[0]) <= 1e-15);
    CHECK(std::fabs(std::fabs(foot[1]) - 1.0) <= 1e-15);
    CHECK(std::fabs(foot[2] - 0.2) <= 1e-15);
  }
  CHECK(m.feet[0][1] * m.feet[1][1] < 0.0);
  // Nearer to one side, from (0, 0.3, 0.2): one foot, (0, 1, 0.2).
  const ProjectionResult one =
      check_auto(elliptic, cells, {0.0, 0.3, 0.2}, {0.0, 1.0, 0.2}, Location::interior);
  CHECK(one.summary.multiplicity.kind == Multiplicity::unique);
  // x^2 + y^2 = 1 from a point of its axis: every point of the circle at that height is a foot
  // (I + l H = diag(0, 0, 1) there, flat along the circle).
  const ImplicitSurfaceEquation circular = test::surface_equation("x^2+y^2-1");
  const ImplicitSurfaceCells round = test::surface_cells(circular, {{-2, -2, -1}, {2, 2, 1}});
  const ProjectionResult axis = implicit_surface_auto(circular, round, {0.0, 0.0, 0.3}, {});
  CHECK(std::fabs(axis.distance - 1.0) <= 1e-15);
  CHECK(std::fabs(axis.foot[2] - 0.3) <= 1e-15);
  CHECK(axis.summary.multiplicity.kind == Multiplicity::continuum);
  CHECK(axis.summary.certificate.lower_bound <= 1.0);
}

TEST_CASE("implicit surface auto: all_minima, a singular point, certify and max_distance") {
  // The elliptic cylinder from (0, 0.3, 0.2): on the section z = 0.2 the squared distance to
  // (2 sin t, ±cos t) is 0.49 + 3.3 t^2 and 1.69 + 2.7 t^2 to second order, along z it grows: two
  // local minima, (0, 1, 0.2) at 0.7 and (0, -1, 0.2) at 1.3; the points at x = ±2 are maxima of
  // the section's distance, and the face curves z = ±1 are left toward the inside of the box.
  const ImplicitSurfaceEquation elliptic = test::surface_equation("x^2/4+y^2-1");
  const ImplicitSurfaceCells cells = test::surface_cells(elliptic, {{-3, -2, -1}, {3, 2, 1}});
  const Vec3 p{0.0, 0.3, 0.2};
  Options all;
  all.all_minima = true;
  const ProjectionResult r = implicit_surface_auto(elliptic, cells, p, all);
  REQUIRE(r.minima.size() == 2);
  CHECK(std::fabs(r.minima[0].distance - 0.7) <= 1e-15);
  CHECK(std::fabs(r.minima[1].distance - 1.3) <= 1e-15);
  CHECK(norm(Vec3{r.minima[1].foot[0], r.minima[1].foot[1], r.minima[1].foot[2]} - Vec3{0, -1, 0.2}) <=
        1e-14);
  CHECK(r.minima[0].foot == r.foot);
  // Not certified: the same answer, no certificate.
  Options quick;
  quick.certify = false;
  const ProjectionResult q = implicit_surface_auto(elliptic, cells, p, quick);
  CHECK(!q.summary.certificate.computed);
  CHECK(std::fabs(q.distance - 0.7) <= 1e-15);
  // Farther than max_distance: beyond_max_distance, nothing answered.
  Options near;
  near.max_distance = 0.5;
  const ProjectionResult far = implicit_surface_auto(elliptic, cells, p, near);
  CHECK(far.summary.status == Status::beyond_max_distance);
  CHECK(std::isnan(far.distance));
  // The cone x^2 + y^2 = z^2 above z = 0 from (0, 0, -1): |X - p|^2 = r^2 + (r + 1)^2 on the cone
  // is least at r = 0, the apex, where grad f = 0.
  const ImplicitSurfaceEquation cone = test::surface_equation("x^2+y^2-z^2");
  const ImplicitSurfaceCells upper = test::surface_cells(cone, {{-1, -1, 0}, {1, 1, 1}});
  const ProjectionResult apex = implicit_surface_auto(cone, upper, {0.0, 0.0, -1.0}, {});
  CHECK(std::fabs(apex.distance - 1.0) <= 1e-12);
  CHECK(norm(foot_of(apex)) <= 1e-12);
  CHECK(apex.summary.location == Location::singular_point);
  CHECK(apex.summary.certificate.lower_bound <= 1.0);
}

}  // namespace implicit_surface_auto_test
