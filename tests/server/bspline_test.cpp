// B-spline and NURBS definitions over HTTP: posted, read back as posted, projected (the NURBS
// circle's closed form), evaluated at a knot (the circle's point at 45 degrees), meshed (every
// vertex on the circle), and every refusal: a wrong shape (400 naming the element), a bad net
// (422 bad_bspline naming the field), a formula member on a B-spline and a net member on a
// formula geometry (400 unknown_field).
#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include <nlohmann/json.hpp>

#include "server_support.hpp"

using namespace footpoint::server;
using namespace footpoint::server::testing;
using json = nlohmann::json;

namespace {

const char* const kNurbsCircle =
    R"J({"type":"bspline_curve","degree":2,"knots":[0,0,0,0.25,0.25,0.5,0.5,0.75,0.75,1,1,1],
    "control_points":[[2,0],[2,2],[0,2],[-2,2],[-2,0],[-2,-2],[0,-2],[2,-2],[2,0]],
    "weights":[1,0.7071067811865476,1,0.7071067811865476,1,0.7071067811865476,1,0.7071067811865476,1]})J";

json post_json(httplib::Client& c, const std::string& path, const std::string& body, int status) {
  auto r = c.Post(path, body, "application/json");
  REQUIRE(r);
  INFO(r->body);
  REQUIRE(r->status == status);
  return json::parse(r->body);
}

}  // namespace

TEST_CASE("a NURBS circle over HTTP: posted, read back, projected, evaluated, meshed") {
  TestServer s;
  auto c = s.client();
  const std::string id = create(*c, kNurbsCircle);
  auto got = c->Get("/v1/geometries/" + id);
  REQUIRE(got);
  const json g = json::parse(got->body);
  CHECK(g["definition"] == json::parse(kNurbsCircle));
  CHECK(g["methods"] == json::array({"auto", "newton", "curvature_circle"}));

  const json r =
      post_json(*c, "/v1/geometries/" + id + "/project", R"({"points":[[3,4],[0.3,-0.4],[2,0.001]]})", 200);
  const double want[3][2] = {{3, 4}, {0.3, -0.4}, {2, 0.001}};
  for (int k = 0; k < 3; ++k) {
    const json& a = r["results"][k];
    const double radius = std::hypot(want[k][0], want[k][1]);
    CHECK(std::fabs(a["distance"].get<double>() - std::fabs(radius - 2.0)) <= 1e-12);
    CHECK(std::fabs(a["foot_point"][0].get<double>() - 2.0 * want[k][0] / radius) <= 1e-12);
    CHECK(a["diagnostics"]["certificate"]["certified"] == true);
    CHECK(a["diagnostics"]["location"] == "interior");
  }

  const json e = post_json(*c, "/v1/geometries/" + id + "/evaluate", R"({"parameter":[0.125]})", 200);
  CHECK(std::fabs(e["result"]["point"][0].get<double>() - std::sqrt(2.0)) <= 1e-15);
  CHECK(std::fabs(e["result"]["point"][1].get<double>() - std::sqrt(2.0)) <= 1e-15);

  auto mesh = c->Get("/v1/geometries/" + id + "/mesh?resolution=16");
  REQUIRE(mesh);
  REQUIRE(mesh->status == 200);
  const json m = json::parse(mesh->body);
  const json& v = m["vertices"];
  REQUIRE(v.size() == 3 * 16);
  for (std::size_t k = 0; k < v.size(); k += 3)
    CHECK(std::fabs(std::hypot(v[k].get<double>(), v[k + 1].get<double>()) - 2.0) <= 1e-14);
  CHECK(m["polylines"][0]["closed"] == true);
}

TEST_CASE("B-spline refusals: shapes 400 naming the element, nets 422 bad_bspline, foreign members 400") {
  TestServer s;
  auto c = s.client();
  struct Case {
    const char* body;
    int status;
    const char* code;
    const char* field;
  };
  const Case cases[] = {
      {R"({"type":"bspline_curve","degree":2,"knots":[0,0,0,1,1],"control_points":[[0,0],[1,1],[2,0]]})", 422,
       "bad_bspline", "knots"},
      {R"({"type":"bspline_curve","degree":1,"knots":[0,0,1,1],"control_points":[[0,0],[1,1]],"weights":[1,0]})",
       422, "bad_bspline", "weights[1]"},
      {R"({"type":"bspline_curve","degree":1,"knots":[0,0,1,1],"control_points":[[0,0],[1,1,1]]})", 422,
       "bad_bspline", "control_points[1]"},
      {R"({"type":"bspline_curve","degree":1.5,"knots":[0,0,1,1],"control_points":[[0,0],[1,1]]})", 400,
       "wrong_type", "degree"},
      {R"({"type":"bspline_curve","degree":1,"knots":[0,0,1,1],"control_points":[[0,0],[1,[1]]]})", 400,
       "wrong_shape", "control_points[1][1]"},
      {R"({"type":"bspline_curve","degree":1,"knots":[0,0,1,1]})", 400, "missing_field", "control_points"},
      {R"({"type":"bspline_curve","degree":1,"knots":[0,0,1,1],"control_points":[[0,0],[1,1]],"x":"t"})", 400,
       "unknown_field", "x"},
      {R"({"type":"bspline_surface","degree":[1,1],"knots":[0,0,1,1],"control_points":[]})", 400,
       "wrong_shape", "knots"},
      {R"({"type":"bspline_surface","degree":[1,1],"knots":{"u":[0,0,1,1],"v":[0,0,1,1]},
          "control_points":[[[0,0,0],[0,1,0]],[[1,0,0]]]})",
       422, "bad_bspline", "control_points[1]"},
      {R"({"type":"bspline_surface","degree":[1,1],"knots":{"u":[0,0,1,1],"v":[0,0,2,1]},
          "control_points":[[[0,0,0],[0,1,0]],[[1,0,0],[1,1,0]]]})",
       422, "bad_bspline", "knots.v[3]"},
      {R"({"type":"parametric_curve","x":"t","y":"t","domain":{"t":[0,1]},"degree":2})", 400, "unknown_field",
       "degree"},
  };
  for (const Case& k : cases) {
    CAPTURE(k.body);
    const json e = post_json(*c, "/v1/geometries", k.body, k.status);
    CHECK(e["error"]["code"] == k.code);
    CHECK(e["error"]["field"] == k.field);
  }
  // Malformed JSON where the knots' kind (a list or an object of u and v) is read (request_fuzz).
  const json e = post_json(*c, "/v1/geometries", R"({"type":"bspline_curve","knots":knots":[0]})", 400);
  CHECK(e["error"]["code"] == "malformed_json");
}
