// implicit/seeding/face_crossings: the points of a curve on a face of a cell, each alone in a small box,
// against closed forms: the unit circle on vertical faces (one point, two points, none), a curve
// touching the face (undecided), a spatial circle crossing a face; the cache answers a face once.
#include <doctest/doctest.h>

#include <cmath>

#include "implicit/seeding/face_crossings.hpp"
#include "implicit_fixtures.hpp"

using namespace footpoint;
using namespace footpoint::test;

TEST_CASE("locate_face_crossings: the unit circle on vertical faces") {
  const ImplicitEquations eq = planar_equations("x^2+y^2-1");
  std::size_t evaluations = 0;
  std::vector<FaceCrossing> one, two, none;
  REQUIRE(locate_face_crossings(eq, {{0.6, 0.5, 0.0}, {0.6, 1.0, 0.0}}, 0, one, evaluations));
  REQUIRE(one.size() == 1);
  CHECK(std::fabs(one[0].point.y - 0.8) <= 1e-15);
  CHECK(one[0].enclosure.contains(Vec3{0.6, 0.8, 0.0}));
  CHECK(one[0].enclosure.max_edge() <= 1e-14);
  REQUIRE(locate_face_crossings(eq, {{0.6, -1.0, 0.0}, {0.6, 1.0, 0.0}}, 0, two, evaluations));
  REQUIRE(two.size() == 2);
  CHECK(std::fabs(std::fabs(two[0].point.y) - 0.8) <= 1e-15);
  CHECK(std::fabs(two[0].point.y + two[1].point.y) <= 1e-15);
  REQUIRE(locate_face_crossings(eq, {{2.0, -1.0, 0.0}, {2.0, 1.0, 0.0}}, 0, none, evaluations));
  CHECK(none.empty());
  CHECK(evaluations > 0);
}

TEST_CASE("locate_face_crossings: a touching point is left undecided") {
  // x = 1 touches the circle at (1, 0): a double root of f(1, y) = y^2.
  const ImplicitEquations eq = planar_equations("x^2+y^2-1");
  std::size_t evaluations = 0;
  std::vector<FaceCrossing> out;
  CHECK(!locate_face_crossings(eq, {{1.0, -0.1, 0.0}, {1.0, 0.1, 0.0}}, 0, out, evaluations));
}

TEST_CASE("locate_face_crossings: a spatial circle through a face") {
  // {|X| = 2} ∩ {z = 1} meets the face x = 1 (y, z in [0, 2]) at (1, √2, 1).
  const ImplicitEquations eq = circle();
  std::size_t evaluations = 0;
  std::vector<FaceCrossing> out;
  REQUIRE(locate_face_crossings(eq, {{1.0, 0.0, 0.0}, {1.0, 2.0, 2.0}}, 0, out, evaluations));
  REQUIRE(out.size() == 1);
  CHECK(norm(out[0].point - Vec3{1.0, std::sqrt(2.0), 1.0}) <= 1e-15);
  CHECK(out[0].enclosure.contains(Vec3{1.0, std::sqrt(2.0), 1.0}));
  FaceCrossingCache cache(eq);
  std::vector<FaceCrossing> first, second;
  std::size_t e1 = 0, e2 = 0;
  REQUIRE(cache.locate({{1.0, 0.0, 0.0}, {1.0, 2.0, 2.0}}, 0, first, e1));
  REQUIRE(cache.locate({{1.0, 0.0, 0.0}, {1.0, 2.0, 2.0}}, 0, second, e2));
  CHECK(first.size() == 1);
  CHECK(second.size() == 1);
  CHECK(e1 > 0);
  CHECK(e2 == 0);  // the second time from the cache
}
