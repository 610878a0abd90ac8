// The seeding of `auto` (seeding/surface_cells.hpp): the cell budget adapts to the surface, the
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
  const SurfaceSeedingOptions defaults;
  const ParametricSurface small = compile_with(example1(3), defaults);
  const Tally ts = tally(small.cells());
  INFO("S1: " << small.cells().cells().size() << " cells");
  CHECK(ts.coarse == 0);
  CHECK(ts.unresolved == 0);
  CHECK(small.cells().cells().size() < static_cast<std::size_t>(defaults.target_cells));

  const ParametricSurface large = compile_with(example1(25), defaults);
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
  capped.max_bytes = 1500 * SurfaceCells::bytes_per_cell();
  const GeometryDefinition def = example1(25);
  const ParametricSurface g = compile_with(def, capped);
  const Tally t = tally(g.cells());
  INFO(g.cells().cells().size() << " cells, " << t.unresolved << " unresolved");
  CHECK(g.cells().cells().size() <= 1500);
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
