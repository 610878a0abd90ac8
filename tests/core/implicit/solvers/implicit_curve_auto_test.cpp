// implicit/solvers/implicit_curve_auto: the global nearest point of an implicit curve in its box, over
// curves discovered here (DiscoveredCurve). Checked against closed forms (a circle from outside
// and inside, its axis where every point of it is nearest, an ellipse's two tied feet, a foot on
// the box's face, two factor curves meeting) and a brute-force sampling of Viviani's curve: the
// distance and foot, the certificate's lower bound below the true distance and certified (where the
// answer is an isolated regular minimum), the multiplicity, max_distance.
#include <doctest/doctest.h>

#include <cmath>
#include <memory>
#include <vector>

#include "closed_form_curves.hpp"
#include "implicit/solvers/implicit_curve_auto.hpp"
#include "implicit_fixtures.hpp"

using namespace footpoint;
using namespace footpoint::test;

namespace implicit_curve_auto_test {

const Box3 kPlane{{-3, -3, 0}, {3, 3, 0}};
const Box3 kSpace{{-3, -3, -3}, {3, 3, 3}};

std::unique_ptr<DiscoveredCurve> discovered(ImplicitEquations eq, const Box3& box) {
  CompileBudget budget;
  return std::make_unique<DiscoveredCurve>(std::move(eq), box, budget);
}

ProjectionResult project(const DiscoveredCurve& curve, const Box3& box, Vec3 p, const Options& o = {}) {
  const DiscoveredCurve* factors[] = {&curve};
  return curve::implicit_curve_auto(factors, box, p, o);
}

Vec3 foot_of(const ProjectionResult& r) { return {r.foot[0], r.foot[1], r.foot[2]}; }

// A converged answer with a certificate whose lower bound is no greater than its distance and than
// the true distance `truth`.
void check_bound(const ProjectionResult& r, double truth) {
  CHECK(r.summary.status == Status::converged);
  CHECK(r.summary.certificate.computed);
  CHECK(r.summary.certificate.lower_bound <= r.distance);
  CHECK(r.summary.certificate.lower_bound <= truth);
}

// The same, certified: the bound within the gap of projection/certificate.hpp (1e-9 relative, or
// the rounding level at distance ~0).
void check_certified(const ProjectionResult& r, double truth) {
  check_bound(r, truth);
  CHECK(r.summary.certificate.certified);
  CHECK(r.distance - r.summary.certificate.lower_bound <=
        std::max(1e-9 * r.distance, r.summary.certificate.absolute_gap));
}

TEST_CASE("implicit_curve_auto: the circle sphere ∩ plane from outside and inside, closed form") {
  // {x^2 + y^2 + z^2 = 4} ∩ {z = 1}: the nearest point of p off the axis is (sqrt 3 (px, py) / r, 1),
  // r = |(px, py)|, at distance sqrt((r - sqrt 3)^2 + (pz - 1)^2), the only one.
  const auto c = discovered(circle(), kSpace);
  for (const Vec3 p : {Vec3{3.0, 1.0, 2.0}, Vec3{0.5, 0.2, 1.0}, Vec3{-0.1, -2.5, -2.0}}) {
    CAPTURE(p);
    const ProjectionResult r = project(*c, kSpace, p);
    const double d = std::hypot(std::hypot(p.x, p.y) - kCircleRadius, p.z - 1.0);
    CHECK(norm(foot_of(r) - circle_foot(p)) <= 1e-13);
    CHECK(r.distance == doctest::Approx(d).epsilon(1e-14));
    check_certified(r, d);
    CHECK(r.summary.method == "auto");
    CHECK(r.summary.location == Location::interior);
    CHECK(r.summary.multiplicity.computed);
    CHECK(r.summary.multiplicity.kind == Multiplicity::unique);
  }
}

TEST_CASE("implicit_curve_auto: on the circle's axis every point of it is nearest, a continuum") {
  // p = (0, 0, z): every point of the circle is at sqrt(3 + (z - 1)^2). The certificate's Krawczyk
  // test proves a critical point alone in its cell, which no cell passes when the critical points
  // are the whole curve: its bound stays below the distance by the cells' capsules (not within the
  // 1e-9 gap), but must not exceed it.
  const auto c = discovered(circle(), kSpace);
  for (const double z : {1.0, 2.5}) {
    CAPTURE(z);
    const ProjectionResult r = project(*c, kSpace, {0.0, 0.0, z});
    const double d = std::sqrt(3.0 + (z - 1.0) * (z - 1.0));
    CHECK(r.distance == doctest::Approx(d).epsilon(1e-14));
    CHECK(std::fabs(std::hypot(r.foot[0], r.foot[1]) - kCircleRadius) <= 1e-14);
    CHECK(r.foot[2] == doctest::Approx(1.0).epsilon(1e-15));
    check_bound(r, d);
    CHECK(r.summary.multiplicity.kind == Multiplicity::continuum);
  }
}

TEST_CASE("implicit_curve_auto: two tied feet on an ellipse") {
  // x^2/4 + y^2 = 1 and p = (0.6, 0): the feet (x, +-y) with x = a^2 px / (a^2 - b^2) = 0.8 (the
  // normal at (x, y) meets the major axis at (1 - b^2/a^2) x), y^2 = 1 - x^2/4 = 0.84, at distance
  // sqrt(0.2^2 + 0.84) = sqrt(0.88); the vertices (+-2, 0) and (0, +-1) are farther.
  const auto e = discovered(planar_equations("x^2/4+y^2-1"), kPlane);
  const ProjectionResult r = project(*e, kPlane, {0.6, 0.0, 0.0});
  CHECK(r.distance == doctest::Approx(std::sqrt(0.88)).epsilon(1e-14));
  CHECK(r.foot[0] == doctest::Approx(0.8).epsilon(1e-12));
  CHECK(std::fabs(r.foot[1]) == doctest::Approx(std::sqrt(0.84)).epsilon(1e-12));
  check_certified(r, std::sqrt(0.88));
  const AnswerMultiplicity& m = r.summary.multiplicity;
  CHECK(m.kind == Multiplicity::tied);
  CHECK(m.count == 2);
  REQUIRE(m.feet.size() == 2);
  CHECK(m.feet[0][0] == doctest::Approx(0.8).epsilon(1e-12));
  CHECK(m.feet[1][0] == doctest::Approx(0.8).epsilon(1e-12));
  CHECK(m.feet[0][1] == doctest::Approx(-m.feet[1][1]).epsilon(1e-12));
  CHECK(std::fabs(m.feet[0][1]) == doctest::Approx(std::sqrt(0.84)).epsilon(1e-12));
  // |p - (2 cos t, sin t)|^2 has derivative sin t (2.4 - 6 cos t): its minima are the two feet
  // (cos t = 0.4), the vertices (+-2, 0) are maxima; all_minima lists exactly the two.
  Options all;
  all.all_minima = true;
  const ProjectionResult both = project(*e, kPlane, {0.6, 0.0, 0.0}, all);
  REQUIRE(both.minima.size() == 2);
  for (const Minimum& min : both.minima) {
    CHECK(min.distance == doctest::Approx(std::sqrt(0.88)).epsilon(1e-14));
    CHECK(min.foot[0] == doctest::Approx(0.8).epsilon(1e-12));
  }
}

TEST_CASE("implicit_curve_auto: Viviani's curve against a brute-force sampling, its double point included") {
  // Brute force: 20000 samples of (1 + cos t, sin t, 2 sin(t/2)), the least refined by Newton in t.
  // p = (2.5, 0, 0): |p - c(t)|^2 = 5.25 - 5 cos t, least at the double point (2, 0, 0), 0.5 away;
  // there the certificate bounds the unproved boxes around the double point by their box distance
  // only, a few of their edges (~6e-6) below the distance: a bound, not certified.
  const auto v = discovered(spatial_equations("x^2+y^2+z^2-4", "(x-1)^2+y^2-1"), kSpace);
  for (const Vec3 p :
       {Vec3{0.5, 1.5, 1.0}, Vec3{-1.0, -0.5, -2.0}, Vec3{1.0, 0.0, 0.3}, Vec3{2.5, 0.0, 0.0}}) {
    CAPTURE(p);
    const ProjectionResult r = project(*v, kSpace, p);
    const CurveNearest ref = nearest_on(viviani_curve(), p);
    CHECK(r.distance <= ref.distance * (1.0 + 1e-13));
    CHECK(r.distance >= ref.distance * (1.0 - 1e-13));
    const Vec3 x = foot_of(r);
    CHECK(std::fabs(norm2(x) - 4.0) <= 1e-13);
    CHECK(std::fabs(norm2(x - Vec3{1, 0, 0}) - x.z * x.z - 1.0) <= 1e-13);
    if (p.x == 2.5) {
      check_bound(r, ref.distance);
      CHECK(r.distance - r.summary.certificate.lower_bound <= 1e-4);
      CHECK(r.summary.location == Location::singular_point);
      CHECK(norm(x - Vec3{2, 0, 0}) <= 1e-12);
    } else {
      check_certified(r, ref.distance);
    }
  }
}

TEST_CASE("implicit_curve_auto: a foot on the box's face is the exact crossing") {
  // x^2 + y^2 = 1 in x <= 0.5: from p = (3, 0.5) the nearest point of the arc left in the box is
  // its end (0.5, sqrt 0.75) (the distance grows along the arc away from it).
  const Box3 box{{-2, -2, 0}, {0.5, 2, 0}};
  const auto c = discovered(planar_equations("x^2+y^2-1"), box);
  const Vec3 p{3.0, 0.5, 0.0};
  const ProjectionResult r = project(*c, box, p);
  const Vec3 end{0.5, std::sqrt(0.75), 0.0};
  CHECK(norm(foot_of(r) - end) <= 1e-15);
  CHECK(r.distance == doctest::Approx(norm(p - end)).epsilon(1e-15));
  CHECK(r.summary.location == Location::box_face);
  check_certified(r, norm(p - end));
}

TEST_CASE("implicit_curve_auto: a union of factor curves; where two meet is a singular point") {
  // The unit circle and the line y = 0 cross at (+-1, 0): from p = (2, 0.1) the nearest point of the
  // circle is p / |p| (at |p| - 1 ~ 1.0025), of the line (2, 0) (at 0.1); p = (1, 0) is on both.
  const auto unit = discovered(planar_equations("x^2+y^2-1"), kPlane);
  const auto axis = discovered(planar_equations("y"), kPlane);
  const DiscoveredCurve* crossing[] = {unit.get(), axis.get()};
  const ProjectionResult r = curve::implicit_curve_auto(crossing, kPlane, {2.0, 0.1, 0.0}, Options{});
  CHECK(r.distance == doctest::Approx(0.1).epsilon(1e-14));
  CHECK(norm(foot_of(r) - Vec3{2, 0, 0}) <= 1e-15);
  CHECK(r.summary.location == Location::interior);
  check_certified(r, 0.1);
  const ProjectionResult on = curve::implicit_curve_auto(crossing, kPlane, {1.0, 0.0, 0.0}, Options{});
  CHECK(on.distance <= 1e-15);
  CHECK(on.summary.location == Location::singular_point);
  check_certified(on, 0.0);
  // The circle and its tangent x = 1 touch at (1, 0), the nearest point of both for p = (2, 0).
  const auto tangent = discovered(planar_equations("x-1"), kPlane);
  const DiscoveredCurve* touching[] = {unit.get(), tangent.get()};
  const ProjectionResult meet = curve::implicit_curve_auto(touching, kPlane, {2.0, 0.0, 0.0}, Options{});
  CHECK(meet.distance == doctest::Approx(1.0).epsilon(1e-14));
  CHECK(norm(foot_of(meet) - Vec3{1, 0, 0}) <= 1e-14);
  CHECK(meet.summary.location == Location::singular_point);
  check_certified(meet, 1.0);
}

TEST_CASE("implicit_curve_auto: every point farther than max_distance withholds the answer") {
  // The circle is sqrt((sqrt 10 - sqrt 3)^2 + 1) ~ 1.75 from p = (3, 1, 2).
  const auto c = discovered(circle(), kSpace);
  Options o;
  o.max_distance = 1.0;
  const ProjectionResult r = project(*c, kSpace, {3.0, 1.0, 2.0}, o);
  CHECK(r.summary.status == Status::beyond_max_distance);
  CHECK(std::isnan(r.distance));
  o.max_distance = 2.0;
  CHECK(project(*c, kSpace, {3.0, 1.0, 2.0}, o).summary.status == Status::converged);
}

}  // namespace implicit_curve_auto_test
