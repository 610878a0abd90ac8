// What the documentation says against what the server does: the functions of the formula
// language (core, openapi.yaml's Formula x-functions, docs/formulas.md's table), and
// GET /v1/methods with each method's full citations, options and statuses.
#include <doctest/doctest.h>

#include <algorithm>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "formula/syntax.hpp"
#include "openapi_text.hpp"
#include "server_support.hpp"

using namespace footpoint::server;
using namespace footpoint::server::testing;
using json = nlohmann::json;

namespace {

// The body of GET `path` on a server of its own, which answers 200.
std::string get_ok(const std::string& path) {
  TestServer s;
  auto c = s.client();
  auto r = c->Get(path);
  REQUIRE(r);
  REQUIRE(r->status == 200);
  return r->body;
}

}  // namespace

TEST_CASE("the formula language's functions: the core's, openapi.yaml's and docs/formulas.md's agree") {
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

  const std::string doc = read_text_file(FOOTPOINT_SOURCE_DIR "/docs/formulas.md");
  const auto begin = doc.find("<!-- formulas:begin -->"), end = doc.find("<!-- formulas:end -->");
  REQUIRE(begin != std::string::npos);
  REQUIRE(end > begin);
  const std::string formulas = doc.substr(begin, end - begin);
  for (const auto& f : core) {
    CAPTURE(f);
    CHECK(formulas.find("`" + f + "(") != std::string::npos);
  }
}

TEST_CASE("GET /v1/methods: each method's full citations, the options it reads, the statuses it reports") {
  const json list = json::parse(get_ok("/v1/methods"));
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
      if (m["name"] == "auto" &&
          (type["type"] == "parametric_surface" || type["type"] == "bspline_surface")) {
        CHECK(m["options"] == json::array({"tolerance", "max_iterations", "initial", "all_minima", "trace",
                                           "max_distance", "certify", "max_minima"}));
      } else if (m["name"] == "auto") {
        CHECK(m["options"] == json::array({"tolerance", "max_iterations", "all_minima", "trace",
                                           "max_distance", "certify", "max_minima"}));
      }
    }
  CHECK(methods == 27);
  // Hu and Wallner's method on implicit surfaces cites its paper and the one its steps follow.
  bool hu_wallner = false;
  for (const auto& type : list["geometry_types"])
    for (const auto& m : type["methods"])
      if (type["type"] == "implicit_surface" && m["name"] == "hu_wallner") {
        hu_wallner = true;
        CHECK(m["citations"].size() == 2);
        CHECK(m["citations"][0].get<std::string>().find("Hu, J. Wallner") != std::string::npos);
      }
  CHECK(hu_wallner);
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

TEST_CASE("every footpoint_* metric GET /metrics exports is in docs/operations.md's metrics table") {
  const std::string metrics = get_ok("/metrics");
  const std::string readme = read_text_file(FOOTPOINT_SOURCE_DIR "/docs/operations.md");
  const auto begin = readme.find("## Metrics"), end = readme.find("## Logs");
  REQUIRE(begin != std::string::npos);
  REQUIRE(end > begin);
  // The names the table gives: `name` and, in a row of several, `…_tail` for the name before it
  // with as many trailing parts replaced as the tail has.
  std::vector<std::string> documented;
  std::istringstream table(readme.substr(begin, end - begin));
  const std::regex token("`(footpoint_[a-z_]+|…_[a-z_]+)");
  for (std::string line; std::getline(table, line);) {
    std::string previous;
    for (auto it = std::sregex_iterator(line.begin(), line.end(), token); it != std::sregex_iterator();
         ++it) {
      std::string name = (*it)[1];
      if (name.rfind("footpoint_", 0) != 0 && !previous.empty()) {
        const std::string tail = name.substr(name.find('_'));  // "_misses_total"
        std::string stem = previous;
        for (char ch : tail)
          if (ch == '_') stem.erase(stem.rfind('_'));
        name = stem + tail;
      }
      documented.push_back(name);
      previous = name;
    }
  }
  std::istringstream exported(metrics);
  int families = 0;
  for (std::string line; std::getline(exported, line);) {
    if (line.rfind("# TYPE footpoint_", 0) != 0) continue;
    const std::string name = line.substr(7, line.find(' ', 7) - 7);
    CAPTURE(name);
    ++families;
    CHECK(std::find(documented.begin(), documented.end(), name) != documented.end());
  }
  CHECK(families > 10);
}
