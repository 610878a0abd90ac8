// Errors that say what to do, over HTTP: formulas (unknown functions and names with the nearest
// valid one, our own messages at the character at fault), domain bounds as constant expressions,
// ids that are no ids, the limits with the flag to raise or what to split, and a body sent to the
// wrong endpoint naming the one that takes it.
#include <doctest/doctest.h>

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "server_support.hpp"

using namespace footpoint::server;
using namespace footpoint::server::testing;
using json = nlohmann::json;

namespace {

const json kErrorsSurface = json::parse(
    R"J({"type":"parametric_surface","x":"u+v","y":"sin(u)+2*cos(v)","z":"sin(u+v)","domain":{"u":[-3,3],"v":[-3,3]}})J");

// The error of a request that must fail with `status`.
json error_of(httplib::Client& c, const std::string& method, const std::string& path, const std::string& body,
              int status) {
  auto r = method == "POST"     ? c.Post(path, body, "application/json")
           : method == "DELETE" ? c.Delete(path)
                                : c.Get(path);
  REQUIRE(r);
  CHECK(r->status == status);
  const json e = json::parse(r->body);
  REQUIRE(e.contains("error"));
  return e["error"];
}

}  // namespace

TEST_CASE("formula errors: code, field, character position, suggestion, no muparser wording") {
  TestServer s;
  auto c = s.client();
  struct Case {
    const char* formula;
    const char* code;
    int position;
    const char* suggestion;  // "" when the error has none
    const char* in_message;
  };
  const std::vector<Case> cases = {
      {"sinn(u)+v", "unknown_function", 0, "sin", "unknown function 'sinn' at position 0; did you mean sin?"},
      {"pow(u,2)", "unknown_function", 0, "u^2", "did you mean u^2?"},
      {"pi*u", "unknown_variable", 0, "_pi", "unknown name 'pi' at position 0; did you mean _pi?"},
      {"u**2", "formula_syntax", 1, "^", "'**' at position 1 is not an operator: powers are written ^"},
      {"sin(u", "formula_syntax", 3, "", "'(' at position 3 (the call of sin) is not closed"},
      {"2\u00B73", "formula_syntax", 1, "*",
       "unexpected character '\u00B7' (U+00B7) at position 1; write * instead"},
  };
  for (const auto& k : cases) {
    CAPTURE(k.formula);
    const json e = error_of(*c, "POST", "/v1/geometries", with(kErrorsSurface, "y", k.formula).dump(), 422);
    CHECK(e["code"] == k.code);
    CHECK(e["field"] == "y");
    CHECK(e["position"] == k.position);
    CHECK(e["position"].get<int>() < static_cast<int>(json(k.formula).get<std::string>().size()));
    if (*k.suggestion)
      CHECK(e["suggestion"] == k.suggestion);
    else
      CHECK_FALSE(e.contains("suggestion"));
    const std::string message = e["message"];
    CHECK(message.find(k.in_message) != std::string::npos);
    CHECK(message.rfind("formula y: ", 0) == 0);
    CHECK(message.find("Unexpected token") == std::string::npos);
    CHECK(message.find("Missing parenthesis") == std::string::npos);
  }
  // Inline, the field carries the geometry's prefix.
  const json inline_error =
      error_of(*c, "POST", "/v1/project",
               json{{"geometry", with(kErrorsSurface, "x", "u+sinn(v)")}, {"point", {1, 2, 2}}}.dump(), 422);
  CHECK(inline_error["code"] == "unknown_function");
  CHECK(inline_error["field"] == "geometry.x");
  CHECK(inline_error["position"] == 2);
  CHECK(inline_error["suggestion"] == "sin");
}

TEST_CASE("domain bounds as constant expressions: compiled, canonical in the id, errors at the bound") {
  TestServer s;
  auto c = s.client();
  const json helix = json::parse(
      R"J({"type":"parametric_curve","x":"cos(t)","y":"sin(t)","z":"t/4","domain":{"t":[0,"4*_pi"]}})J");
  auto r = c->Post("/v1/geometries", helix.dump(), "application/json");
  REQUIRE(r);
  CHECK(r->status == 201);
  const std::string id = json::parse(r->body)["geometry_id"];
  // The same helix with the number: the same id, already cached.
  r = c->Post("/v1/geometries", with(helix, "domain", {{"t", {0, 12.566370614359172}}}).dump(),
              "application/json");
  REQUIRE(r);
  CHECK(r->status == 200);
  CHECK(json::parse(r->body)["geometry_id"] == id);
  r = c->Get("/v1/geometries/" + id);
  REQUIRE(r);
  CHECK(json::parse(r->body)["definition"]["domain"]["t"] == json::array({0, 12.566370614359172}));
  // With the definition's constants.
  r = c->Post("/v1/project",
              json::parse(R"J({"geometry":{"type":"parametric_curve","x":"R*cos(t)","y":"R*sin(t)",
                              "domain":{"t":["-_pi","_pi"]},"constants":{"R":2}},"point":[3,0]})J")
                  .dump(),
              "application/json");
  REQUIRE(r);
  CHECK(r->status == 200);
  CHECK(json::parse(r->body)["result"]["distance"] == 1.0);

  const json e =
      error_of(*c, "POST", "/v1/geometries", with(helix, "domain", {{"t", {0, "4*pi"}}}).dump(), 422);
  CHECK(e["code"] == "unknown_variable");
  CHECK(e["field"] == "domain.t[1]");
  CHECK(e["position"] == 2);
  CHECK(e["suggestion"] == "_pi");
  const json reversed =
      error_of(*c, "POST", "/v1/geometries", with(helix, "domain", {{"t", {"_pi", "-_pi"}}}).dump(), 422);
  CHECK(reversed["code"] == "bad_domain");
  CHECK(reversed["field"] == "domain.t");
  // An object where [lo, hi] belongs is reported at the interval, not at its first bound.
  const json object = error_of(*c, "POST", "/v1/geometries",
                               with(helix, "domain", {{"t", {{"lo", 0}, {"hi", 1}}}}).dump(), 400);
  CHECK(object["code"] == "wrong_type");
  CHECK(object["field"] == "domain.t");
}

TEST_CASE("what is no geometry id is 400 invalid_geometry_id on every route that takes one") {
  TestServer s;
  auto c = s.client();
  const std::string upper = "0123456789ABCDEF0123456789ABCDEF";
  struct Case {
    std::string method, path;
  };
  const std::vector<Case> cases = {
      {"POST", "/v1/geometries/xyz/project"},
      {"GET", "/v1/geometries/xyz"},
      {"DELETE", "/v1/geometries/xyz"},
      {"GET", "/v1/geometries/xyz/mesh"},
      {"POST", "/v1/geometries/" + upper + "/project"},
      {"GET", "/v1/geometries/0123/mesh"},
  };
  for (const auto& k : cases) {
    CAPTURE(k.path);
    const json e = error_of(*c, k.method, k.path, R"J({"point":[1,2,2]})J", 400);
    CHECK(e["code"] == "invalid_geometry_id");
    CHECK(e["field"] == "id");
    CHECK(std::string(e["message"]).find("32 lower-case hex digits") != std::string::npos);
  }
  const json e = error_of(*c, "POST", "/v1/geometries/" + upper + "/project", R"J({"point":[1,2,2]})J", 400);
  CHECK(e["suggestion"] == "0123456789abcdef0123456789abcdef");
  // A well-formed id that is not held stays 404: post it again.
  CHECK(error_of(*c, "GET", "/v1/geometries/0123456789abcdef0123456789abcdef", "", 404)["code"] ==
        "geometry_not_found");
}

TEST_CASE("limits say the limit and what to do; a body for another endpoint names it") {
  ServerConfig config;
  config.max_points = 3;
  config.max_body_bytes = 2048;
  TestServer s(config);
  auto c = s.client();
  const std::string id = create(*c, kErrorsSurface.dump());
  const json many = error_of(*c, "POST", "/v1/geometries/" + id + "/project",
                             R"J({"points":[[1,2,2],[1,2,2],[1,2,2],[1,2,2]]})J", 413);
  CHECK(many["code"] == "too_many_points");
  CHECK(many["field"] == "points");
  CHECK(std::string(many["message"]).find("more than 3 points") != std::string::npos);
  CHECK(std::string(many["message"]).find("--max-points") != std::string::npos);
  CHECK(std::string(many["message"]).find("split the batch into requests of at most 3 points") !=
        std::string::npos);
  const json large = error_of(*c, "POST", "/v1/geometries/" + id + "/project",
                              R"J({"point":[1,2,2],"method":")J" + std::string(3000, 'a') + "\"}", 413);
  CHECK(large["code"] == "body_too_large");
  CHECK(large["field"] == "body");
  CHECK(std::string(large["message"]).find("over the limit of 2048 (--max-body-bytes)") != std::string::npos);
  CHECK(std::string(large["message"]).find("split the batch") != std::string::npos);

  c = s.client();  // the server closed the connection after the body it did not read
  const json to_geometries = error_of(*c, "POST", "/v1/geometries",
                                      json{{"geometry", kErrorsSurface}, {"point", {1, 2, 2}}}.dump(), 400);
  CHECK(to_geometries["code"] == "unknown_field");
  CHECK(to_geometries["field"] == "geometry");
  CHECK(std::string(to_geometries["message"]).find("POST /v1/project") != std::string::npos);
  // A definition with a point, its members first (as a client would write it).
  const std::string definition_with_point =
      R"J({"type":"parametric_surface","x":"u","y":"v","z":"0","domain":{"u":[0,1],"v":[0,1]},"point":[1,2,2]})J";
  const json definition_inline = error_of(*c, "POST", "/v1/project", definition_with_point, 400);
  CHECK(definition_inline["code"] == "unknown_field");
  CHECK(definition_inline["field"] == "type");
  CHECK(std::string(definition_inline["message"]).find("under \"geometry\"") != std::string::npos);
  const json definition_by_id =
      error_of(*c, "POST", "/v1/geometries/" + id + "/project", definition_with_point, 400);
  CHECK(definition_by_id["field"] == "type");
  CHECK(std::string(definition_by_id["message"]).find("POST /v1/geometries") != std::string::npos);
}
