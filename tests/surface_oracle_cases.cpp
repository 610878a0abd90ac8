// `auto` against references computed by shared/cases/oracle.py for geometries of our own
// (tests/data/surface_*.json, each file records the command that made it): a sphere with poles
// (s_u = 0) and a seam, a torus (periodic in both parameters), a near-flat monkey saddle (k_n = 0
// at the origin) and a plane, and the benchmark surfaces S1, S2, S3 with points in the box twice
// their size (mostly edge and corner answers) and within 1% of them; far points and points on the
// surface are among them.
#include <doctest/doctest.h>

#include "surface_fixtures.hpp"

using namespace footpoint;
using namespace footpoint::test;

TEST_CASE("auto against oracle references") {
  for (const char* name : {"sphere", "torus", "monkey_saddle", "plane", "S1", "S2", "S3"}) {
    SUBCASE(name) {
      const nlohmann::json c = read_json(std::string(FOOTPOINT_TESTS_DIR) + "/data/surface_" + name + ".json");
      const auto& f = c.at("formulas");
      const auto g = make_surface(f.at("x"), f.at("y"), f.at("z"), c.at("domain").at("u").get<std::array<double, 2>>(),
                                  c.at("domain").at("v").get<std::array<double, 2>>());
      REQUIRE(g);
      REQUIRE(c.at("points").size() >= 7);
      for (const auto& point : c.at("points")) check_auto_against_oracle(*g, point);
    }
  }
}
