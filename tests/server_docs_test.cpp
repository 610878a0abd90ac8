// What the documentation says against what the server does: the functions of the formula
// language (core, openapi.yaml's Formula x-functions, the README's Formulas table), and
// GET /v1/methods with each method's full citations, options and statuses.
#include <doctest/doctest.h>

#include <algorithm>
#include <regex>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "formula/syntax.hpp"
#include "openapi_text.hpp"
#include "server_support.hpp"

using namespace footpoint::server;
using namespace footpoint::server::testing;
using json = nlohmann::json;

TEST_CASE("the functions of the formula language: the core's, openapi.yaml's and the README's are the same") {
  std::vector<std::string> core;
  for (const auto& f : footpoint::formula::function_signatures()) core.emplace_back(f.name);
  const std::string openapi(openapi_text());
  std::smatch m;
  REQUIRE(std::regex_search(openapi, m, std::regex("x-functions: \\[([^\\]]*)\\]")));
  std::vector<std::string> documented;
  const std::string list = m[1];
  const std::regex name("[a-z0-9]+");
  for (auto it = std::sregex_iterator(list.begin(), list.end(), name); it != std::sregex_iterator(); ++it)
    documented.push_back(it->str());
  CHECK(documented == core);

  const std::string readme = read_text_file(FOOTPOINT_SOURCE_DIR "/README.md");
  const auto begin = readme.find("<!-- formulas:begin -->"), end = readme.find("<!-- formulas:end -->");
  REQUIRE(begin != std::string::npos);
  REQUIRE(end > begin);
  const std::string formulas = readme.substr(begin, end - begin);
  for (const auto& f : core) {
    CAPTURE(f);
    CHECK(formulas.find("`" + f + "(") != std::string::npos);
  }
}

TEST_CASE("GET /v1/methods: each method's full citations, the options it reads, the statuses it reports") {
  TestServer s;
  auto c = s.client();
  auto r = c->Get("/v1/methods");
  REQUIRE(r);
  REQUIRE(r->status == 200);
  const json list = json::parse(r->body);
  std::size_t methods = 0;
  for (const auto& type : list["geometry_types"])
    for (const auto& m : type["methods"]) {
      CAPTURE(m["name"]);
      ++methods;
      CHECK(m["statuses"].size() >= 2);
      CHECK(std::find(m["statuses"].begin(), m["statuses"].end(), "deadline_exceeded") !=
            m["statuses"].end());
      CHECK(m["options"].size() >= 5);
      CHECK(m["citations"].empty() == m["paper"].get<std::string>().empty());
      // auto on surfaces also takes a warm start
      if (m["name"] == "auto" && type["type"] == "parametric_surface") {
        CHECK(m["options"] == json::array({"tolerance", "max_iterations", "initial", "all_minima", "trace",
                                           "max_distance", "certify", "max_minima"}));
      } else if (m["name"] == "auto") {
        CHECK(m["options"] == json::array({"tolerance", "max_iterations", "all_minima", "trace",
                                           "max_distance", "certify", "max_minima"}));
      }
    }
  CHECK(methods == 18);
  const json& gsa = list["geometry_types"][0]["methods"][1];
  CHECK(gsa["name"] == "gsa");
  CHECK(gsa["citations"] ==
        json::array(
            {"Xiaowu Li, Zhinan Wu, Feng Pan, Juan Liang, Jiafeng Zhang, Linke Hou. A Geometric Strategy "
             "Algorithm for Orthogonal Projection onto a Parametric Surface. Journal of Computer Science and "
             "Technology, Springer and Science Press, 2019"}));
  CHECK(gsa["options"] == json::array({"tolerance", "max_iterations", "initial", "trace", "certify"}));
  CHECK(gsa["statuses"] == json::array({"converged", "max_iterations", "diverged", "non_finite", "degenerate",
                                        "outside_domain", "deadline_exceeded"}));
}
