// Every surface case of the papers (tests/data/papers/public_cases.json) through `auto`: the global nearest
// point over the closed domain, against the 50-digit references.
#include <doctest/doctest.h>

#include "surface_fixtures.hpp"

using namespace footpoint;
using namespace footpoint::test;

TEST_CASE("auto answers every surface case of public_cases.json") {
  const nlohmann::json cases = read_json(FOOTPOINT_CASES_FILE);
  int points = 0;
  for (const auto& c : cases.at("cases")) {
    if (c.at("kind") != "surface") continue;
    SUBCASE(c.at("id").get<std::string>().c_str()) {
      const auto& f = c.at("formulas");
      const auto g =
          make_surface(f.at("x"), f.at("y"), f.at("z"), c.at("domain").at("u").get<std::array<double, 2>>(),
                       c.at("domain").at("v").get<std::array<double, 2>>());
      REQUIRE(g);
      for (const auto& point : c.at("points")) {
        check_auto_against_oracle(*g, point);
        ++points;
      }
    }
  }
  CHECK(points > 0);
}
