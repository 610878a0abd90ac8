// `auto` against 50-digit references (tests/tools/gen_reference.py) for geometries of our own
// (tests/data/surface_*.json, each file records the command that makes it): a sphere with poles
// (s_u = 0) and a seam, a torus (periodic in both parameters), a near-flat monkey saddle (k_n = 0
// at the origin) and a plane, and the benchmark surfaces S1, S2, S3 with points in the box twice
// their size (mostly edge and corner answers) and within 1% of them; far points and points on the
// surface are among them. Then surfaces that need more than a fixed budget of cells, or whose points sit
// where a search easily goes wrong (each file's first points are the hardest):
//  - A1: [GSA] Example 1 over [-25,25]^2, folded and 8 periods each way (~16 parameter
//    pairs per foot point; the seeding's budget must grow to resolve it);
//  - fold: a sheet folded along curves (s_u x s_v = 0), where two minima lie a cell apart;
//  - fold_near: a sheet folded harder, and points nearer to it than the cells' model error, whose
//    nearest point lies in a cell whose model claims that the distance falls into a neighbour;
//  - wavy: bumps a few cells wide; two minima a cell apart;
//  - ripple: a corner answer next to an edge minimum within the corner cell's model error;
//  - cone: the apex and the seam u = 0 = 2pi, with feet next to the seam;
//  - S3_edge: edge answers next to an interior minimum within the models' error, from far and near;
//  - bump: a plane with a bump 0.01 wide that the cells' samples miss (its cells look flat): the
//    certificate's interval bounds find it, and the answer on it;
//  - large_coordinates: a torus around 2e4, points on it (the distance is rounding, ~1e-12) and
//    near it: the solve must not stop at the coordinates' relative tolerance.
#include <doctest/doctest.h>

#include "surface_fixtures.hpp"

using namespace footpoint;
using namespace footpoint::test;

TEST_CASE("auto against oracle references") {
  for (const char* name : {"sphere", "torus", "monkey_saddle", "plane", "S1", "S2", "S3", "A1", "fold",
                           "fold_near", "wavy", "ripple", "cone", "S3_edge", "bump", "large_coordinates"}) {
    SUBCASE(name) {
      const nlohmann::json c =
          read_json(std::string(FOOTPOINT_TESTS_DIR) + "/data/surface_" + name + ".json");
      const auto& f = c.at("formulas");
      const auto g =
          make_surface(f.at("x"), f.at("y"), f.at("z"), c.at("domain").at("u").get<std::array<double, 2>>(),
                       c.at("domain").at("v").get<std::array<double, 2>>());
      REQUIRE(g);
      REQUIRE(c.at("points").size() >= 7);
      for (const auto& point : c.at("points")) check_auto_against_oracle(*g, point);
    }
  }
}
