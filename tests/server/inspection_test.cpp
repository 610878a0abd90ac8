// Inspection over HTTP: the normal and signed distance of each result and stats.deviation on a
// sphere of radius 2 (closed form: the signed distance of p is 2 - |p| for this parametrisation,
// whose s_u x s_v points inwards); points in binary (float64, float32, a length that is no whole
// number of points); answers streamed as NDJSON (the same results as the JSON batch, in order,
// then the stats) and as binary records (decoded by the layout the header names); a client that
// goes away stops the work; the deadline holds per stream.
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "server_support.hpp"

using namespace footpoint::server;
using namespace footpoint::server::testing;
using json = nlohmann::json;

namespace {

const std::string& kInspectionSphere = kSphereRadius2;

// n points at radii 1.5 .. 2.5 in directions away from the poles, and their signed distances.
std::vector<double> inspection_points(int n, std::vector<double>* signed_distances = nullptr) {
  std::vector<double> p;
  for (int i = 0; i < n; ++i) {
    const double u = 0.1 + 6.0 * i / n, v = 0.4 + 2.3 * ((i * 7) % n) / n, r = 1.5 + (i % 11) / 10.0;
    p.insert(p.end(), {r * std::sin(v) * std::cos(u), r * std::sin(v) * std::sin(u), r * std::cos(v)});
    if (signed_distances) signed_distances->push_back(2.0 - r);
  }
  return p;
}

json inspection_json_points(const std::vector<double>& p) {
  json points = json::array();
  for (std::size_t i = 0; i < p.size(); i += 3) points.push_back({p[i], p[i + 1], p[i + 2]});
  return points;
}

std::string as_float64(const std::vector<double>& p) { return float64_bytes(p); }

std::vector<double> decode_float64(const std::string& body) {
  std::vector<double> x(body.size() / 8);
  std::memcpy(x.data(), body.data(), x.size() * 8);
  return x;
}

std::vector<json> ndjson_lines(const std::string& body) {
  std::vector<json> lines;
  std::size_t at = 0;
  while (at < body.size()) {
    const auto end = body.find('\n', at);
    REQUIRE(end != std::string::npos);  // every line ends with a newline
    lines.push_back(json::parse(body.substr(at, end - at)));
    at = end + 1;
  }
  return lines;
}

}  // namespace

TEST_CASE("inspection: normal, signed distance and stats.deviation against the sphere's closed form") {
  TestServer s;
  auto c = s.client();
  std::vector<double> expected;
  const std::vector<double> p = inspection_points(60, &expected);
  const json body = {{"geometry", json::parse(kInspectionSphere)},
                     {"points", inspection_json_points(p)},
                     {"options", {{"histogram_bins", 4}, {"tolerance_band", {-0.25, 0.25}}}}};
  auto r = c->Post("/v1/project", body.dump(), "application/json");
  REQUIRE(r);
  REQUIRE_MESSAGE(r->status == 200, r->body);
  const json answer = json::parse(r->body);
  double sum = 0, squares = 0;
  std::size_t within = 0;
  for (std::size_t i = 0; i < expected.size(); ++i) {
    const json& res = answer["results"][i];
    const double radius =
        std::sqrt(p[3 * i] * p[3 * i] + p[3 * i + 1] * p[3 * i + 1] + p[3 * i + 2] * p[3 * i + 2]);
    CHECK(res["signed_distance"].get<double>() == doctest::Approx(expected[i]).epsilon(1e-12));
    for (int k = 0; k < 3; ++k)
      CHECK(res["normal"][k].get<double>() == doctest::Approx(-p[3 * i + k] / radius).epsilon(1e-12));
    sum += expected[i];
    squares += expected[i] * expected[i];
    within += expected[i] >= -0.25 && expected[i] <= 0.25;
  }
  const json& d = answer["stats"]["deviation"];
  CHECK(d["count"] == 60);
  CHECK(d["signed"] == 60);
  CHECK(d["min"].get<double>() == doctest::Approx(-0.5));
  CHECK(d["max"].get<double>() == doctest::Approx(0.5));
  CHECK(d["mean"].get<double>() == doctest::Approx(sum / 60));
  CHECK(d["rms"].get<double>() == doctest::Approx(std::sqrt(squares / 60)));
  REQUIRE(d["histogram"]["counts"].size() == 4);
  CHECK(d["histogram"]["edges"].size() == 5);
  int total = 0;
  for (const auto& n : d["histogram"]["counts"]) total += n.get<int>();
  CHECK(total == 60);
  CHECK(d["tolerance_band"]["within"] == within);
  CHECK(d["tolerance_band"]["share"].get<double>() == doctest::Approx(within / 60.0));

  // fields selects them; a space curve has none (null)
  const json trimmed = {{"geometry", json::parse(kInspectionSphere)},
                        {"point", {0, 0.5, 0.2}},
                        {"fields", {"signed_distance"}}};
  r = c->Post("/v1/project", trimmed.dump(), "application/json");
  REQUIRE(r);
  CHECK(json::parse(r->body)["result"].size() == 1);
  const json helix = {{"geometry",
                       {{"type", "parametric_curve"},
                        {"x", "cos(t)"},
                        {"y", "sin(t)"},
                        {"z", "t"},
                        {"domain", {{"t", {0, 6}}}}}},
                      {"point", {2, 0, 1}}};
  r = c->Post("/v1/project", helix.dump(), "application/json");
  REQUIRE(r);
  const json h = json::parse(r->body);
  CHECK(h["result"]["normal"].is_null());
  CHECK(h["result"]["signed_distance"].is_null());
  CHECK(h["stats"]["deviation"]["signed"] == 0);
  CHECK(h["stats"]["deviation"]["count"] == 1);
  for (const json& bad :
       {json{{"histogram_bins", 0}}, json{{"tolerance_band", {1, -1}}}, json{{"tolerance_band", {1}}}}) {
    r = c->Post(
        "/v1/project",
        json{{"geometry", json::parse(kInspectionSphere)}, {"point", {0, 0, 1}}, {"options", bad}}.dump(),
        "application/json");
    REQUIRE(r);
    CHECK(r->status == 400);
  }
}

TEST_CASE("inspection: points in binary, float64 and float32, with the options in the query") {
  TestServer s;
  auto c = s.client();
  const std::string id = create(*c, kInspectionSphere);
  std::vector<double> expected;
  const std::vector<double> p = inspection_points(50, &expected);
  const std::string path = "/v1/geometries/" + id + "/project";
  auto r = c->Post(path + "?fields=signed_distance,diagnostics.status&histogram_bins=5", as_float64(p),
                   "application/octet-stream");
  REQUIRE(r);
  REQUIRE_MESSAGE(r->status == 200, r->body);
  json answer = json::parse(r->body);
  REQUIRE(answer["results"].size() == 50);
  for (std::size_t i = 0; i < expected.size(); ++i) {
    CHECK(answer["results"][i].size() == 2);
    CHECK(answer["results"][i]["signed_distance"].get<double>() ==
          doctest::Approx(expected[i]).epsilon(1e-12));
  }
  CHECK(answer["stats"]["deviation"]["histogram"]["counts"].size() == 5);

  std::vector<float> single(p.begin(), p.end());
  std::string body32(single.size() * 4, '\0');
  std::memcpy(body32.data(), single.data(), body32.size());
  r = c->Post(path + "?dtype=float32&max_distance=0.3", body32, "application/octet-stream");
  REQUIRE(r);
  REQUIRE_MESSAGE(r->status == 200, r->body);
  answer = json::parse(r->body);
  for (std::size_t i = 0; i < expected.size(); ++i) {
    const json& res = answer["results"][i];
    const double x = single[3 * i], y = single[3 * i + 1], z = single[3 * i + 2];
    const double d = 2.0 - std::sqrt(x * x + y * y + z * z);
    if (std::fabs(d) > 0.3 + 1e-9) {
      CHECK(res["diagnostics"]["status"] == "beyond_max_distance");
    } else if (std::fabs(d) < 0.3 - 1e-9) {
      CHECK(res["signed_distance"].get<double>() == doctest::Approx(d).epsilon(1e-12));
    }
  }

  // a length that is no whole number of points: 400 with the byte counts
  r = c->Post(path, as_float64(p).substr(0, 100), "application/octet-stream");
  REQUIRE(r);
  CHECK(r->status == 400);
  CHECK(json::parse(r->body)["error"]["code"] == "wrong_shape");
  CHECK(r->body.find("100 bytes") != std::string::npos);
  CHECK(r->body.find("24-byte") != std::string::npos);
  r = c->Post(path + "?dtype=float32", std::string(10, '\0'), "application/octet-stream");
  REQUIRE(r);
  CHECK(r->status == 400);
  CHECK(r->body.find("10 bytes") != std::string::npos);
  for (const char* query : {"?colour=red", "?dtype=int8", "?max_distance=-1", "?fields=nothing",
                            "?certify=maybe", "?tolerance_band=1"}) {
    r = c->Post(path + query, as_float64(p), "application/octet-stream");
    REQUIRE(r);
    INFO(query << " " << r->body);
    CHECK(r->status == 400);
  }
  // NaN and infinity, which JSON cannot write, are refused with the coordinate named
  for (const double bad : {std::nan(""), HUGE_VAL}) {
    std::vector<double> q = p;
    q[3 * 17 + 2] = bad;
    for (const bool streamed : {false, true}) {
      r = streamed ? c->Post(path, httplib::Headers{{"Accept", "application/x-ndjson"}}, as_float64(q),
                             "application/octet-stream")
                   : c->Post(path, as_float64(q), "application/octet-stream");
      REQUIRE(r);
      INFO(r->body);
      CHECK(r->status == 400);
      CHECK(json::parse(r->body)["error"]["code"] == "number_out_of_range");
      CHECK(json::parse(r->body)["error"]["field"] == "points[17][2]");
    }
  }
  // the inline route needs the definition, which binary cannot carry
  r = c->Post("/v1/project", as_float64(p), "application/octet-stream");
  REQUIRE(r);
  CHECK(r->status == 415);
  // other routes stay JSON only
  r = c->Post("/v1/geometries", "x", "application/octet-stream");
  REQUIRE(r);
  CHECK(r->status == 415);
}

TEST_CASE("inspection: NDJSON streams the JSON batch's results in order, then the stats") {
  TestServer s;
  auto c = s.client();
  const std::string id = create(*c, kInspectionSphere);
  // more than a few windows (kFirstStreamWindow 256, then doubling)
  const std::vector<double> p = inspection_points(1500);
  const json body = {{"points", inspection_json_points(p)},
                     {"fields", {"foot_point", "distance", "signed_distance", "diagnostics.status"}},
                     {"options", {{"tolerance_band", {-0.1, 0.1}}}}};
  const std::string path = "/v1/geometries/" + id + "/project";
  auto whole = c->Post(path, body.dump(), "application/json");
  REQUIRE(whole);
  REQUIRE(whole->status == 200);
  const json batch = json::parse(whole->body);

  httplib::Headers ndjson{{"Accept", "application/x-ndjson"}};
  auto r = c->Post(path, ndjson, body.dump(), "application/json");
  REQUIRE(r);
  REQUIRE_MESSAGE(r->status == 200, r->body);
  CHECK(r->get_header_value("Content-Type") == "application/x-ndjson");
  CHECK(r->get_header_value("Transfer-Encoding") == "chunked");
  const std::vector<json> lines = ndjson_lines(r->body);
  REQUIRE(lines.size() == 1501);
  for (std::size_t i = 0; i < 1500; ++i) CHECK(lines[i] == batch["results"][i]);
  json stats = lines.back()["stats"], expected_stats = batch["stats"];
  stats.erase("elapsed_ms");
  expected_stats.erase("elapsed_ms");
  CHECK(lines.back()["geometry_id"] == id);
  CHECK(stats == expected_stats);

  // binary in, NDJSON out: the same lines
  r = c->Post(path + "?fields=foot_point,distance,signed_distance,diagnostics.status&tolerance_band=-0.1,0.1",
              ndjson, as_float64(p), "application/octet-stream");
  REQUIRE(r);
  REQUIRE(r->status == 200);
  const std::vector<json> binary_lines = ndjson_lines(r->body);
  REQUIRE(binary_lines.size() == 1501);
  for (std::size_t i = 0; i < 1500; ++i) CHECK(binary_lines[i] == lines[i]);

  // one point is answered in JSON only
  r = c->Post(path, ndjson, R"({"point":[0,0,1]})", "application/json");
  REQUIRE(r);
  CHECK(r->status == 406);
}

TEST_CASE("inspection: binary records of the requested fields, NaN where JSON has null") {
  TestServer s;
  auto c = s.client();
  const std::string id = create(*c, kInspectionSphere);
  std::vector<double> expected;
  std::vector<double> p = inspection_points(700, &expected);
  const std::string path = "/v1/geometries/" + id + "/project";
  httplib::Headers binary{{"Accept", "application/octet-stream"}};
  auto r = c->Post(path + "?max_distance=0.45", binary, as_float64(p), "application/octet-stream");
  REQUIRE(r);
  REQUIRE_MESSAGE(r->status == 200, r->body);
  CHECK(r->get_header_value("Content-Type") == "application/octet-stream");
  CHECK(r->get_header_value("X-Footpoint-Record") ==
        "foot_point:3,parameters:2,distance:1,normal:3,signed_distance:1,status:1");
  CHECK(r->get_header_value("X-Footpoint-Record-Bytes") == "88");
  REQUIRE(r->body.size() == 700 * 88);
  const std::vector<double> x = decode_float64(r->body);
  for (std::size_t i = 0; i < 700; ++i) {
    const double* rec = &x[11 * i];
    INFO("point " << i << " expected " << expected[i]);
    if (std::fabs(expected[i]) > 0.45) {
      CHECK(rec[10] == 7.0);  // beyond_max_distance
      CHECK(std::isnan(rec[0]));
      CHECK(std::isnan(rec[5]));
      CHECK(std::isnan(rec[9]));
    } else {
      CHECK(rec[10] == 0.0);  // converged
      CHECK(rec[5] == doctest::Approx(std::fabs(expected[i])).epsilon(1e-12));
      CHECK(rec[9] == doctest::Approx(expected[i]).epsilon(1e-12));
      const double radius =
          std::sqrt(p[3 * i] * p[3 * i] + p[3 * i + 1] * p[3 * i + 1] + p[3 * i + 2] * p[3 * i + 2]);
      CHECK(rec[6] == doctest::Approx(-p[3 * i] / radius).epsilon(1e-12));
      CHECK(rec[0] == doctest::Approx(2 * p[3 * i] / radius).epsilon(1e-12));
    }
  }
  r = c->Post(path + "?fields=diagnostics.certificate", binary, as_float64(p), "application/octet-stream");
  REQUIRE(r);
  CHECK(r->status == 400);
  CHECK(json::parse(r->body)["error"]["code"] == "unsupported_field");
  r = c->Post(path + "?fields=distance,diagnostics.iterations", binary, as_float64(p),
              "application/octet-stream");
  REQUIRE(r);
  CHECK(r->get_header_value("X-Footpoint-Record") == "distance:1,iterations:1");
  CHECK(r->body.size() == 700 * 16);
}

TEST_CASE("inspection: a client that goes away stops the stream's work") {
  ServerConfig config;
  config.threads = 1;
  TestServer s(config);
  auto c = s.client();
  const std::string id = create(*c, kInspectionSphere);
  const int n = 200000;
  const std::string body = as_float64(inspection_points(n));
  const std::string request = "POST /v1/geometries/" + id +
                              "/project HTTP/1.1\r\nHost: x\r\nAccept: application/x-ndjson\r\n"
                              "Content-Type: application/octet-stream\r\nContent-Length: " +
                              std::to_string(body.size()) + "\r\n\r\n" + body;
  const int fd = raw_connect(s.port());
  REQUIRE(send_all(fd, request) == request.size());
  // the first lines arrive, then the client leaves without reading on
  std::string got;
  char buf[4096];
  while (got.find("\"signed_distance\"") == std::string::npos) {
    const auto k = ::recv(fd, buf, sizeof buf, 0);
    REQUIRE(k > 0);
    got.append(buf, static_cast<std::size_t>(k));
  }
  CHECK(got.rfind("HTTP/1.1 200", 0) == 0);
  ::shutdown(fd, SHUT_RDWR);
  ::close(fd);
  // the request ends long before its points would all be projected (~1 µs... tens of µs each)
  CHECK(wait_until_idle(s.server()));
  auto m = c->Get("/metrics");
  REQUIRE(m);
  const auto at = m->body.find("footpoint_projections_total{status=\"converged\"} ");
  REQUIRE(at != std::string::npos);
  const double projected = std::stod(m->body.substr(at + 48));
  INFO("projected " << projected << " of " << n);
  CHECK(projected < n / 4);
}

TEST_CASE("inspection: the request's deadline holds for a stream") {
  ServerConfig config;
  config.deadline = std::chrono::milliseconds(20);
  config.compile_deadline = std::chrono::milliseconds(60000);
  config.threads = 1;
  TestServer s(config);
  auto c = s.client();
  const std::string id = create(*c, kInspectionSphere);
  const int n = 100000;
  httplib::Headers ndjson{{"Accept", "application/x-ndjson"}};
  auto r = c->Post("/v1/geometries/" + id + "/project?fields=diagnostics.status", ndjson,
                   as_float64(inspection_points(n)), "application/octet-stream");
  REQUIRE(r);
  REQUIRE(r->status == 200);
  const std::vector<json> lines = ndjson_lines(r->body);
  REQUIRE(lines.size() == n + 1);
  const json& statuses = lines.back()["stats"]["statuses"];
  INFO(statuses.dump());
  REQUIRE(statuses.contains("deadline_exceeded"));
  CHECK(statuses["deadline_exceeded"].get<int>() > n / 2);
  CHECK(lines.back()["stats"]["deviation"]["count"].get<int>() ==
        n - statuses["deadline_exceeded"].get<int>());
}

TEST_CASE("inspection: a stream in progress at shutdown is finished, as a batch is") {
  ServerConfig config;
  config.threads = 1;
  TestServer s(config);
  auto c = s.client();
  const std::string id = create(*c, kInspectionSphere);
  const int n = 50000;
  const std::string body = as_float64(inspection_points(n));
  std::optional<httplib::Result> r;
  std::thread client([&] {
    r.emplace(c->Post("/v1/geometries/" + id + "/project?fields=diagnostics.status",
                      httplib::Headers{{"Accept", "application/x-ndjson"}}, body,
                      "application/octet-stream"));
  });
  const auto start = std::chrono::steady_clock::now();
  while (s.server().api().in_flight() == 0 &&
         std::chrono::steady_clock::now() - start < std::chrono::seconds(60))
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  s.stop();  // graceful: returns when the server has stopped
  client.join();
  REQUIRE(r);
  REQUIRE(*r);
  REQUIRE((*r)->status == 200);
  const std::vector<json> lines = ndjson_lines((*r)->body);
  REQUIRE(lines.size() == n + 1);
  CHECK(lines.back()["stats"]["converged"] == n);
}
