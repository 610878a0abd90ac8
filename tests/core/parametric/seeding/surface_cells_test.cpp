// The seeding of `auto` (parametric/seeding/surface_cells.hpp): the cell budget adapts to the surface, the
// memory cap holds and is reported, and `auto` stays right when the cap leaves cells unresolved.
#include <doctest/doctest.h>

#include <cmath>

#include "surface_fixtures.hpp"

using namespace footpoint;
using namespace footpoint::test;

namespace {

struct Tally {
  std::size_t fine = 0, coarse = 0, unresolved = 0;
};
Tally tally(const SurfaceCells& cells) {
  Tally t;
  for (const SurfaceCell& c : cells.cells()) {
    if (c.fine) CHECK(c.resolved);  // fine cells are resolved
    (c.fine ? t.fine : (c.resolved ? t.coarse : t.unresolved))++;
  }
  return t;
}

}  // namespace

TEST_CASE("the cell budget adapts: fine on [-3,3]^2, grown past the target on [-25,25]^2, all resolved") {
  // over [-25,25]^2 with z = sin(u + v) + u/1000: the formulas no longer repeat (the translation
  // (2π, -2π) of [GSA] Ex. 1 moves u), so every cell is searched
  const SurfaceSeedingOptions defaults;
  const ParametricSurface small = compile_with(example1(3), defaults);
  const Tally ts = tally(small.cells());
  INFO("S1: " << small.cells().cells().size() << " cells");
  CHECK(ts.coarse == 0);
  CHECK(ts.unresolved == 0);
  CHECK(small.cells().cells().size() < static_cast<std::size_t>(defaults.target_cells));

  GeometryDefinition unrepeated = example1(25);
  unrepeated.formulas[2].expression = "sin(u+v)+u/1000";
  const ParametricSurface large = compile_with(unrepeated, defaults);
  CHECK(large.self_covering().translations.empty());
  const Tally tl = tally(large.cells());
  const std::size_t n = large.cells().cells().size();
  INFO("[-25,25]^2: " << n << " cells, " << tl.fine << " fine, " << tl.coarse << " coarse");
  // a fixed budget of 4096 cells leaves every cell unresolved here
  CHECK(n > static_cast<std::size_t>(defaults.target_cells));
  CHECK(tl.unresolved == 0);
  CHECK(large.cells().memory_bytes() >= n * sizeof(SurfaceCell));
  CHECK(large.cells().memory_bytes() - large.cells().bounds_bytes() <=
        n * SurfaceCells::bytes_per_cell() + sizeof(SurfaceCells));
  CHECK(large.cells().memory_bytes() - large.cells().bounds_bytes() <=
        defaults.max_bytes + sizeof(SurfaceCells));
  CHECK(large.memory_bytes() > large.cells().memory_bytes());
}

TEST_CASE("the memory cap holds, is reported, and auto stays right on the cells it leaves unresolved") {
  SurfaceSeedingOptions capped;
  capped.max_bytes = 300 * SurfaceCells::bytes_per_cell();
  const GeometryDefinition def = example1(25);
  const ParametricSurface g = compile_with(def, capped);
  const Tally t = tally(g.cells());
  INFO(g.cells().cells().size() << " cells, " << t.unresolved << " unresolved");
  CHECK(g.cells().cells().size() <= 300);
  CHECK(g.cells().memory_bytes() - g.cells().bounds_bytes() <= capped.max_bytes + sizeof(SurfaceCells));
  CHECK(t.unresolved > 0);
  const nlohmann::json c = read_json(std::string(FOOTPOINT_TESTS_DIR) + "/data/surface_A1.json");
  for (const auto& point : c.at("points")) check_auto_against_oracle(g, point);
}

TEST_CASE("the domain's corners are kept with their points") {
  const auto g = make_surface("u", "v", "u*v", {-1, 2}, {3, 5});
  const auto& corners = g->cells().corners();
  const double expect[4][2] = {{-1, 3}, {2, 3}, {-1, 5}, {2, 5}};
  for (int k = 0; k < 4; ++k) {
    const SurfaceCorner& c = corners[static_cast<std::size_t>(k)];
    CHECK(c.finite);
    CHECK(c.u == expect[k][0]);
    CHECK(c.v == expect[k][1]);
    CHECK(c.jet.s.x == expect[k][0]);
    CHECK(c.jet.s.y == expect[k][1]);
    CHECK(c.jet.s.z == expect[k][0] * expect[k][1]);
  }
}

TEST_CASE(
    "a self-covering box: the cells leave out the translates, and every parameter point has a copy in a "
    "cell") {
  // [GSA] Ex. 1 over [-25,25]^2 repeats along (2π, -2π) (tests/core/formula/invariant_translations_test.cpp)
  const ParametricSurface g = compile_with(example1(25), SurfaceSeedingOptions{});
  const auto& translations = g.self_covering().translations;
  REQUIRE(translations.size() == 7);
  const ParamBox& box = g.domain();
  double area = 0.0;
  for (const SurfaceCell& c : g.cells().cells()) {
    CHECK_FALSE(g.self_covering().covered(box, c.u0, c.u1, c.v0, c.v1));
    area += (c.u1 - c.u0) * (c.v1 - c.v0);
  }
  // the box less its translate by (2π, -2π): an L of area 50^2 - (50 - 2π)^2, and the cells
  // that straddle its inner border
  const double l_shape = 2500.0 - (50.0 - 2.0 * M_PI) * (50.0 - 2.0 * M_PI);
  INFO(g.cells().cells().size() << " cells, area " << area << ", the L " << l_shape);
  CHECK(area >= l_shape);
  CHECK(area < 1.5 * l_shape);
  // every point of the box, stepped down by the translations, reaches a cell, and the surface's
  // point there is the same
  auto in_cell = [&](double u, double v) {
    for (const SurfaceCell& c : g.cells().cells())
      if (u >= c.u0 && u <= c.u1 && v >= c.v0 && v <= c.v1) return true;
    return false;
  };
  for (int k = 0; k < 500; ++k) {
    const double u0 = -25.0 + 50.0 * std::fmod(0.7548776662 * (k + 1), 1.0);
    const double v0 = -25.0 + 50.0 * std::fmod(0.5698402910 * (k + 1), 1.0);
    double u = u0, v = v0;
    for (int steps = 0; steps < 64 && !in_cell(u, v); ++steps) {
      bool moved = false;
      for (const auto& d : translations)
        if (box.contains(u - d[0], v - d[1])) {
          u -= d[0];
          v -= d[1];
          moved = true;
          break;
        }
      REQUIRE(moved);
    }
    REQUIRE(in_cell(u, v));
    const Vec3 a = g.formulas().point(u0, v0), b = g.formulas().point(u, v);
    CHECK(norm(a - b) <= 1e-13 * (1.0 + norm(a)));
  }
}
