// POST /v1/geometries/{id}/evaluate: points, exact first and second derivatives and unit normals
// of parametric surfaces and curves at given parameters, and the equations of implicit surfaces
// and curves (values, gradients, Hessians, normals) at given points, against closed forms; and
// its errors.
#include <doctest/doctest.h>

#include <cmath>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "server_support.hpp"

using namespace footpoint::server;
using namespace footpoint::server::testing;
using json = nlohmann::json;

namespace {

json evaluate(httplib::Client& c, const std::string& id, const json& body, int status = 200) {
  auto r = c.Post("/v1/geometries/" + id + "/evaluate", body.dump(), "application/json");
  REQUIRE(r);
  INFO(r->body);
  REQUIRE(r->status == status);
  return json::parse(r->body);
}

void check_near(const json& got, const std::vector<double>& want, double tolerance = 1e-15) {
  REQUIRE(got.size() == want.size());
  for (std::size_t k = 0; k < want.size(); ++k) CHECK(std::fabs(got[k].get<double>() - want[k]) <= tolerance);
}

}  // namespace

TEST_CASE("evaluate a surface: point, derivatives, second derivatives, unit normal, inside the domain") {
  TestServer s;
  auto c = s.client();
  // s(u, v) = (u, v, u^2 + 3uv): s_u = (1, 0, 2u + 3v), s_v = (0, 1, 3u), s_uu = (0, 0, 2),
  // s_uv = (0, 0, 3), s_vv = 0, normal (-(2u + 3v), -3u, 1) / |...|.
  const std::string id = create(
      *c,
      R"J({"type":"parametric_surface","x":"u","y":"v","z":"u^2+3*u*v","domain":{"u":[-1,1],"v":[-1,3]}})J");
  const json r = evaluate(*c, id, {{"parameters", {{1, 2}, {-2, 0}}}, {"derivatives", 2}, {"normals", true}});
  REQUIRE(r["results"].size() == 2);
  const json& a = r["results"][0];
  CHECK(a["parameters"] == json::array({1, 2}));
  check_near(a["point"], {1, 2, 7});
  CHECK(a["inside_domain"] == true);
  check_near(a["derivatives"]["u"], {1, 0, 8});
  check_near(a["derivatives"]["v"], {0, 1, 3});
  check_near(a["second_derivatives"]["uu"], {0, 0, 2});
  check_near(a["second_derivatives"]["uv"], {0, 0, 3});
  check_near(a["second_derivatives"]["vv"], {0, 0, 0});
  const double n = std::sqrt(74.0);
  check_near(a["normal"], {-8 / n, -3 / n, 1 / n});
  const json& b = r["results"][1];
  CHECK(b["inside_domain"] == false);  // u = -2 is outside [-1, 1]: the formulas still answer
  check_near(b["point"], {-2, 0, 4});
  CHECK(r["stats"] == json{{"parameters", 2}, {"inside_domain", 1}});

  // Without options: the point alone.
  const json plain = evaluate(*c, id, {{"parameter", {0.5, 0.5}}});
  std::set<std::string> keys;
  for (const auto& [k, v] : plain["result"].items()) keys.insert(k);
  CHECK(keys == std::set<std::string>{"parameters", "point", "inside_domain"});
  check_near(plain["result"]["point"], {0.5, 0.5, 1.0});
}

TEST_CASE("evaluate curves: a helix's principal normal, a planar curve in 2-D, a line without normal") {
  TestServer s;
  auto c = s.client();
  const std::string helix = create(
      *c, R"J({"type":"parametric_curve","x":"cos(t)","y":"sin(t)","z":"t/4","domain":{"t":[0,"4*_pi"]}})J");
  const json h = evaluate(*c, helix, {{"parameter", {0}}, {"derivatives", 2}, {"normals", true}});
  check_near(h["result"]["point"], {1, 0, 0});
  check_near(h["result"]["derivatives"]["t"], {0, 1, 0.25});
  check_near(h["result"]["second_derivatives"]["tt"], {-1, 0, 0});
  check_near(h["result"]["normal"], {-1, 0, 0});  // towards the axis

  // (t, t^2) at t = 1: c' = (1, 2), c'' = (0, 2), principal normal (-2, 1) / sqrt(5).
  const std::string parabola =
      create(*c, R"J({"type":"parametric_curve","x":"t","y":"t^2","domain":{"t":[-2,2]}})J");
  const json p = evaluate(*c, parabola, {{"parameter", {1}}, {"derivatives", 1}, {"normals", true}});
  check_near(p["result"]["point"], {1, 1});
  check_near(p["result"]["derivatives"]["t"], {1, 2});
  CHECK_FALSE(p["result"].contains("second_derivatives"));
  check_near(p["result"]["normal"], {-2 / std::sqrt(5.0), 1 / std::sqrt(5.0)}, 2e-16);

  const std::string line =
      create(*c, R"J({"type":"parametric_curve","x":"1+t","y":"2*t","domain":{"t":[0,1]}})J");
  CHECK(evaluate(*c, line, {{"parameter", {0.5}}, {"normals", true}})["result"]["normal"].is_null());
}

TEST_CASE("evaluate: every bad request its status, code and field") {
  ServerConfig config;
  config.max_points = 3;
  TestServer s(config);
  auto c = s.client();
  const std::string surface = create(
      *c, R"J({"type":"parametric_surface","x":"u","y":"v","z":"u*v","domain":{"u":[0,1],"v":[0,1]}})J");
  const std::string implicit =
      create(*c, R"J({"type":"implicit_curve","equations":["x^2+y^2-1"],"domain":{"x":[-2,2],"y":[-2,2]}})J");
  struct Case {
    std::string id;
    json body;
    int status;
    const char* code;
    const char* field;
  };
  const std::vector<Case> cases = {
      {implicit, {{"parameter", {1}}}, 400, "not_parametric", "parameter"},
      {implicit, {{"parameters", {{1, 2}}}}, 400, "not_parametric", "parameters"},
      {implicit, {{"point", {1, 2, 3}}}, 400, "wrong_dimension", "point"},
      {surface, {{"parameter", {1}}}, 400, "wrong_dimension", "parameter"},
      {surface, {{"parameters", {{1, 2, 3}}}}, 400, "wrong_dimension", "parameters[0]"},
      {surface, {{"parameters", {{1, 2}, {1}}}}, 400, "wrong_dimension", "parameters[1]"},
      {surface, {{"parameters", {{1, 2}, {1, 2}, {1, 2}, {1, 2}}}}, 413, "too_many_points", "parameters"},
      {surface, {{"parameters", json::array()}}, 400, "empty_batch", "parameters"},
      {surface, {{"parameter", {1, 2}}, {"derivatives", 3}}, 400, "invalid_option", "derivatives"},
      {surface, {{"parameter", {1, 2}}, {"normals", "yes"}}, 400, "wrong_type", "normals"},
      {surface, {{"point", {1, 2, 3}}}, 400, "not_implicit", "point"},
      {surface, {{"points", {{1, 2, 3}}}}, 400, "not_implicit", "points"},
      {surface, {{"parameter", {1, 2}}, {"point", {1, 2}}}, 400, "conflicting_fields", "point"},
      {surface, {{"parameter", {1, 2}}, {"values", 1}}, 400, "unknown_field", "values"},
      {surface, {{"derivatives", 1}}, 400, "missing_field", "parameter"},
      {surface, {{"parameter", {1, 2}}, {"parameters", {{1, 2}}}}, 400, "conflicting_fields", "parameters"},
      {"0123456789abcdef0123456789abcdef", {{"parameter", {1, 2}}}, 404, "geometry_not_found", "id"},
      {"not-an-id", {{"parameter", {1, 2}}}, 400, "invalid_geometry_id", "id"},
  };
  for (const auto& k : cases) {
    CAPTURE(k.body.dump());
    const json e = evaluate(*c, k.id, k.body, k.status);
    CHECK(e["error"]["code"] == k.code);
    CHECK(e["error"]["field"] == k.field);
  }
  // The messages name the type with its article: "an implicit_curve".
  const json e = evaluate(*c, implicit, {{"parameter", {1}}}, 400);
  CHECK(e["error"]["message"].get<std::string>().rfind("an implicit_curve has no parameters", 0) == 0);
  auto p = c->Post("/v1/geometries/" + implicit + "/project",
                   json{{"point", {1, 2}}, {"options", {{"initial", {1, 2, 3}}}}}.dump(), "application/json");
  REQUIRE(p);
  CHECK(p->status == 400);
  CHECK(p->body.find("numbers for an implicit_curve") != std::string::npos);
  auto r = c->Get("/v1/geometries/" + surface + "/evaluate");
  REQUIRE(r);
  CHECK(r->status == 405);
  CHECK(r->get_header_value("Allow") == "POST");
}

TEST_CASE("evaluate implicit geometries: values, gradients, Hessians and normals at points") {
  TestServer s;
  auto c = s.client();
  // f = (x^2 + y^2 + z^2 - 1)^2 as written: grad f = 4 r (x, y, z), with r = x^2 + y^2 + z^2 - 1,
  // Hessian 8 x x^T + 4 r I; the normal is the square-free sphere's, (x, y, z) / |(x, y, z)|, also
  // on the surface where the written gradient vanishes.
  const std::string sphere = create(
      *c,
      R"J({"type":"implicit_surface","equation":"(x^2+y^2+z^2-1)^2","domain":{"x":[-2,2],"y":[-2,2],"z":[-2,2]}})J");
  const json r =
      evaluate(*c, sphere, {{"points", {{1, 2, 3}, {0.6, 0.8, 0}}}, {"derivatives", 2}, {"normals", true}});
  REQUIRE(r["results"].size() == 2);
  const json& a = r["results"][0];
  check_near(a["point"], {1, 2, 3});
  CHECK(a["inside_box"] == false);  // z = 3 is outside [-2, 2]: the equation still answers
  CHECK(a["value"].get<double>() == 169.0);
  check_near(a["gradient"], {52, 104, 156});
  check_near(a["hessian"][0], {8 + 52, 16, 24});
  check_near(a["hessian"][1], {16, 32 + 52, 48});
  check_near(a["hessian"][2], {24, 48, 72 + 52});
  const double n = std::sqrt(14.0);
  check_near(a["normal"], {1 / n, 2 / n, 3 / n});
  const json& b = r["results"][1];
  CHECK(b["inside_box"] == true);
  CHECK(std::fabs(b["value"].get<double>()) <= 1e-30);
  check_near(b["gradient"], {0, 0, 0}, 1e-15);
  check_near(b["normal"], {0.6, 0.8, 0}, 1e-15);
  CHECK(r["stats"] == json{{"points", 2}, {"inside_box", 1}});
  // Without options: the point, inside_box and the value.
  const json plain = evaluate(*c, sphere, {{"point", {0, 0, 0}}});
  std::set<std::string> keys;
  for (const auto& [k, v] : plain["result"].items()) keys.insert(k);
  CHECK(keys == std::set<std::string>{"point", "inside_box", "value"});
  CHECK(plain["result"]["value"] == 1.0);

  // A planar curve in 2-D: f = x^2 + y^2 - 1 at (1, 2): 4, (2, 4), [[2, 0], [0, 2]].
  const std::string circle =
      create(*c, R"J({"type":"implicit_curve","equations":["x^2+y^2-1"],"domain":{"x":[-2,2],"y":[-2,2]}})J");
  const json p = evaluate(*c, circle, {{"point", {1, 2}}, {"derivatives", 2}, {"normals", true}});
  CHECK(p["result"]["value"] == 4.0);
  check_near(p["result"]["gradient"], {2, 4});
  check_near(p["result"]["hessian"][0], {2, 0});
  check_near(p["result"]["hessian"][1], {0, 2});
  check_near(p["result"]["normal"], {1 / std::sqrt(5.0), 2 / std::sqrt(5.0)}, 2e-16);

  // A space curve: two values, two gradients, two Hessians, no normal (a plane of them).
  const std::string space = create(
      *c,
      R"J({"type":"implicit_curve","equations":["x^2+y^2-1","x*z"],"domain":{"x":[-2,2],"y":[-2,2],"z":[-2,2]}})J");
  const json q = evaluate(*c, space, {{"point", {1, 2, 3}}, {"derivatives", 2}, {"normals", true}});
  check_near(q["result"]["values"], {4, 3});
  check_near(q["result"]["gradients"][0], {2, 4, 0});
  check_near(q["result"]["gradients"][1], {3, 0, 1});
  check_near(q["result"]["hessians"][0][0], {2, 0, 0});
  check_near(q["result"]["hessians"][1][0], {0, 0, 1});
  check_near(q["result"]["hessians"][1][2], {1, 0, 0});
  CHECK(q["result"]["normal"].is_null());
}
