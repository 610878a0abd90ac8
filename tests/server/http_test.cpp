// The HTTP service end to end: an in-process server on an ephemeral port, an httplib client (and
// raw sockets for what that client cannot send). Every endpoint, every error class, the cache,
// batches against single points, thread-count independence, deadlines, load shedding and
// graceful shutdown.
#include <doctest/doctest.h>

#include <atomic>
#include <cmath>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "json_writer.hpp"
#include "server_support.hpp"

using namespace footpoint;
using namespace footpoint::server;
using namespace footpoint::server::testing;
using json = nlohmann::json;

namespace {

// [GSA] Example 1 (public case paperA_ex1).
const char* const kSurfaceA1 =
    R"J({"type":"parametric_surface","x":"u+v","y":"sin(u)+2*cos(v)","z":"sin(u+v)","domain":{"u":[-25,25],"v":[-25,25]}})J";
// Hybrid paper, counterexample 1: a paraboloid over [-2,2]^2.
const char* const kParaboloid =
    R"J({"type":"parametric_surface","x":"u","y":"v","z":"1+u^2+v^2","domain":{"u":[-2,2],"v":[-2,2]}})J";
// [Curve] Example 1.
const char* const kCurveC1 =
    R"J({"type":"implicit_curve","equations":["x^2/9+y^2/16+z^2/9-1","x^2+y^2-4*z"],"domain":{"x":[-300,300],"y":[-300,300],"z":[-300,300]}})J";
const char* const kPlanarCircle =
    R"J({"type":"parametric_curve","x":"R*cos(t)","y":"R*sin(t)","domain":{"t":[0,6]},"constants":{"R":2}})J";

bool is_hex(const std::string& s, std::size_t length) {
  if (s.size() != length) return false;
  for (char ch : s)
    if (!((ch >= '0' && ch <= '9') || (ch >= 'a' && ch <= 'f'))) return false;
  return true;
}

json case_by_id(const std::string& id) {
  const json all = json::parse(read_text_file(FOOTPOINT_CASES_FILE));
  for (const auto& c : all["cases"])
    if (c["id"] == id) return c;
  FAIL("no case " << id);
  return {};
}

json post_json(httplib::Client& c, const std::string& path, const std::string& body, int expected_status) {
  auto r = c.Post(path, body, "application/json");
  REQUIRE(r);
  INFO(path << " " << body.substr(0, 300) << " -> " << r->body.substr(0, 500));
  REQUIRE(r->status == expected_status);
  return r->body.empty() ? json() : json::parse(r->body);
}

std::string http_points_body(const std::vector<std::array<double, 3>>& pts, int dim = 3,
                             const std::string& extra = "") {
  JsonWriter w;
  w.begin_object();
  w.key("points");
  w.begin_array();
  for (const auto& p : pts) {
    w.begin_array();
    for (int k = 0; k < dim; ++k) w.number(p[k]);
    w.end_array();
  }
  w.end_array();
  w.end_object();
  std::string body = w.take();
  if (!extra.empty()) body.insert(body.size() - 1, "," + extra);
  return body;
}

std::vector<std::array<double, 3>> random_points(std::size_t n, unsigned seed, double lo, double hi) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> d(lo, hi);
  std::vector<std::array<double, 3>> pts(n);
  for (auto& p : pts) p = {d(rng), d(rng), d(rng)};
  return pts;
}

// Waits until the metrics show the sample `series value`.
void wait_metric(httplib::Client& c, const std::string& series, long value) {
  const std::string needle = "\n" + series + " " + std::to_string(value) + "\n";
  for (int i = 0; i < 2000; ++i) {
    auto r = c.Get("/metrics");
    REQUIRE(r);
    if (r->body.find(needle) != std::string::npos) return;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  FAIL("never saw " << series << " " << value);
}

void wait_in_flight(httplib::Client& c, int n) { wait_metric(c, "footpoint_http_requests_in_flight", n); }

double metric(httplib::Client& c, const std::string& series) {
  auto r = c.Get("/metrics");
  REQUIRE(r);
  const auto at = r->body.find("\n" + series + " ");
  REQUIRE_MESSAGE(at != std::string::npos, series);
  return std::stod(r->body.substr(at + series.size() + 2));
}

}  // namespace

TEST_CASE("every endpoint answers as documented") {
  TestServer s;
  auto c = s.client();

  auto health = c->Get("/healthz");
  REQUIRE(health);
  CHECK(health->status == 200);
  CHECK(json::parse(health->body) == json{{"status", "ok"}});
  CHECK(is_hex(health->get_header_value("X-Request-Id"), 16));
  CHECK(health->get_header_value("Content-Type") == "application/json");

  auto ready = c->Get("/readyz");
  REQUIRE(ready);
  CHECK(ready->status == 200);
  CHECK(json::parse(ready->body)["status"] == "ready");

  auto spec = c->Get("/openapi.yaml");
  REQUIRE(spec);
  CHECK(spec->status == 200);
  CHECK(spec->get_header_value("Content-Type") == "application/yaml");
  CHECK(spec->body == read_text_file(FOOTPOINT_SOURCE_DIR "/openapi.yaml"));

  auto methods = c->Get("/v1/methods");
  REQUIRE(methods);
  CHECK(methods->status == 200);
  const json m = json::parse(methods->body);
  REQUIRE(m["geometry_types"].size() == 6);
  for (const auto& t : m["geometry_types"]) {
    CAPTURE(t["type"]);
    REQUIRE(!t["methods"].empty());
    CHECK(t["methods"][0]["name"] == "auto");
  }

  // Create: 201, then 200 for the same definition (same id), whatever its key order.
  auto created = c->Post("/v1/geometries", kSurfaceA1, "application/json");
  REQUIRE(created);
  CHECK(created->status == 201);
  const json g = json::parse(created->body);
  const std::string id = g["geometry_id"];
  CHECK(is_hex(id, 32));
  CHECK(created->get_header_value("Location") == "/v1/geometries/" + id);
  CHECK(g["point_dim"] == 3);
  CHECK(g["num_params"] == 2);
  const json reordered = json::parse(kSurfaceA1);
  std::string reordered_text = R"J({"domain":{"v":[-25,25],"u":[-25,25]},"z":"sin(u + v)",)J"
                               R"J("y":"sin(u)+2*cos(v)","x":"u+v","type":"parametric_surface"})J";
  auto again = c->Post("/v1/geometries", reordered_text, "application/json");
  REQUIRE(again);
  CHECK(again->status == 200);
  CHECK(json::parse(again->body)["geometry_id"] == id);

  // Read it back: the definition and the cache statistics.
  auto info = c->Get("/v1/geometries/" + id);
  REQUIRE(info);
  CHECK(info->status == 200);
  const json gi = json::parse(info->body);
  CHECK(gi["definition"] == reordered);
  CHECK(gi["cache"]["hits"].get<int>() >= 1);
  CHECK(gi["cache"]["memory_bytes"].get<long>() > 0);
  auto head = c->Head("/v1/geometries/" + id);
  REQUIRE(head);
  CHECK(head->status == 200);
  CHECK(head->body.empty());

  // Project the paper's point: the global nearest point of the reference case.
  const json ref = case_by_id("paperA_ex1")["points"][0];
  const json one = post_json(*c, "/v1/geometries/" + id + "/project", json{{"point", ref["p"]}}.dump(), 200);
  CHECK(one["geometry_id"] == id);
  const json& r = one["result"];
  CHECK(r["diagnostics"]["status"] == "converged");
  CHECK(r["diagnostics"]["converged"] == true);
  CHECK(r["diagnostics"]["method"] == "auto");
  const double d_ref = ref["oracle"]["distance"];
  CHECK(std::abs(r["distance"].get<double>() - d_ref) <= 1e-9 * d_ref);
  for (int k = 0; k < 3; ++k)
    CHECK(std::abs(r["foot_point"][k].get<double>() - ref["oracle"]["foot"][k].get<double>()) <= 1e-8);
  CHECK(r["parameters"].size() == 2);
  CHECK(one["stats"]["points"] == 1);
  CHECK(one["stats"]["converged"] == 1);

  // One-shot with the definition inline: same id, same answer to the last bit.
  const json inline_req = {{"geometry", json::parse(kSurfaceA1)}, {"point", ref["p"]}};
  const json two = post_json(*c, "/v1/project", inline_req.dump(), 200);
  CHECK(two["geometry_id"] == id);
  CHECK(two["result"] == one["result"]);

  // A batch with every option.
  const json batch = post_json(*c, "/v1/geometries/" + id + "/project",
                               R"J({"points":[[1,2,2],[0,0,3]],"method":"auto",
                                   "options":{"all_minima":true,"trace":true,"tolerance":0,"max_iterations":0}})J",
                               200);
  REQUIRE(batch["results"].size() == 2);
  // all_minima may end on a different last iterate of the same minimum: equal to rounding.
  CHECK(std::abs(batch["results"][0]["distance"].get<double>() - d_ref) <= 1e-12 * d_ref);
  CHECK(!batch["results"][0]["minima"].empty());
  CHECK(batch["results"][0].contains("trace"));

  // An implicit curve (no parameters) and a planar parametric curve (2-D points).
  const json curve = post_json(
      *c, "/v1/project", std::string(R"J({"geometry":)J") + kCurveC1 + R"J(,"point":[217,273,129]})J", 200);
  CHECK_FALSE(curve["result"].contains("parameters"));
  CHECK(std::abs(curve["result"]["distance"].get<double>() - 368.57191569417705) <= 1e-9 * 368.6);
  const json circle = post_json(
      *c, "/v1/project", std::string(R"J({"geometry":)J") + kPlanarCircle + R"J(,"point":[3,0.5]})J", 200);
  CHECK(circle["result"]["foot_point"].size() == 2);
  CHECK(std::abs(circle["result"]["distance"].get<double>() - (std::hypot(3.0, 0.5) - 2.0)) <= 1e-12);

  // Delete: 204, then 404 with the code that tells the client to post the definition again.
  auto del = c->Delete("/v1/geometries/" + id);
  REQUIRE(del);
  CHECK(del->status == 204);
  auto gone = c->Get("/v1/geometries/" + id);
  REQUIRE(gone);
  CHECK(gone->status == 404);
  CHECK(json::parse(gone->body)["error"]["code"] == "geometry_not_found");
  const json lost = post_json(*c, "/v1/geometries/" + id + "/project", R"J({"point":[1,2,2]})J", 404);
  CHECK(lost["error"]["code"] == "geometry_not_found");
  auto del2 = c->Delete("/v1/geometries/" + id);
  REQUIRE(del2);
  CHECK(del2->status == 404);

  // Metrics: Prometheus text with the series the deployment docs list.
  auto metrics = c->Get("/metrics");
  REQUIRE(metrics);
  CHECK(metrics->status == 200);
  CHECK(metrics->get_header_value("Content-Type").rfind("text/plain; version=0.0.4", 0) == 0);
  for (const char* series :
       {"footpoint_http_requests_total{route=\"/v1/geometries\",status=\"201\"} 1",
        "footpoint_http_requests_total{route=\"/v1/geometries/{id}\",status=\"204\"} 1",
        "footpoint_http_request_duration_seconds_bucket{route=\"/v1/project\",le=\"+Inf\"} 3",
        "footpoint_points_projected_total 6", "footpoint_projections_total{status=\"converged\"} 6",
        "footpoint_geometry_compile_seconds_count 3", "footpoint_geometry_cache_entries 2",
        "footpoint_geometry_cache_evictions_total 0", "footpoint_worker_threads 2",
        "footpoint_http_requests_in_flight 0", "footpoint_shutting_down 0"})
    CHECK_MESSAGE(metrics->body.find(series) != std::string::npos, std::string(series));
}

TEST_CASE("HTTP answers equal the core's answers to the last bit") {
  TestServer s;
  auto c = s.client();
  const std::string id = create(*c, kSurfaceA1);
  const auto geometry = s.server().cache().find(id);
  REQUIRE(geometry);
  const auto pts = random_points(200, 7, -6, 6);
  const json batch = post_json(*c, "/v1/geometries/" + id + "/project", http_points_body(pts), 200);
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const ProjectionResult direct = geometry->project(pts[i].data(), "auto", Options{}).value();
    const json& r = batch["results"][i];
    CHECK(r["distance"].get<double>() == direct.distance);
    for (int k = 0; k < 3; ++k) CHECK(r["foot_point"][k].get<double>() == direct.foot[k]);
    for (int k = 0; k < 2; ++k) CHECK(r["parameters"][k].get<double>() == direct.params[k]);
    CHECK(r["diagnostics"]["iterations"] == direct.summary.iterations);
    CHECK(r["diagnostics"]["status"] == to_string(direct.summary.status));
  }
}

TEST_CASE("a batch of 10,000 points equals the same points sent one by one") {
  TestServer s;
  auto c = s.client();
  const std::string id = create(*c, kParaboloid);
  const auto pts = random_points(10000, 11, -3, 3);
  const json batch = post_json(*c, "/v1/geometries/" + id + "/project", http_points_body(pts), 200);
  REQUIRE(batch["results"].size() == pts.size());
  CHECK(batch["stats"]["points"] == 10000);
  std::size_t differ = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    JsonWriter w;
    w.begin_object();
    w.key("point");
    w.begin_array();
    for (double x : pts[i]) w.number(x);
    w.end_array();
    w.end_object();
    auto r = c->Post("/v1/geometries/" + id + "/project", w.str(), "application/json");
    REQUIRE(r);
    REQUIRE(r->status == 200);
    if (json::parse(r->body)["result"] != batch["results"][i]) ++differ;
  }
  CHECK(differ == 0);
}

TEST_CASE("results do not depend on the number of worker threads") {
  const auto pts = random_points(1000, 5, -8, 8);
  const std::string body = http_points_body(pts);
  const std::string minima_body =
      http_points_body(random_points(40, 6, -8, 8), 3, R"J("options":{"all_minima":true})J");
  std::vector<json> answers, minima;
  for (unsigned threads : {1u, 2u, 4u}) {
    ServerConfig config;
    config.threads = threads;
    TestServer s(config);
    auto c = s.client();
    const std::string id = create(*c, kSurfaceA1);
    answers.push_back(post_json(*c, "/v1/geometries/" + id + "/project", body, 200)["results"]);
    minima.push_back(post_json(*c, "/v1/geometries/" + id + "/project", minima_body, 200)["results"]);
  }
  for (std::size_t t = 1; t < answers.size(); ++t) {
    CAPTURE(t);
    REQUIRE(answers[t].size() == pts.size());
    std::size_t differ = 0;
    for (std::size_t i = 0; i < pts.size(); ++i) differ += answers[t][i] != answers[0][i];
    CHECK(differ == 0);
    CHECK(minima[t] == minima[0]);
  }
  for (const auto& r : answers[0]) CHECK(r["diagnostics"]["status"] == "converged");
}

TEST_CASE("every error class: status, code and field, and the server keeps answering") {
  ServerConfig config;
  config.max_points = 100;
  config.max_body_bytes = std::size_t{64} * 1024;
  config.max_formula_length = 200;
  TestServer s(config);
  auto c = s.client();
  const std::string id = create(*c, kSurfaceA1);
  const std::string project = "/v1/geometries/" + id + "/project";
  const std::string good_point = R"J({"point":[1,2,2]})J";
  const json good_answer = post_json(*c, project, good_point, 200)["result"];

  struct Case {
    const char* name;
    std::string method, path, content_type, body;
    int status;
    const char* code;
    const char* field;  // nullptr: no field expected
  };
  auto surface_with = [](const std::string& member, const std::string& value) {
    json d = json::parse(kSurfaceA1);
    d[member] = json::parse(value);
    return d.dump();
  };
  const std::string big_points = [] {
    std::string b = R"J({"points":[)J";
    for (int i = 0; i < 101; ++i) b += std::string(i ? "," : "") + "[1,2,3]";
    return b + "]}";
  }();
  const std::vector<Case> cases = {
      {"malformed JSON", "POST", project, "application/json", R"J({"point":[1,2,)J", 400, "malformed_json",
       nullptr},
      {"NaN literal", "POST", project, "application/json", R"J({"point":[1,NaN,2]})J", 400, "malformed_json",
       nullptr},
      {"wrong type in a batch", "POST", project, "application/json", R"J({"points":[[1,2,3],[1,2,"x"]]})J",
       400, "wrong_type", "points[1][2]"},
      {"1e400", "POST", project, "application/json", R"J({"point":[1,2,1e400]})J", 400, "number_out_of_range",
       "point[2]"},
      {"2-D point on a surface", "POST", project, "application/json", R"J({"point":[1,2]})J", 400,
       "wrong_dimension", "point"},
      {"mixed dimensions", "POST", project, "application/json", R"J({"points":[[1,2,3],[1,2,3],[1,2]]})J",
       400, "wrong_dimension", "points[2]"},
      {"empty batch", "POST", project, "application/json", R"J({"points":[]})J", 400, "empty_batch",
       "points"},
      {"missing point", "POST", project, "application/json", R"J({"method":"auto"})J", 400, "missing_field",
       "point"},
      {"unknown method", "POST", project, "application/json", R"J({"point":[1,2,2],"method":"magic"})J", 400,
       "unknown_method", "method"},
      {"negative tolerance", "POST", project, "application/json",
       R"J({"point":[1,2,2],"options":{"tolerance":-1}})J", 400, "invalid_option", "options.tolerance"},
      {"absurd max_iterations", "POST", project, "application/json",
       R"J({"point":[1,2,2],"options":{"max_iterations":1000000000}})J", 400, "invalid_option",
       "options.max_iterations"},
      {"start of the wrong size", "POST", project, "application/json",
       R"J({"point":[1,2,2],"options":{"initial":[1,2,3]}})J", 400, "wrong_dimension", "options.initial"},
      {"unknown geometry type", "POST", "/v1/geometries", "application/json", R"J({"type":"torus"})J", 400,
       "unknown_geometry_type", "type"},
      {"geometry missing on /v1/project", "POST", "/v1/project", "application/json", good_point, 400,
       "missing_field", "geometry"},
      {"body is not an object", "POST", "/v1/geometries", "application/json", "[]", 400, "wrong_type",
       "body"},
      {"unknown geometry id", "POST", "/v1/geometries/0123456789abcdef0123456789abcdef/project",
       "application/json", good_point, 404, "geometry_not_found", "id"},
      {"unknown route", "GET", "/v2/nothing", "", "", 404, "route_not_found", nullptr},
      {"GET on a POST route", "GET", "/v1/project", "", "", 405, "method_not_allowed", nullptr},
      {"DELETE on /healthz", "DELETE", "/healthz", "", "", 405, "method_not_allowed", nullptr},
      {"too many points", "POST", project, "application/json", big_points, 413, "too_many_points", "points"},
      {"body over the limit", "POST", project, "application/json",
       R"J({"point":[1,2,2],"method":")J" + std::string(70000, 'a') + "\"}", 413, "body_too_large", nullptr},
      {"text/plain body", "POST", project, "text/plain", good_point, 415, "unsupported_media_type", nullptr},
      {"formula syntax", "POST", "/v1/geometries", "application/json", surface_with("z", R"J("sin(u+")J"),
       422, "formula_syntax", "z"},
      {"unknown variable", "POST", "/v1/geometries", "application/json", surface_with("x", R"J("u+w")J"), 422,
       "unknown_variable", "x"},
      {"reversed domain", "POST", "/v1/geometries", "application/json",
       surface_with("domain", R"J({"u":[1,-1],"v":[0,1]})J"), 422, "bad_domain", "domain.u"},
      {"over-long formula", "POST", "/v1/geometries", "application/json",
       surface_with("y", "\"" + std::string(150, 'u') + "+" + std::string(150, 'v') + "\""), 422,
       "formula_too_long", "y"},
      {"inline geometry that does not compile", "POST", "/v1/project", "application/json",
       R"J({"point":[1,2,3],"geometry":)J" + surface_with("x", R"J("u**2")J") + "}", 422, "formula_syntax",
       "geometry.x"},
  };
  for (const auto& k : cases) {
    CAPTURE(k.name);
    httplib::Result r{nullptr, httplib::Error::Unknown};
    if (k.method == "POST")
      r = c->Post(k.path, k.body, k.content_type);
    else if (k.method == "GET")
      r = c->Get(k.path);
    else
      r = c->Delete(k.path);
    REQUIRE(r);
    CHECK(r->status == k.status);
    const json e = json::parse(r->body);
    CHECK(e["error"]["code"] == k.code);
    CHECK(e["error"]["message"].is_string());
    if (k.field) CHECK(e["error"]["field"] == k.field);
    CHECK(r->get_header_value("Content-Type") == "application/json");
    CHECK_FALSE(r->get_header_value("X-Request-Id").empty());
    if (k.status == 405) CHECK_FALSE(r->get_header_value("Allow").empty());
    if (k.status == 422 && std::string(k.code) == "formula_syntax")
      CHECK(e["error"]["position"].get<int>() >= 0);
    // The server still answers correctly, on a fresh connection too.
    c = s.client();
    CHECK(post_json(*c, project, good_point, 200)["result"] == good_answer);
  }

  // Framing problems httplib's client would not produce, on raw connections.
  const std::string host = "Host: 127.0.0.1\r\n";
  struct Raw {
    const char* name;
    std::string request;
    int status;
    const char* code;
  };
  const std::vector<Raw> raws = {
      {"chunked body",
       "POST " + project + " HTTP/1.1\r\n" + host +
           "Content-Type: application/json\r\nTransfer-Encoding: chunked\r\n\r\n"
           "11\r\n{\"point\":[1,2,2]}\r\n0\r\n\r\n",
       411, "length_required"},
      {"no Content-Length",
       "POST " + project + " HTTP/1.1\r\n" + host +
           "Content-Type: application/json\r\nConnection: close\r\n\r\n" + good_point,
       411, "length_required"},
      {"gzip body",
       "POST " + project + " HTTP/1.1\r\n" + host +
           "Content-Type: application/json\r\nContent-Encoding: gzip\r\nContent-Length: 17\r\n\r\n" +
           good_point,
       415, "unsupported_content_encoding"},
      {"huge Content-Length, body never sent",
       "POST " + project + " HTTP/1.1\r\n" + host +
           "Content-Type: application/json\r\nContent-Length: 99999999999\r\n\r\n",
       413, "body_too_large"},
      {"PUT", "PUT /v1/project HTTP/1.1\r\n" + host + "Content-Length: 0\r\nConnection: close\r\n\r\n", 405,
       "method_not_allowed"},
      {"malformed request line", "GARBAGE\r\n\r\n", 400, "bad_request"},
      {"GET with a body", "GET /healthz HTTP/1.1\r\n" + host + "Content-Length: 5\r\n\r\nhello", 400,
       "body_not_allowed"},
  };
  for (const auto& k : raws) {
    CAPTURE(k.name);
    const std::string response = raw_exchange(s.port(), k.request);
    CHECK(raw_status(response) == k.status);
    CHECK(raw_json(response)["error"]["code"] == k.code);
    CHECK(post_json(*c, project, good_point, 200)["result"] == good_answer);
  }

  // Nothing above reached the cache: one geometry, compiled once, no failed state kept.
  CHECK(s.server().cache().stats().size == 1);
  CHECK(s.server().cache().stats().compilations == 1);
}

TEST_CASE("responses are never compressed and X-Request-Id is honoured") {
  TestServer s;
  auto c = s.client();
  const std::string id = create(*c, kParaboloid);
  const std::string body = http_points_body(random_points(500, 3, -2, 2));
  const std::string response = raw_exchange(
      s.port(), "POST /v1/geometries/" + id +
                    "/project HTTP/1.1\r\nHost: x\r\nConnection: close\r\n"
                    "Accept-Encoding: br, gzip, deflate\r\nRange: bytes=0-10\r\nX-Request-Id: trace-42\r\n"
                    "Content-Type: application/json; charset=utf-8\r\nContent-Length: " +
                    std::to_string(body.size()) + "\r\n\r\n" + body);
  CHECK(raw_status(response) == 200);
  CHECK(response.find("Content-Encoding") == std::string::npos);
  CHECK(response.find("X-Request-Id: trace-42\r\n") != std::string::npos);
  CHECK(raw_json(response)["results"].size() == 500);

  httplib::Headers bad_id = {{"X-Request-Id", std::string(300, 'a')}};
  auto r = c->Get("/healthz", bad_id);
  REQUIRE(r);
  CHECK(r->get_header_value("X-Request-Id").size() == 16);
}

TEST_CASE("Expect: 100-continue gets the final answer at once when the request would be refused") {
  TestServer s;
  auto c = s.client();
  const std::string id = create(*c, kParaboloid);
  const std::string head =
      "POST /v1/geometries/" + id + "/project HTTP/1.1\r\nHost: x\r\nExpect: 100-continue\r\n";
  const std::string refused =
      raw_exchange(s.port(), head + "Content-Type: text/plain\r\nContent-Length: 17\r\n\r\n");
  CHECK(raw_status(refused) == 415);
  CHECK(refused.find("100 Continue") == std::string::npos);
  CHECK(raw_json(refused)["error"]["code"] == "unsupported_media_type");
  // Admitted: 100 Continue, then the answer once the body is sent (here sent right away).
  const std::string body = R"J({"point":[0,0,3]})J";
  const std::string admitted = raw_exchange(
      s.port(), head + "Connection: close\r\nContent-Type: application/json\r\nContent-Length: " +
                    std::to_string(body.size()) + "\r\n\r\n" + body);
  REQUIRE(admitted.rfind("HTTP/1.1 100 Continue\r\n\r\n", 0) == 0);
  const std::string final_response = admitted.substr(std::string("HTTP/1.1 100 Continue\r\n\r\n").size());
  CHECK(raw_status(final_response) == 200);
  CHECK(raw_json(final_response)["result"]["diagnostics"]["status"] == "converged");
}

TEST_CASE("the cache evicts by count, keeps serving, and 404s tell the client to re-post") {
  ServerConfig config;
  config.cache_entries = 2;
  TestServer s(config);
  auto c = s.client();
  const std::string a = create(*c, kSurfaceA1);
  const std::string b = create(*c, kParaboloid);
  post_json(*c, "/v1/geometries/" + a + "/project", R"J({"point":[1,2,2]})J",
            200);                              // a is now the most recent
  const std::string d = create(*c, kCurveC1);  // evicts b
  CHECK(c->Get("/v1/geometries/" + a)->status == 200);
  CHECK(c->Get("/v1/geometries/" + d)->status == 200);
  const json lost = post_json(*c, "/v1/geometries/" + b + "/project", R"J({"point":[0,0,3]})J", 404);
  CHECK(lost["error"]["code"] == "geometry_not_found");
  CHECK(lost["error"]["message"].get<std::string>().find("POST its definition") != std::string::npos);
  CHECK(metric(*c, "footpoint_geometry_cache_evictions_total") == 1);
  CHECK(metric(*c, "footpoint_geometry_cache_entries") == 2);
  // Re-posting brings it back under the same id.
  CHECK(create(*c, kParaboloid) == b);
  // A flood of distinct formulas stays bounded.
  for (int i = 0; i < 20; ++i)
    create(*c, R"J({"type":"parametric_curve","x":"t","y":"t^2+)J" + std::to_string(i) +
                   R"J(","domain":{"t":[0,1]}})J");
  CHECK(metric(*c, "footpoint_geometry_cache_entries") == 2);
  CHECK(metric(*c, "footpoint_geometry_cache_evictions_total") == 22);
}

TEST_CASE("points not done by the deadline get deadline_exceeded, with null answers") {
  ServerConfig config;
  config.deadline = std::chrono::milliseconds(1);
  config.compile_deadline = std::chrono::milliseconds(60000);  // compile fully, project against 1 ms
  config.threads = 1;
  TestServer s(config);
  auto c = s.client();
  const std::string id = create(*c, kSurfaceA1);
  const json r = post_json(*c, "/v1/geometries/" + id + "/project",
                           http_points_body(random_points(50000, 9, -9, 9)), 200);
  std::size_t late = 0;
  for (const auto& x : r["results"]) {
    if (x["diagnostics"]["status"] != "deadline_exceeded") continue;
    ++late;
    CHECK(x["foot_point"].is_null());
    CHECK(x["distance"].is_null());
    CHECK(x["diagnostics"]["converged"] == false);
  }
  CHECK(late > 0);
  CHECK(r["stats"]["converged"].get<std::size_t>() + late <= 50000);
}

TEST_CASE("beyond --max-inflight, compute requests are shed with 503 overloaded") {
  ServerConfig config;
  config.max_inflight = 1;
  config.threads = 1;
  config.deadline = std::chrono::milliseconds(1500);  // bounds the heavy request below
  TestServer s(config);
  auto c = s.client();
  const std::string id = create(*c, kSurfaceA1);
  const std::string heavy =
      http_points_body(random_points(100000, 13, -9, 9), 3, R"J("options":{"all_minima":true})J");
  std::thread slow([&] {
    auto c2 = s.client();
    post_json(*c2, "/v1/geometries/" + id + "/project", heavy, 200);
  });
  wait_in_flight(*c, 1);
  auto r = c->Post("/v1/geometries/" + id + "/project", R"J({"point":[1,2,2]})J", "application/json");
  REQUIRE(r);
  CHECK(r->status == 503);
  CHECK(json::parse(r->body)["error"]["code"] == "overloaded");
  CHECK(r->get_header_value("Retry-After") == "1");
  auto h = s.client()->Get("/healthz");  // operations endpoints are never shed
  REQUIRE(h);
  CHECK(h->status == 200);
  slow.join();
  c = s.client();
  post_json(*c, "/v1/geometries/" + id + "/project", R"J({"point":[1,2,2]})J", 200);
}

TEST_CASE("beyond --max-inflight-points, a second batch is shed; a lone oversized batch still runs") {
  ServerConfig config;
  config.max_inflight_points = 30000;
  config.threads = 1;
  config.deadline = std::chrono::milliseconds(1500);
  TestServer s(config);
  auto c = s.client();
  const std::string id = create(*c, kSurfaceA1);
  const std::string project = "/v1/geometries/" + id + "/project";
  // 40,000 points: more than the budget, admitted because nothing else is in flight (without their
  // certificates: the search alone keeps them in flight long enough, also under a sanitizer)
  const std::string big =
      http_points_body(random_points(40000, 21, -9, 9), 3, R"J("options":{"certify":false})J");
  std::thread slow([&] {
    auto c2 = s.client();
    CHECK(post_json(*c2, project, big, 200)["stats"]["points"] == 40000);
  });
  wait_metric(*c, "footpoint_points_in_flight", 40000);
  auto r = c->Post(project, R"J({"points":[[1,2,2],[0,0,3]]})J", "application/json");
  REQUIRE(r);
  CHECK(r->status == 503);
  CHECK(json::parse(r->body)["error"]["code"] == "overloaded");
  CHECK(r->get_header_value("Retry-After") == "1");
  slow.join();
  CHECK(post_json(*c, project, R"J({"points":[[1,2,2],[0,0,3]]})J", 200)["stats"]["points"] == 2);
  CHECK(metric(*c, "footpoint_points_in_flight") == 0);
}

TEST_CASE("graceful shutdown: idle connections close at once, in-flight requests finish, run() returns") {
  ServerConfig config;
  config.threads = 1;
  config.keep_alive_timeout_s = 60;  // what the shutdown would wait for the idle connections
  TestServer s(config);
  auto c = s.client();
  const std::string id = create(*c, kSurfaceA1);
  const auto pts = random_points(20000, 17, -9, 9);
  httplib::Result in_flight{nullptr, httplib::Error::Unknown};
  std::thread slow([&] {
    auto c2 = s.client();
    // without certificates: a batch that takes a while, not minutes under a sanitizer
    in_flight = c2->Post("/v1/geometries/" + id + "/project",
                         http_points_body(pts, 3, R"J("options":{"certify":false})J"), "application/json");
  });
  // A kept-alive connection that has already been served once, and `c`, idle since it saw the
  // batch in flight.
  auto idle = s.client();
  REQUIRE(idle->Get("/healthz")->status == 200);
  wait_in_flight(*c, 1);

  const auto start = std::chrono::steady_clock::now();
  s.server().shutdown();  // returns at once
  CHECK(s.server().api().shutting_down());
  // The idle connections are closed and nobody listens: no answer at all.
  CHECK_FALSE(idle->Get("/readyz"));
  CHECK_FALSE(c->Get("/readyz"));
  slow.join();
  s.stop();  // run() has returned
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  CHECK(seconds < 40.0);  // the batch's time (longer on a loaded machine), not the 60 s keep-alive timeout
  REQUIRE(in_flight);
  CHECK(in_flight->status == 200);
  CHECK(in_flight->get_header_value("Connection") == "close");
  const json answer = json::parse(in_flight->body);
  REQUIRE(answer["results"].size() == pts.size());
  CHECK(answer["stats"]["points"] == 20000);
  CHECK_FALSE(s.client()->Get("/healthz"));
}

TEST_CASE("a second server cannot bind the port of a running one") {
  TestServer s;
  ServerConfig config = test_config();
  config.port = s.port();
  HttpServer second(config);
  CHECK_THROWS_AS(second.bind(), std::runtime_error);
}
