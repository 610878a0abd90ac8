// implicit/seeding/curve_enclosure: the interval enclosure keeps every cell that holds a point of the curve
// (checked against the curve's points in closed form) and drops cells the curve stays away from.
#include <doctest/doctest.h>

#include <cmath>
#include <set>
#include <vector>

#include "geometry/compile_budget.hpp"
#include "geometry/geometry_error.hpp"
#include "implicit/seeding/curve_cells.hpp"
#include "implicit/seeding/curve_enclosure.hpp"
#include "implicit_fixtures.hpp"

using namespace footpoint;
using namespace footpoint::test;

namespace {

std::set<std::uint64_t> keys(const std::vector<CellIndex>& cells) {
  std::set<std::uint64_t> k;
  for (const CellIndex& c : cells) k.insert(CellGrid::key(c));
  return k;
}

}  // namespace

TEST_CASE("CellGrid: cells tile the box, index_of finds the cell of a point, planar boxes keep z whole") {
  CellGrid grid{{{-2, -1, 0}, {2, 1, 0}}, {3, 2, 0}};
  CHECK(grid.edge().x == 0.5);
  CHECK(grid.edge().y == 0.5);
  CHECK(grid.max_edge() == 0.5);
  const Box3 last = grid.cell({7, 3, 0});
  CHECK(last.hi.x == 2.0);  // the last cell ends exactly on the box
  CHECK(last.lo.x == 1.5);
  for (const Vec3 x : {Vec3{-1.99, 0.7, 0}, Vec3{0.25, -0.25, 0}, Vec3{1.75, 0.99, 0}}) {
    const CellIndex c = grid.index_of(x);
    CHECK(grid.cell(c).contains(x));
  }
  CHECK(grid.index_of({5, 5, 0}) == CellIndex{7, 3, 0});  // clamped
  const CellGrid fine = grid.refined();
  CHECK(fine.bits == std::array<int, 3>{4, 3, 0});  // z has no extent: never split
}

TEST_CASE("enclose_curve: every point of the circle lies in a kept cell; far cells are dropped") {
  const ImplicitEquations eq = planar_equations("x^2+y^2-1");
  const Box3 box{{-2, -2, 0}, {2, 2, 0}};
  CompileBudget budget;
  const CurveEnclosure e = enclose_curve(eq, box, budget);
  REQUIRE(!e.cells.empty());
  CHECK(!e.truncated);
  CHECK(e.levels >= 5);
  const std::set<std::uint64_t> kept = keys(e.cells);
  for (int k = 0; k < 2000; ++k) {
    const double a = 2.0 * M_PI * k / 2000;
    CHECK(kept.count(CellGrid::key(e.grid.index_of({std::cos(a), std::sin(a), 0.0}))) == 1);
  }
  // A cell at the box's corner and one at the centre hold no point of the circle, and their interval
  // ranges say so at this size.
  CHECK(kept.count(CellGrid::key(e.grid.index_of({1.9, 1.9, 0.0}))) == 0);
  CHECK(kept.count(CellGrid::key(e.grid.index_of({0.0, 0.0, 0.0}))) == 0);
  // Every kept cell passed the exclusion test; the cells are far fewer than the grid's.
  for (const CellIndex& c : e.cells) CHECK(eq.may_vanish(e.grid.cell(c)));
  const double total = std::ldexp(1.0, e.grid.bits[0] + e.grid.bits[1]);
  CHECK(static_cast<double>(e.cells.size()) < 0.25 * total);
  // The size criterion: cells at most 1/48 of what remains (the circle's bounding box, ~2.8 across).
  CHECK(e.grid.max_edge() <= 2.0 * std::sqrt(2.0) / 48.0 * 1.5);
}

TEST_CASE("enclose_curve: nothing kept when the curve misses the box, and the cell budget truncates") {
  const ImplicitEquations eq = planar_equations("x^2+y^2-1");
  CompileBudget budget;
  CHECK(enclose_curve(eq, {{2, 2, 0}, {3, 3, 0}}, budget).cells.empty());
  EnclosureSettings small;
  small.max_cells = 64;
  const CurveEnclosure e = enclose_curve(eq, {{-2, -2, 0}, {2, 2, 0}}, budget, small);
  CHECK(e.truncated);
  CHECK(e.cells.size() * 8 > small.max_cells);
}

TEST_CASE("refine_cell: the children of a kept cell cover its part of the curve") {
  const ImplicitEquations eq = circle();
  const Box3 box{{-2, -2, 0}, {2, 2, 2}};
  CompileBudget budget;
  const CurveEnclosure e = enclose_curve(eq, box, budget);
  REQUIRE(!e.cells.empty());
  const CellGrid fine = e.grid.refined();
  std::size_t tests = 0;
  std::set<std::uint64_t> children;
  for (const CellIndex& c : e.cells) {
    std::vector<CellIndex> found;
    refine_cell(eq, e.grid, c, found, tests, budget);
    for (const CellIndex& f : found) {
      children.insert(CellGrid::key(f));
      const Box3 child = fine.cell(f), parent = e.grid.cell(c);
      CHECK(parent.contains(child.lo));
      CHECK(parent.contains(child.hi));
    }
  }
  CHECK(tests == 8 * e.cells.size());  // a spatial box splits along all three axes
  for (int k = 0; k < 1000; ++k)
    CHECK(children.count(CellGrid::key(fine.index_of(circle_point(2.0 * M_PI * k / 1000)))) == 1);
}

TEST_CASE("subdivide_curve: past max_cells the curve is refused as too intricate for its box") {
  // sin(40 x) + sin(40 y) = 0 has pieces every ~0.08 across [-30, 30]^2: far more cells than 500.
  const ImplicitEquations eq = planar_equations("sin(40*x)+sin(40*y)");
  const Box3 box{{-30, -30, 0}, {30, 30, 0}};
  SubdivisionSettings settings;
  settings.max_cells = 500;
  try {
    CompileBudget budget;
    (void)subdivide_curve(eq, enclose_curve(eq, box, budget), budget, settings);
    FAIL("expected geometry_too_complex");
  } catch (const GeometryError& e) {
    CHECK(e.code == "geometry_too_complex");
    CHECK(e.field == "domain");
  }
}
