// Results as users consume them: "fields" trims each result to the members named (the same
// numbers as the full answer, a fraction of the bytes), and stats counts each status.
#include <doctest/doctest.h>

#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "server_support.hpp"

using namespace footpoint::server;
using namespace footpoint::server::testing;
using json = nlohmann::json;

namespace {

const std::string kResultsSurface =
    R"J({"type":"parametric_surface","x":"u+v","y":"sin(u)+2*cos(v)","z":"sin(u+v)","domain":{"u":[-3,3],"v":[-3,3]}})J";

json post_results(httplib::Client& c, const std::string& path, const json& body, int status = 200) {
  auto r = c.Post(path, body.dump(), "application/json");
  REQUIRE(r);
  INFO(r->body);
  REQUIRE(r->status == status);
  return json::parse(r->body);
}

std::set<std::string> keys(const json& object) {
  std::set<std::string> k;
  for (const auto& [key, value] : object.items()) k.insert(key);
  return k;
}

json batch(int n) {
  json points = json::array();
  for (int i = 0; i < n; ++i) points.push_back({-3.0 + 6.0 * i / n, 2.0 - 0.003 * i, 0.5 + 0.001 * i});
  return points;
}

}  // namespace

TEST_CASE("fields: each result has the members named, in the result's order, with the full answer's values") {
  TestServer s;
  auto c = s.client();
  const std::string project = "/v1/geometries/" + create(*c, kResultsSurface) + "/project";
  const json points = batch(50);
  const json full = post_results(*c, project, {{"points", points}});

  const json trimmed =
      post_results(*c, project, {{"points", points}, {"fields", {"distance", "foot_point"}}});
  REQUIRE(trimmed["results"].size() == 50);
  for (std::size_t i = 0; i < 50; ++i) {
    const json& t = trimmed["results"][i];
    CHECK(keys(t) == std::set<std::string>{"foot_point", "distance"});
    CHECK(t["foot_point"] == full["results"][i]["foot_point"]);
    CHECK(t["distance"] == full["results"][i]["distance"]);
  }
  auto raw = c->Post(project, json{{"point", {1, 2, 2}}, {"fields", {"distance", "foot_point"}}}.dump(),
                     "application/json");
  REQUIRE(raw);
  CHECK(raw->body.find(R"("result":{"foot_point":[)") != std::string::npos);  // the result's order

  const json status_only =
      post_results(*c, project, {{"points", points}, {"fields", {"diagnostics.status", "parameters"}}});
  for (std::size_t i = 0; i < 50; ++i) {
    const json& t = status_only["results"][i];
    CHECK(keys(t) == std::set<std::string>{"parameters", "diagnostics"});
    CHECK(keys(t["diagnostics"]) == std::set<std::string>{"status"});
    CHECK(t["diagnostics"]["status"] == full["results"][i]["diagnostics"]["status"]);
    CHECK(t["parameters"] == full["results"][i]["parameters"]);
  }
  const json diagnostics = post_results(*c, project, {{"point", {1, 2, 2}}, {"fields", {"diagnostics"}}});
  CHECK(keys(diagnostics["result"]) == std::set<std::string>{"diagnostics"});
  CHECK(diagnostics["result"]["diagnostics"] ==
        post_results(*c, project, {{"point", {1, 2, 2}}})["result"]["diagnostics"]);
  CHECK(keys(diagnostics["result"]["diagnostics"]) ==
        std::set<std::string>{"method", "status", "converged", "iterations", "residual", "step_norm",
                              "starts", "location", "certificate", "multiplicity"});

  // minima and trace: named and asked for
  const json minima = post_results(
      *c, project, {{"point", {1, 2, 2}}, {"options", {{"all_minima", true}}}, {"fields", {"minima"}}});
  CHECK(keys(minima["result"]) == std::set<std::string>{"minima", "minima_truncated"});
  CHECK(minima["result"]["minima"].size() >= 1);

  // The stats are whole whatever the fields.
  CHECK(trimmed["stats"]["points"] == 50);
  CHECK(trimmed["stats"]["statuses"] == full["stats"]["statuses"]);
}

TEST_CASE("fields: the bytes of a big answer shrink to what was asked") {
  TestServer s;
  auto c = s.client();
  const std::string project = "/v1/geometries/" + create(*c, kResultsSurface) + "/project";
  const json points = batch(2000);
  auto full = c->Post(project, json{{"points", points}}.dump(), "application/json");
  auto trimmed = c->Post(project, json{{"points", points}, {"fields", {"foot_point", "distance"}}}.dump(),
                         "application/json");
  REQUIRE(full);
  REQUIRE(trimmed);
  const double share = static_cast<double>(trimmed->body.size()) / static_cast<double>(full->body.size());
  MESSAGE("2,000 points: " << full->body.size() << " bytes, with fields [foot_point, distance] "
                           << trimmed->body.size() << " (" << 100 * share << "%)");
  CHECK(share < 0.4);
}

TEST_CASE("fields: every bad value its 400, naming the field") {
  TestServer s;
  auto c = s.client();
  const std::string project = "/v1/geometries/" + create(*c, kResultsSurface) + "/project";
  struct Case {
    json fields;
    json options;
    const char* code;
    const char* field;
    const char* in_message;
  };
  const std::vector<Case> cases = {
      {{"distance", "distnce"},
       json::object(),
       "unknown_field",
       "fields[1]",
       "foot_point, parameters, distance"},
      {json::array(), json::object(), "wrong_shape", "fields", "fields is empty"},
      {"distance", json::object(), "wrong_type", "fields", ""},
      {{1}, json::object(), "wrong_type", "fields[0]", ""},
      {{"minima"}, json::object(), "conflicting_fields", "fields", "options.all_minima"},
      {{"distance", "trace"}, {{"all_minima", true}}, "conflicting_fields", "fields", "options.trace"},
  };
  for (const auto& k : cases) {
    CAPTURE(k.fields.dump());
    const json e =
        post_results(*c, project, {{"point", {1, 2, 2}}, {"fields", k.fields}, {"options", k.options}}, 400);
    CHECK(e["error"]["code"] == k.code);
    CHECK(e["error"]["field"] == k.field);
    CHECK(std::string(e["error"]["message"]).find(k.in_message) != std::string::npos);
  }
}

TEST_CASE("stats count each status that occurs; the counts add up to the points") {
  ServerConfig config;
  config.deadline = std::chrono::milliseconds(1);
  config.compile_deadline = std::chrono::milliseconds(60000);  // compile fully, project against 1 ms
  TestServer s(config);
  auto c = s.client();
  const std::string project = "/v1/geometries/" + create(*c, kResultsSurface) + "/project";
  // Two points near the surface, one far beyond max_distance.
  const json near_far = post_results(
      *c, project,
      {{"points", {{1, 2, 2}, {0.5, 1.5, 0.2}, {100, 100, 100}}}, {"options", {{"max_distance", 5}}}});
  CHECK(near_far["stats"]["statuses"] == json{{"converged", 2}, {"beyond_max_distance", 1}});
  CHECK(near_far["stats"]["converged"] == 2);
  // Under a 1 ms deadline, a big batch leaves points unsolved: they are counted too.
  const json late = post_results(*c, project, {{"points", batch(20000)}});
  long total = 0;
  for (const auto& [status, count] : late["stats"]["statuses"].items()) {
    CHECK(count.get<long>() > 0);
    total += count.get<long>();
  }
  CHECK(total == 20000);
  CHECK(late["stats"]["statuses"]["deadline_exceeded"].get<long>() > 0);
}

namespace {

// Every member that describes the foot point is null (location unknown) in a result without one.
void check_no_answer(const json& result) {
  INFO(result.dump());
  CHECK(result["foot_point"].is_null());
  CHECK(result["distance"].is_null());
  const json& d = result["diagnostics"];
  CHECK(d["residual"].is_null());
  CHECK(d["step_norm"].is_null());
  CHECK(d["location"] == "unknown");
  CHECK(d["multiplicity"].is_null());
  CHECK((d["certificate"].is_null() || d["certificate"]["gap"].is_null()));
}

}  // namespace

TEST_CASE("answers without a foot point: residual, step_norm and location say nothing") {
  {
    TestServer s;
    auto c = s.client();
    const std::string sphere =
        "/v1/geometries/" +
        create(*c, R"J({"type":"parametric_surface","x":"cos(u)*sin(v)","y":"sin(u)*sin(v)","z":"cos(v)",
                        "domain":{"u":[0,"2*_pi"],"v":[0,"_pi"]}})J") +
        "/project";
    // Beyond max_distance; beyond the range where squared distances are finite (non_finite).
    const json beyond = post_results(*c, sphere, {{"point", {0, 0, 50}}, {"options", {{"max_distance", 5}}}});
    CHECK(beyond["result"]["diagnostics"]["status"] == "beyond_max_distance");
    check_no_answer(beyond["result"]);
    const json far = post_results(*c, sphere, {{"point", {1e160, 0, 0}}});
    CHECK(far["result"]["diagnostics"]["status"] == "non_finite");
    check_no_answer(far["result"]);
  }
  // Points a 1 ms deadline leaves unsolved.
  ServerConfig config;
  config.deadline = std::chrono::milliseconds(1);
  config.compile_deadline = std::chrono::milliseconds(60000);
  TestServer s(config);
  auto c = s.client();
  const std::string surface = "/v1/geometries/" + create(*c, kResultsSurface) + "/project";
  const json late = post_results(*c, surface, {{"points", batch(20000)}});
  int unsolved = 0;
  for (const json& r : late["results"]) {
    if (r["diagnostics"]["status"] != "deadline_exceeded") continue;
    ++unsolved;
    check_no_answer(r);
  }
  CHECK(unsolved > 0);
}
