// The bad-input matrix: kinds of bad request, each with the exact status and error code (and the
// field it names), and after each one the server still answers a good request with the same
// answer as before, on the same connection and on a new one. Then inputs that are valid but
// numerically hostile (division by zero at the start, formulas undefined on part of the domain or
// everywhere, overflowing coordinates): 200, and every result honest (converged with finite
// numbers that hold together, or a status saying what happened and null numbers). Then the
// deadline: a batch of expensive solves does not hold the workers past it.
#include <doctest/doctest.h>

#include <chrono>
#include <cmath>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "server_support.hpp"

using namespace footpoint::server;
using namespace footpoint::server::testing;
using json = nlohmann::json;

namespace {

// [GSA] Example 1 (public case paperA_ex1), and its reference answer for (1, 2, 2).
const json kSurface = json::parse(
    R"J({"type":"parametric_surface","x":"u+v","y":"sin(u)+2*cos(v)","z":"sin(u+v)","domain":{"u":[-25,25],"v":[-25,25]}})J");
const json kPlanarCurve =
    json::parse(R"J({"type":"parametric_curve","x":"cos(t)","y":"2*sin(t)","domain":{"t":[0,6]}})J");
const json kSpatialImplicit = json::parse(
    R"J({"type":"implicit_curve","equations":["x^2/9+y^2/16+z^2/9-1","x^2+y^2-4*z"],"domain":{"x":[-300,300],"y":[-300,300],"z":[-300,300]}})J");
const json kPlanarImplicit =
    json::parse(R"J({"type":"implicit_curve","equations":["x^2+y^2-1"],"domain":{"x":[-2,2],"y":[-2,2]}})J");
const std::string kGoodPoint = R"J({"point":[1,2,2]})J";

// An inline /v1/project body: the geometry, then the other members.
std::string inline_body(const json& geometry, const json& rest) {
  json b = rest;
  b["geometry"] = geometry;
  return b.dump();
}

std::string repeat(const std::string& s, std::size_t n) {
  std::string r;
  r.reserve(s.size() * n);
  for (std::size_t i = 0; i < n; ++i) r += s;
  return r;
}

std::string points_body(std::size_t n) {
  std::string b = R"J({"points":[)J";
  for (std::size_t i = 0; i < n; ++i) b += std::string(i ? "," : "") + "[1,2,2]";
  return b + "]}";
}

struct Bad {
  const char* name;
  std::string method;  // POST, GET, DELETE, PUT
  std::string path;    // "ID" stands for /v1/geometries/<id of kSurface>
  std::string content_type;
  std::string body;
  int status;
  const char* code;
  const char* field;  // nullptr: the error names no field
};

// The answer to the good request, checked against the reference once.
json good_answer(httplib::Client& c, const std::string& project) {
  auto r = c.Post(project, kGoodPoint, "application/json");
  REQUIRE(r);
  REQUIRE(r->status == 200);
  return json::parse(r->body)["result"];
}

}  // namespace

TEST_CASE("bad-input matrix: exact status and code for each kind, and the server keeps answering") {
  ServerConfig config;
  config.max_points = 100;
  config.max_body_bytes = 2 << 20;  // 2 MiB: a 1 MB formula fits, a 3 MB body does not
  TestServer s(config);
  auto c = s.client();
  auto created = c->Post("/v1/geometries", kSurface.dump(), "application/json");
  REQUIRE(created);
  REQUIRE(created->status == 201);
  const std::string id = json::parse(created->body)["geometry_id"];
  const std::string project = "/v1/geometries/" + id + "/project";
  const json good = good_answer(*c, project);
  // paperA_ex1: distance 1.07887060698367359338660328836 (tests/data/papers/public_cases.json).
  CHECK(std::fabs(good["distance"].get<double>() - 1.0788706069836736) <= 1e-14);
  CHECK(good["diagnostics"]["status"] == "converged");

  const std::string J = "application/json";
  const json p3 = {{"point", {1, 2, 2}}};
  const std::vector<Bad> cases = {
      // ---- malformed JSON ----
      {"truncated JSON", "POST", "ID", J, R"J({"point":[1,2,)J", 400, "malformed_json", nullptr},
      {"trailing garbage", "POST", "ID", J, R"J({"point":[1,2,2]} x)J", 400, "malformed_json", nullptr},
      {"two documents", "POST", "ID", J, R"J({"point":[1,2,2]}{"point":[1,2,2]})J", 400, "malformed_json",
       nullptr},
      {"single quotes", "POST", "ID", J, R"J({'point':[1,2,2]})J", 400, "malformed_json", nullptr},
      {"trailing comma", "POST", "ID", J, R"J({"point":[1,2,2],})J", 400, "malformed_json", nullptr},
      {"comment", "POST", "ID", J, R"J({"point":[1,2,2] /* c */})J", 400, "malformed_json", nullptr},
      {"invalid UTF-8 in a string", "POST", "ID", J, "{\"point\":[1,2,2],\"method\":\"\xff\xfe\"}", 400,
       "malformed_json", nullptr},
      {"raw control character in a string", "POST", "ID", J, "{\"point\":[1,2,2],\"method\":\"a\tb\"}", 400,
       "malformed_json", nullptr},
      {"byte order mark", "POST", "ID", J, "\xef\xbb\xbf" + kGoodPoint, 400, "malformed_json", nullptr},
      {"empty body", "POST", "/v1/project", J, "", 400, "malformed_json", nullptr},
      // Beyond the reader's nesting limit the body is not JSON it accepts, whatever the shape.
      {"nesting 5,000 deep", "POST", "ID", J, R"J({"point":)J" + repeat("[", 5000) + repeat("]", 5000) + "}",
       400, "malformed_json", nullptr},
      // ---- numbers JSON cannot hold ----
      {"NaN", "POST", "ID", J, R"J({"point":[1,NaN,2]})J", 400, "malformed_json", nullptr},
      {"Infinity", "POST", "ID", J, R"J({"point":[Infinity,1,2]})J", 400, "malformed_json", nullptr},
      {"-Infinity", "POST", "ID", J, R"J({"point":[1,2,-Infinity]})J", 400, "malformed_json", nullptr},
      {"hexadecimal number", "POST", "ID", J, R"J({"point":[0x10,1,2]})J", 400, "malformed_json", nullptr},
      {"leading zero", "POST", "ID", J, R"J({"point":[01,1,2]})J", 400, "malformed_json", nullptr},
      {"1e400", "POST", "ID", J, R"J({"point":[1,2,1e400]})J", 400, "number_out_of_range", "point[2]"},
      {"-1e400 in a batch", "POST", "ID", J, R"J({"points":[[1,2,2],[-1e400,0,0]]})J", 400,
       "number_out_of_range", "points[1][0]"},
      {"1e400 in a domain (an infinite domain)", "POST", "/v1/geometries", J,
       R"J({"type":"parametric_surface","x":"u","y":"v","z":"u*v","domain":{"u":[0,1],"v":[0,1e400]}})J", 400,
       "number_out_of_range", "domain.v[1]"},
      // ---- wrong types ----
      {"body is an array", "POST", "ID", J, "[1,2,2]", 400, "wrong_type", "body"},
      {"coordinate as a string", "POST", "ID", J, R"J({"point":[1,"2",2]})J", 400, "wrong_type", "point[1]"},
      {"point is a number", "POST", "ID", J, R"J({"point":5})J", 400, "wrong_type", "point"},
      {"points is a flat array", "POST", "ID", J, R"J({"points":[1,2,2]})J", 400, "wrong_type", "points[0]"},
      {"null coordinate in a batch", "POST", "ID", J, R"J({"points":[[1,2,2],[1,null,2]]})J", 400,
       "wrong_type", "points[1][1]"},
      {"method is a number", "POST", "ID", J, R"J({"point":[1,2,2],"method":5})J", 400, "wrong_type",
       "method"},
      {"options is a number", "POST", "ID", J, R"J({"point":[1,2,2],"options":5})J", 400, "wrong_type",
       "options"},
      {"all_minima is a string", "POST", "ID", J, R"J({"point":[1,2,2],"options":{"all_minima":"yes"}})J",
       400, "wrong_type", "options.all_minima"},
      {"geometry is a string", "POST", "/v1/project", J, R"J({"point":[1,2,2],"geometry":"sphere"})J", 400,
       "wrong_type", "geometry"},
      {"type is a number", "POST", "/v1/geometries", J, with(kSurface, "type", 5).dump(), 400, "wrong_type",
       "type"},
      {"formula is a number", "POST", "/v1/project", J, inline_body(with(kSurface, "x", 5), p3), 400,
       "wrong_type", "geometry.x"},
      {"constant is a string", "POST", "/v1/geometries", J, with(kSurface, "constants", {{"a", "x"}}).dump(),
       400, "wrong_type", "constants.a"},
      // ---- missing, unknown, duplicate, conflicting fields ----
      {"missing point", "POST", "ID", J, R"J({"method":"auto"})J", 400, "missing_field", "point"},
      {"missing geometry on /v1/project", "POST", "/v1/project", J, kGoodPoint, 400, "missing_field",
       "geometry"},
      {"missing type", "POST", "/v1/geometries", J,
       [] {
         json d = kSurface;
         d.erase("type");
         return d.dump();
       }(),
       400, "missing_field", "type"},
      {"missing formula z", "POST", "/v1/project", J,
       inline_body(
           [] {
             json d = kSurface;
             d.erase("z");
             return d;
           }(),
           p3),
       400, "missing_field", "geometry.z"},
      {"missing domain v", "POST", "/v1/geometries", J, with(kSurface, "domain", {{"u", {0, 1}}}).dump(), 400,
       "missing_field", "domain.v"},
      {"spatial implicit curve without domain z", "POST", "/v1/geometries", J,
       with(kSpatialImplicit, "domain", json::parse(R"J({"x":[-3,3],"y":[-3,3]})J")).dump(), 400,
       "missing_field", "domain.z"},
      {"unknown top-level field", "POST", "ID", J, R"J({"point":[1,2,2],"pointz":[1]})J", 400,
       "unknown_field", "pointz"},
      {"unknown option", "POST", "ID", J, R"J({"point":[1,2,2],"options":{"speed":11}})J", 400,
       "unknown_field", "options.speed"},
      {"domain variable of another type", "POST", "/v1/geometries", J,
       with(kPlanarCurve, "domain", {{"u", {0, 1}}}).dump(), 400, "unknown_field", "domain.u"},
      {"duplicate key", "POST", "ID", J, R"J({"point":[1,2,2],"point":[3,4,5]})J", 400, "duplicate_field",
       "point"},
      {"point and points", "POST", "ID", J, R"J({"point":[1,2,2],"points":[[1,2,2]]})J", 400,
       "conflicting_fields", "points"},
      {"unknown geometry type", "POST", "/v1/geometries", J, R"J({"type":"torus"})J", 400,
       "unknown_geometry_type", "type"},
      {"three implicit equations", "POST", "/v1/geometries", J,
       with(kSpatialImplicit, "equations", {"x", "y", "z"}).dump(), 400, "wrong_shape", "equations"},
      {"domain with three numbers", "POST", "/v1/geometries", J,
       with(kSurface, "domain", json::parse(R"J({"u":[0,1,2],"v":[0,1]})J")).dump(), 400, "wrong_shape",
       "domain.u"},
      // ---- dimensions and batches ----
      {"2-D point for a surface", "POST", "ID", J, R"J({"point":[1,2]})J", 400, "wrong_dimension", "point"},
      {"4 coordinates", "POST", "ID", J, R"J({"point":[1,2,2,1]})J", 400, "wrong_dimension", "point"},
      {"empty point", "POST", "ID", J, R"J({"point":[]})J", 400, "wrong_dimension", "point"},
      {"mixed dimensions in a batch", "POST", "ID", J, R"J({"points":[[1,2,2],[1,2]]})J", 400,
       "wrong_dimension", "points[1]"},
      {"3-D point for a planar curve", "POST", "/v1/project", J, inline_body(kPlanarCurve, p3), 400,
       "wrong_dimension", "point"},
      {"3-D points for a planar implicit curve", "POST", "/v1/project", J,
       inline_body(kPlanarImplicit, {{"points", {{1, 2, 2}}}}), 400, "wrong_dimension", "points[0]"},
      {"2-D point for a spatial implicit curve", "POST", "/v1/project", J,
       inline_body(kSpatialImplicit, {{"point", {1, 2}}}), 400, "wrong_dimension", "point"},
      {"empty batch", "POST", "ID", J, R"J({"points":[]})J", 400, "empty_batch", "points"},
      {"huge batch (over --max-points)", "POST", "ID", J, points_body(101), 413, "too_many_points", "points"},
      {"start of the wrong size", "POST", "ID", J,
       R"J({"point":[1,2,2],"method":"gsa","options":{"initial":[1]}})J", 400, "wrong_dimension",
       "options.initial"},
      {"fewer starts than points", "POST", "ID", J,
       R"J({"points":[[1,2,2],[0,0,0],[3,3,3]],"method":"gsa","options":{"initial":[[0,0],[1,1]]}})J", 400,
       "wrong_shape", "options.initial"},
      // ---- methods and options ----
      {"unknown method", "POST", "ID", J, R"J({"point":[1,2,2],"method":"magic"})J", 400, "unknown_method",
       "method"},
      {"a surface method for a curve", "POST", "/v1/project", J,
       inline_body(kPlanarCurve, {{"point", {1, 2}}, {"method", "gsa"}}), 400, "unknown_method", "method"},
      {"negative tolerance", "POST", "ID", J, R"J({"point":[1,2,2],"options":{"tolerance":-1}})J", 400,
       "invalid_option", "options.tolerance"},
      {"tolerance of 1 or more", "POST", "ID", J, R"J({"point":[1,2,2],"options":{"tolerance":2}})J", 400,
       "invalid_option", "options.tolerance"},
      {"absurd max_iterations", "POST", "ID", J, R"J({"point":[1,2,2],"options":{"max_iterations":1e9}})J",
       400, "invalid_option", "options.max_iterations"},
      {"negative max_iterations", "POST", "ID", J, R"J({"point":[1,2,2],"options":{"max_iterations":-3}})J",
       400, "invalid_option", "options.max_iterations"},
      {"fractional max_iterations", "POST", "ID", J,
       R"J({"point":[1,2,2],"options":{"max_iterations":2.5}})J", 400, "invalid_option",
       "options.max_iterations"},
      {"non-positive max_distance", "POST", "ID", J, R"J({"point":[1,2,2],"options":{"max_distance":0}})J",
       400, "invalid_option", "options.max_distance"},
      // ---- definitions that do not compile (422) ----
      {"reversed domain", "POST", "/v1/geometries", J,
       with(kSurface, "domain", json::parse(R"J({"u":[1,-1],"v":[0,1]})J")).dump(), 422, "bad_domain",
       "domain.u"},
      {"empty domain interval", "POST", "/v1/project", J,
       inline_body(with(kSurface, "domain", json::parse(R"J({"u":[0,1],"v":[2,2]})J")), p3), 422,
       "bad_domain", "geometry.domain.v"},
      {"formula syntax", "POST", "/v1/project", J, inline_body(with(kSurface, "z", "sin(u+"), p3), 422,
       "formula_syntax", "geometry.z"},
      {"unknown variable", "POST", "/v1/geometries", J, with(kSurface, "x", "u+w").dump(), 422,
       "unknown_variable", "x"},
      {"unknown function", "POST", "/v1/geometries", J, with(kSurface, "y", "foo(u)").dump(), 422,
       "unknown_function", "y"},
      {"empty formula", "POST", "/v1/geometries", J, with(kSurface, "z", "  ").dump(), 422, "empty_formula",
       "z"},
      {"1 MB formula", "POST", "/v1/project", J,
       inline_body(with(kSurface, "x", repeat("u+", 500000) + "u"), p3), 422, "formula_too_long",
       "geometry.x"},
      {"constant named like a variable", "POST", "/v1/geometries", J,
       with(kSurface, "constants", {{"u", 1}}).dump(), 422, "bad_constant", "constants.u"},
      {"constant redefining _pi", "POST", "/v1/geometries", J,
       with(kSurface, "constants", {{"_pi", 3}}).dump(), 422, "bad_constant", "constants._pi"},
      // ---- routes, methods, media types, sizes ----
      {"unknown geometry id", "POST", "/v1/geometries/0123456789abcdef0123456789abcdef/project", J,
       kGoodPoint, 404, "geometry_not_found", "id"},
      {"DELETE of an unknown id", "DELETE", "/v1/geometries/0123456789abcdef0123456789abcdef", "", "", 404,
       "geometry_not_found", "id"},
      {"DELETE of what is no id", "DELETE", "/v1/geometries/not-an-id", "", "", 400, "invalid_geometry_id",
       "id"},
      {"unknown route", "GET", "/v2/project", "", "", 404, "route_not_found", nullptr},
      {"path traversal", "GET", "/v1/geometries/../../etc/passwd", "", "", 404, "route_not_found", nullptr},
      {"GET on a POST route", "GET", "/v1/project", "", "", 405, "method_not_allowed", nullptr},
      {"PUT on a POST route", "PUT", "/v1/project", J, kGoodPoint, 405, "method_not_allowed", nullptr},
      {"text/plain body", "POST", "ID", "text/plain", kGoodPoint, 415, "unsupported_media_type", nullptr},
      {"form body", "POST", "ID", "application/x-www-form-urlencoded", "point=1,2,2", 415,
       "unsupported_media_type", nullptr},
      {"body over the limit", "POST", "/v1/project", J,
       inline_body(with(kSurface, "x", repeat("u+", 1500000) + "u"), p3), 413, "body_too_large", "body"},
  };
  REQUIRE(cases.size() >= 40);
  MESSAGE(cases.size() << " kinds of bad request");

  for (const auto& k : cases) {
    INFO(std::string(k.name));
    const std::string path = k.path == "ID" ? project : k.path;
    httplib::Result r{nullptr, httplib::Error::Unknown};
    if (k.method == "POST")
      r = c->Post(path, k.body, k.content_type);
    else if (k.method == "PUT")
      r = c->Put(path, k.body, k.content_type);
    else if (k.method == "DELETE")
      r = c->Delete(path);
    else
      r = c->Get(path);
    REQUIRE(r);
    CHECK(r->status == k.status);
    CHECK(r->get_header_value("Content-Type") == "application/json");
    const json e = json::parse(r->body, nullptr, false);
    REQUIRE_FALSE(e.is_discarded());
    CHECK(e["error"]["code"] == std::string(k.code));
    CHECK(e["error"]["message"].is_string());
    if (k.field)
      CHECK(e["error"]["field"] == k.field);
    else
      CHECK_FALSE(e["error"].contains("field"));
    if (std::string(k.code) == "malformed_json" || std::string(k.code) == "formula_syntax")
      CHECK(e["error"]["position"].get<long>() >= 0);
    // The server still answers the good request correctly: on this connection when the server
    // kept it open, and on a new one.
    auto again = c->Post(project, kGoodPoint, "application/json");
    if (!again) {  // the server closed the connection after a body it would not read
      c = s.client();
      again = c->Post(project, kGoodPoint, "application/json");
    }
    REQUIRE(again);
    CHECK(again->status == 200);
    CHECK(json::parse(again->body)["result"] == good);
    c = s.client();
  }

  // Framing problems an HTTP client library would not produce, on raw connections.
  const std::string host = "Host: 127.0.0.1\r\n";
  struct Raw {
    const char* name;
    std::string request;
    int status;
    const char* code;
  };
  const std::string post = "POST " + project + " HTTP/1.1\r\n" + host + "Content-Type: application/json\r\n";
  const std::vector<Raw> raws = {
      {"chunked body", post + "Transfer-Encoding: chunked\r\n\r\n11\r\n" + kGoodPoint + "\r\n0\r\n\r\n", 411,
       "length_required"},
      {"no Content-Length", post + "Connection: close\r\n\r\n" + kGoodPoint, 411, "length_required"},
      {"Content-Length not a number", post + "Content-Length: abc\r\n\r\n" + kGoodPoint, 400, "bad_request"},
      {"negative Content-Length", post + "Content-Length: -5\r\n\r\n" + kGoodPoint, 400, "bad_request"},
      {"conflicting Content-Length headers",
       post + "Content-Length: 17\r\nContent-Length: 18\r\nConnection: close\r\n\r\n" + kGoodPoint + " ", 400,
       "bad_request"},
      {"huge Content-Length, body never sent", post + "Content-Length: 99999999999\r\n\r\n", 413,
       "body_too_large"},
      {"gzip body", post + "Content-Encoding: gzip\r\nContent-Length: 17\r\n\r\n" + kGoodPoint, 415,
       "unsupported_content_encoding"},
      {"brotli body", post + "Content-Encoding: br\r\nContent-Length: 17\r\n\r\n" + kGoodPoint, 415,
       "unsupported_content_encoding"},
      {"no Content-Type",
       "POST " + project + " HTTP/1.1\r\n" + host + "Content-Length: 17\r\n\r\n" + kGoodPoint, 415,
       "unsupported_media_type"},
      {"GET with a body", "GET /healthz HTTP/1.1\r\n" + host + "Content-Length: 5\r\n\r\nhello", 400,
       "body_not_allowed"},
      {"malformed request line", "GARBAGE\r\n\r\n", 400, "bad_request"},
      {"URI over the limit", "GET /" + std::string(20000, 'a') + " HTTP/1.1\r\n" + host + "\r\n", 414,
       "uri_too_long"},
  };
  for (const auto& k : raws) {
    INFO(std::string(k.name));
    const std::string response = raw_exchange(s.port(), k.request);
    CHECK(raw_status(response) == k.status);
    CHECK(raw_json(response)["error"]["code"] == k.code);
    auto again = c->Post(project, kGoodPoint, "application/json");
    REQUIRE(again);
    CHECK(again->status == 200);
    CHECK(json::parse(again->body)["result"] == good);
  }
  MESSAGE(raws.size() << " kinds of bad HTTP framing");

  // Nothing that failed reached the cache: the geometry posted, compiled once, and the three
  // valid inline geometries of requests rejected for their points or method.
  CHECK(s.server().cache().stats().size == 4);
  CHECK(s.server().cache().stats().compilations == 4);
}

namespace {

// A result is honest: converged with finite numbers that hold together (distance = |p - foot|),
// or another status with null numbers or numbers that hold together all the same (where the
// method stopped); never NaN (the body would not parse).
void check_honest(const json& result, const json& point) {
  CAPTURE(result.dump());
  const json& d = result["diagnostics"];
  REQUIRE(d["status"].is_string());
  CHECK(d["converged"] == (d["status"] == "converged"));
  if (d["status"] == "converged") CHECK(result["distance"].is_number());
  if (result["distance"].is_null()) {
    CHECK(result["foot_point"].is_null());
    return;
  }
  REQUIRE(result["foot_point"].is_array());
  REQUIRE(result["foot_point"].size() == point.size());
  double sum = 0.0;
  for (std::size_t k = 0; k < point.size(); ++k) {
    const double e = point[k].get<double>() - result["foot_point"][k].get<double>();
    sum += e * e;
  }
  CHECK(std::fabs(std::sqrt(sum) - result["distance"].get<double>()) <= 1e-12 * (1 + std::sqrt(sum)));
}

}  // namespace

TEST_CASE("numerically hostile but valid requests: 200 and an honest status for every point") {
  // ln t on [-1, 2] compiles to more search structure than the default per-geometry bound (a
  // quarter of the cache; tests/server/access_test.cpp tests the bound): these cases are about
  // the solvers' answers, so the bound is lifted.
  ServerConfig config;
  config.max_geometry_bytes = std::size_t{1} << 30;
  TestServer s(config);
  auto c = s.client();
  struct Hostile {
    const char* name;
    std::string body;
    const char* status;  // the exact diagnostics status expected for the first point
  };
  const json p3 = {{"point", {1, 2, 2}}};
  const json unit = json::parse(R"J({"u":[0,1],"v":[0,1]})J");
  const std::vector<Hostile> cases = {
      // Division by zero where the method starts: nothing finite to iterate from.
      {"division by zero at the start point",
       inline_body(with(with(kSurface, "x", "1/u"), "domain", unit),
                   {{"point", {1, 2, 2}}, {"method", "newton"}, {"options", {{"initial", {0, 0.5}}}}}),
       "non_finite"},
      // The same geometry with auto: the pole is one edge; the nearest point is elsewhere.
      {"division by zero on an edge, auto", inline_body(with(with(kSurface, "x", "1/u"), "domain", unit), p3),
       "converged"},
      // NaN on half the domain (sqrt of negative u): auto answers on the defined half.
      {"formula NaN on part of the domain",
       inline_body(with(with(kSurface, "z", "sqrt(u)"), "domain", json::parse(R"J({"u":[-1,1],"v":[0,1]})J")),
                   p3),
       "converged"},
      {"curve undefined on part of its domain (ln t, t < 0)",
       inline_body(json::parse(R"J({"type":"parametric_curve","x":"t","y":"ln(t)","domain":{"t":[-1,2]}})J"),
                   {{"point", {0.5, -3}}}),
       "converged"},
      {"formula NaN on the whole domain", inline_body(with(kSurface, "z", "sqrt(-1-u*u)"), p3), "non_finite"},
      {"coordinates near the largest double", inline_body(kSurface, {{"point", {1e308, -1e308, 1e308}}}),
       "non_finite"},
      {"one iteration allowed",
       inline_body(kSurface, {{"point", {1, 2, 2}},
                              {"method", "gsa"},
                              {"options", {{"max_iterations", 1}, {"initial", {0, 0}}}}}),
       "max_iterations"},
  };
  for (const auto& k : cases) {
    INFO(std::string(k.name));
    auto r = c->Post("/v1/project", k.body, "application/json");
    REQUIRE(r);
    REQUIRE(r->status == 200);
    const json answer = json::parse(r->body, nullptr, false);
    REQUIRE_FALSE(answer.is_discarded());
    const json point = json::parse(k.body)["point"];
    CHECK(answer["result"]["diagnostics"]["status"] == k.status);
    check_honest(answer["result"], point);
  }
}

TEST_CASE("a batch of expensive solves does not hold the workers past the deadline") {
  ServerConfig config;
  config.deadline = std::chrono::milliseconds(300);
  // The compilation (interval discovery of the curve's cells) has a budget of its own: under
  // the sanitizers on a loaded machine it may take longer than the solving deadline.
  config.compile_deadline = std::chrono::seconds(60);
  config.threads = 2;
  TestServer s(config);
  auto c = s.client();
  // [Curve] Example 2 with its slowest method and the largest budget: ~40 ms a
  // point in Release, so 20,000 points would take minutes.
  const json curve = json::parse(
      R"J({"type":"implicit_curve","equations":["x^2/9+y^2/16+z^2/9+4*x*y-1","x^2+y^2+x-4*z"],"domain":{"x":[-300,300],"y":[-300,300],"z":[-300,300]}})J");
  json points = json::array();
  for (int i = 0; i < 20000; ++i) points.push_back({-400.0 + i * 0.04, 300.0 - i * 0.03, 350.0 - i * 0.035});
  const std::string body = inline_body(
      curve, {{"points", points}, {"method", "complete"}, {"options", {{"max_iterations", 10000}}}});
  const auto start = std::chrono::steady_clock::now();
  auto r = c->Post("/v1/project", body, "application/json");
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  REQUIRE(r);
  REQUIRE(r->status == 200);
  const json answer = json::parse(r->body);
  std::size_t late = 0;
  for (std::size_t i = 0; i < answer["results"].size(); ++i) {
    const json& x = answer["results"][i];
    late += x["diagnostics"]["status"] == "deadline_exceeded";
    check_honest(x, points[i]);
  }
  MESSAGE("deadline 0.3 s: answered in " << seconds << " s, batch " << answer["stats"]["elapsed_ms"]
                                         << " ms, " << late << " of 20000 points deadline_exceeded");
  CHECK(late > 0);
  // The solving stopped at the deadline, give or take the points already started (one each
  // per worker) and the sanitizers' slowdown.
  CHECK(answer["stats"]["elapsed_ms"].get<double>() < 300 + 1500);
  // The workers are free again: a good request is answered at once, and right.
  auto created = c->Post("/v1/geometries", kSurface.dump(), "application/json");
  REQUIRE(created);
  const std::string id = json::parse(created->body)["geometry_id"];
  const auto t0 = std::chrono::steady_clock::now();
  auto good = c->Post("/v1/geometries/" + id + "/project", kGoodPoint, "application/json");
  REQUIRE(good);
  CHECK(good->status == 200);
  CHECK(std::fabs(json::parse(good->body)["result"]["distance"].get<double>() - 1.0788706069836736) <= 1e-14);
  CHECK(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() < 1.0);
}
