// implicit/seeding/curve_cells: the certified subdivision of a curve's box. Checked against points of
// the curves known from their parametrisations (a circle, the circle clipped by its box, Viviani's
// curve with its double point (2, 0, 0), the isolated point of x^2 + y^2 = 0): every point of the
// curve in the box lies in a proved cell or an unproved box; in a proved cell it lies on one of
// the cell's arcs, inside that arc's capsule, where the tangent component T_axis (worked out by
// hand) keeps one sign; the cells' crossings are points of the curve on their faces; the unproved
// boxes are the double point's neighbourhood; the cell budget and the deadline stop it with the
// documented errors.
#include <doctest/doctest.h>

#include <chrono>
#include <cmath>
#include <string>
#include <vector>

#include "closed_form_curves.hpp"
#include "geometry/geometry_error.hpp"
#include "implicit_fixtures.hpp"

using namespace footpoint;
using namespace footpoint::test;

namespace curve_cells_test {

const Box3 kPlane{{-2, -2, 0}, {2, 2, 0}};
const Box3 kSpace{{-3, -3, -3}, {3, 3, 3}};

ImplicitEquations viviani() { return spatial_equations("x^2+y^2+z^2-4", "(x-1)^2+y^2-1"); }

// n points of the curve, evenly spaced in its parameter, that lie in `box`.
std::vector<Vec3> dense_points(const ParamCurve& curve, const Box3& box, int n = 4000) {
  std::vector<Vec3> out;
  for (int i = 0; i < n; ++i) {
    const Vec3 x = curve.c(curve.t0 + (curve.t1 - curve.t0) * i / n);
    if (box.contains(x)) out.push_back(x);
  }
  return out;
}

bool in_some_box(const CurveCells& cells, Vec3 x) {
  for (const ProvedCell& c : cells.cells)
    if (c.box.contains(x, 1e-12)) return true;
  for (const UnprovedBox& u : cells.unproved)
    if (u.box.contains(x, 1e-12)) return true;
  return false;
}

double segment_distance(Vec3 x, Vec3 a, Vec3 b) {
  const Vec3 d = b - a;
  const double l2 = norm2(d);
  const double s = l2 > 0.0 ? std::clamp(dot(x - a, d) / l2, 0.0, 1.0) : 0.0;
  return norm(x - (a + s * d));
}

// In some proved cell that holds x, x lies in one of the cell's arc capsules.
bool in_a_capsule(const CurveCells& cells, Vec3 x) {
  for (std::size_t c = 0; c < cells.cells.size(); ++c) {
    if (!cells.cells[c].box.contains(x, 1e-12)) continue;
    for (const ArcCapsule& a : cells.arc_capsules(c))
      if (segment_distance(x, a.a, a.b) <= a.radius * (1.0 + 1e-9) + 1e-12) return true;
  }
  return false;
}

// The layout of the cells: an even, positive number of crossings each, sorted along the cell's
// axis, on the cell's boundary and on the curve (|f_i| by hand); one capsule per arc. Returns the
// cells that break it.
template <class F>
int bad_cells(const CurveCells& cells, F&& residual) {
  REQUIRE(cells.capsule_begin.size() == cells.cells.size() + 1);
  int bad = 0;
  for (std::size_t c = 0; c < cells.cells.size(); ++c) {
    const ProvedCell& cell = cells.cells[c];
    bool ok = cell.crossing_count > 0 && cell.crossing_count % 2 == 0 &&
              cells.arc_capsules(c).size() == static_cast<std::size_t>(cell.crossing_count / 2);
    for (std::int32_t i = 0; i < cell.crossing_count; ++i) {
      const Vec3 x = cells.crossings[static_cast<std::size_t>(cell.first_crossing + i)].point;
      bool on_face = false;
      for (int k = 0; k < 3; ++k)
        on_face = on_face || (cell.box.hi[k] > cell.box.lo[k] && (std::fabs(x[k] - cell.box.lo[k]) <= 1e-12 ||
                                                                  std::fabs(x[k] - cell.box.hi[k]) <= 1e-12));
      ok = ok && on_face && cell.box.contains(x, 1e-12) && residual(x) <= 1e-12;
      if (i > 0)
        ok = ok && cells.crossings[static_cast<std::size_t>(cell.first_crossing + i - 1)].point[cell.axis] <=
                       x[cell.axis];
    }
    if (!ok) ++bad;
  }
  return bad;
}

// The proved cells in which the component T_axis (tangent(x)) changes sign or vanishes along the
// arcs (at the given points of the curve).
template <class T>
int not_monotone(const CurveCells& cells, const std::vector<Vec3>& points, T&& tangent) {
  int bad = 0;
  for (const ProvedCell& cell : cells.cells) {
    int sign = 0;
    bool ok = true;
    for (const Vec3& x : points) {
      if (!cell.box.contains(x)) continue;
      const double t = tangent(x)[cell.axis];
      const int s = t > 0.0 ? 1 : (t < 0.0 ? -1 : 0);
      if (sign == 0) sign = s;
      ok = ok && s != 0 && s == sign;
    }
    if (!ok) ++bad;
  }
  return bad;
}

// The points in no proved cell and no unproved box; with `capsules`, also those in no capsule of
// a proved cell that holds them, unless within `spared` of `centre`.
int uncovered(const CurveCells& cells, const std::vector<Vec3>& points, bool capsules, Vec3 centre = {},
              double spared = 0.0) {
  int out = 0;
  for (const Vec3& x : points)
    if (!in_some_box(cells, x) || (capsules && norm(x - centre) > spared && !in_a_capsule(cells, x))) ++out;
  return out;
}

TEST_CASE("subdivide_curve: a circle, every point in a proved cell, on an arc's capsule, monotone") {
  // x^2 + y^2 = 1: T = grad f x e_z = (2y, -2x, 0). No singular point: nothing is left unproved.
  const ImplicitEquations eq = planar_equations("x^2+y^2-1");
  const CurveCells cells = subdivided_cells(eq, kPlane);
  CHECK(cells.unproved.empty());
  CHECK(!cells.cells.empty());
  const std::vector<Vec3> points = dense_points(ellipse_curve(1.0, 1.0), kPlane);
  REQUIRE(points.size() == 4000);
  CHECK(uncovered(cells, points, true) == 0);
  CHECK(bad_cells(cells, [](Vec3 x) { return std::fabs(x.x * x.x + x.y * x.y - 1.0); }) == 0);
  CHECK(not_monotone(cells, points, [](Vec3 x) { return Vec3{2 * x.y, -2 * x.x, 0.0}; }) == 0);
  CHECK(cells.examined >= cells.cells.size());
}

TEST_CASE("subdivide_curve: Viviani's curve, unproved only next to its double point") {
  // T = grad f1 x grad f2 = 4 (x, y, z) x (x - 1, y, 0) = 4 (-yz, z (x - 1), y), zero only at (2, 0, 0).
  const ImplicitEquations eq = viviani();
  const CurveCells cells = subdivided_cells(eq, kSpace);
  const std::vector<Vec3> points = dense_points(viviani_curve(), kSpace, 2000);
  // Every point in a box; away from the double point in a proved cell's capsule.
  CHECK(uncovered(cells, points, false) == 0);
  CHECK(uncovered(cells, points, true, {2, 0, 0}, 1e-3) == 0);
  REQUIRE(!cells.unproved.empty());
  // The unproved boxes, at most max_extra_levels = 14 bisections below the enclosure's cells
  // (edge 6.2 / 64 after the enclosure's offset), lie around the double point.
  const double finest = 6.2 / 64 / 16384;
  for (const UnprovedBox& u : cells.unproved) {
    CHECK(u.box.max_edge() <= finest);
    CHECK(norm(u.box.center() - Vec3{2, 0, 0}) <= 4 * finest);
    CHECK(u.reason == UnprovedReason::tangent_may_vanish);
  }
  CHECK(cells.deepest <= 14);
  CHECK(bad_cells(cells, [](Vec3 x) {
          return std::max(std::fabs(x.x * x.x + x.y * x.y + x.z * x.z - 4.0),
                          std::fabs((x.x - 1) * (x.x - 1) + x.y * x.y - 1.0));
        }) == 0);
  CHECK(not_monotone(cells, points, [](Vec3 x) { return Vec3{-x.y * x.z, x.z * (x.x - 1), x.y}; }) == 0);
}

TEST_CASE("subdivide_curve: what no bisection is allowed to prove stays as unproved boxes") {
  // With no level below the enclosure, every cell (at level 0 too loose for the certificates'
  // tightness) is kept unproved: still every point of the curve is in one of them.
  SubdivisionSettings s;
  s.max_extra_levels = 0;
  const CurveCells cells = subdivided_cells(viviani(), kSpace, s);
  CHECK(cells.deepest == 0);
  CHECK(!cells.unproved.empty());
  CHECK(uncovered(cells, dense_points(viviani_curve(), kSpace), false) == 0);
  // The isolated point of x^2 + y^2 = 0 is a curve with no arc: it stays in an unproved box.
  const CurveCells point = subdivided_cells(planar_equations("x^2+y^2"), {{-1, -1, 0}, {1, 1, 0}});
  CHECK(point.cells.empty());
  REQUIRE(!point.unproved.empty());
  CHECK(in_some_box(point, {0, 0, 0}));
}

TEST_CASE("subdivide_curve: a circle clipped by its box, covered up to the box's face") {
  // x <= 0.5 cuts the unit circle at (0.5, +-sqrt 0.75): the cells end there, crossings included.
  const Box3 box{{-2, -2, 0}, {0.5, 2, 0}};
  const CurveCells cells = subdivided_cells(planar_equations("x^2+y^2-1"), box);
  CHECK(uncovered(cells, dense_points(ellipse_curve(1.0, 1.0), box), false) == 0);
  int on_face = 0;
  for (const FaceCrossing& c : cells.crossings)
    if (c.point.x == 0.5) {
      ++on_face;
      CHECK(std::fabs(std::fabs(c.point.y) - std::sqrt(0.75)) <= 1e-15);
    }
  CHECK(on_face == 2);
  CHECK(cells.unproved.empty());
}

TEST_CASE("subdivide_curve: the cell budget and the deadline stop it with what was reached") {
  CompileBudget unlimited;
  const ImplicitEquations eq = viviani();
  const CurveEnclosure enclosure = enclose_curve(eq, kSpace, unlimited);
  SubdivisionSettings few;
  few.max_cells = 10;
  try {
    subdivide_curve(eq, enclosure, unlimited, few);
    FAIL("expected geometry_too_complex");
  } catch (const GeometryError& e) {
    CHECK(e.code == "geometry_too_complex");
    CHECK(e.field == "domain");
    CHECK(std::string(e.what()).find("limit of 10 cells") != std::string::npos);
    CHECK(std::string(e.what()).find("11 cells examined") != std::string::npos);
  }
  // A deadline already past: the budget's check (every 64th call, per cell and per refinement) throws
  // compile_timeout, and the message says how far the subdivision got.
  CompileBudget late(CompileBudget::clock::now() - std::chrono::seconds(1));
  try {
    subdivide_curve(eq, enclosure, late);
    FAIL("expected compile_timeout");
  } catch (const GeometryError& e) {
    CHECK(e.code == "compile_timeout");
    CHECK(std::string(e.what()).find("(reached: ") != std::string::npos);
    CHECK(std::string(e.what()).find(" cells examined, ") != std::string::npos);
  }
}

}  // namespace curve_cells_test
