// Seams, poles and closed curves over HTTP: POST /v1/geometries and GET /v1/geometries/{id} report
// the closure found at compile time (torus, sphere, cone, Möbius band, plane, circle, helix; none
// for implicit curves) and a surface's translations ([GSA] Ex. 1 over [-25,25]^2); "periodic" is read,
// validated (400 for an unknown or repeated name, 422 for a direction whose edges do not coincide), written
// back in the definition and part of the id only when present, so that the ids of definitions without it stay
// what they were.
#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include <nlohmann/json.hpp>

#include "server_support.hpp"

using namespace footpoint::server;
using namespace footpoint::server::testing;
using json = nlohmann::json;

namespace {

const std::string kTwoPi = "6.283185307179586";

std::string surface(const std::string& x, const std::string& y, const std::string& z, const std::string& u,
                    const std::string& v, const std::string& extra = "") {
  return R"J({"type":"parametric_surface","x":")J" + x + R"J(","y":")J" + y + R"J(","z":")J" + z +
         R"J(","domain":{"u":)J" + u + R"J(,"v":)J" + v + "}" + extra + "}";
}

const std::string kTorus = surface("(2+0.5*cos(v))*cos(u)", "(2+0.5*cos(v))*sin(u)", "0.5*sin(v)",
                                   "[0," + kTwoPi + "]", "[0," + kTwoPi + "]");

json post(httplib::Client& c, const std::string& path, const std::string& body, int expected) {
  auto r = c.Post(path, body, "application/json");
  REQUIRE(r);
  INFO(body << " -> " << r->body);
  REQUIRE(r->status == expected);
  return json::parse(r->body);
}

json get(httplib::Client& c, const std::string& path) {
  auto r = c.Get(path);
  REQUIRE(r);
  REQUIRE(r->status == 200);
  return json::parse(r->body);
}

// The error of a refused definition: its code and field.
void check_error(const json& body, const std::string& code, const std::string& field) {
  CHECK(body["error"]["code"] == code);
  CHECK(body["error"]["field"] == field);
}

}  // namespace

TEST_CASE("the closure of each geometry, in the POST response and in GET /v1/geometries/{id}") {
  TestServer s;
  auto c = s.client();

  const json torus = post(*c, "/v1/geometries", kTorus, 201);
  const json info = get(*c, "/v1/geometries/" + torus["geometry_id"].get<std::string>());
  CHECK(info["closure"] == torus["closure"]);
  const json& t = torus["closure"];
  CHECK(t["periodic"] == json::array({"u", "v"}));
  CHECK(t["declared"] == json::array());
  CHECK(t["poles"] == json::array());
  REQUIRE(t["seams"].size() == 2);
  for (const json& seam : t["seams"]) {
    CHECK(seam["reversed"] == false);
    CHECK(seam["smooth"] == true);
    CHECK(seam["max_gap"].get<double>() <= t["tolerance"].get<double>());
    CHECK(seam["gap_bound"].get<double>() >= seam["max_gap"].get<double>());
  }
  CHECK(!info["definition"].contains("periodic"));

  const json sphere = post(*c, "/v1/geometries",
                           surface("cos(u)*cos(v)", "sin(u)*cos(v)", "sin(v)", "[0," + kTwoPi + "]",
                                   "[-1.5707963267948966,1.5707963267948966]"),
                           201)["closure"];
  CHECK(sphere["periodic"] == json::array({"u"}));
  REQUIRE(sphere["poles"].size() == 2);
  CHECK(sphere["poles"][0]["edge"] == "v=vmin");
  CHECK(sphere["poles"][1]["edge"] == "v=vmax");
  CHECK(std::abs(sphere["poles"][0]["point"][2].get<double>() + 1.0) <= 1e-15);
  CHECK(std::abs(sphere["poles"][1]["point"][2].get<double>() - 1.0) <= 1e-15);
  CHECK(sphere["poles"][1]["radius_bound"].get<double>() <= 1e-14);

  const json cone = post(*c, "/v1/geometries",
                         surface("v*cos(u)", "v*sin(u)", "v", "[0," + kTwoPi + "]", "[0,1]"), 201)["closure"];
  REQUIRE(cone["poles"].size() == 1);
  CHECK(cone["poles"][0] == json{{"edge", "v=vmin"}, {"point", {0, 0, 0}}, {"radius_bound", 0}});

  const json band = post(*c, "/v1/geometries",
                         surface("(1+v*cos(u/2))*cos(u)", "(1+v*cos(u/2))*sin(u)", "v*sin(u/2)",
                                 "[0," + kTwoPi + "]", "[-0.5,0.5]"),
                         201)["closure"];
  CHECK(band["periodic"] == json::array());
  REQUIRE(band["seams"].size() == 1);
  CHECK(band["seams"][0]["direction"] == "u");
  CHECK(band["seams"][0]["reversed"] == true);

  const json plane = post(*c, "/v1/geometries", surface("u", "v", "u*v", "[-1,1]", "[-1,1]"), 201)["closure"];
  CHECK(plane["periodic"] == json::array());
  CHECK(plane["seams"] == json::array());
  CHECK(plane["poles"] == json::array());
  CHECK(plane["translations"] == json::array());
  CHECK(t["translations"] == json::array());  // one period each way: no translate inside the box

  // [GSA] Ex. 1 over [-25,25]^2 repeats along k (2π, -2π), k = 1..7
  const json a1 =
      post(*c, "/v1/geometries", surface("u+v", "sin(u)+2*cos(v)", "sin(u+v)", "[-25,25]", "[-25,25]"), 201);
  const json& moves = a1["closure"]["translations"];
  REQUIRE(moves.size() == 7);
  for (int k = 0; k < 7; ++k) {
    CHECK(moves[k][0].get<double>() == doctest::Approx(2.0 * M_PI * (k + 1)).epsilon(1e-15));
    CHECK(moves[k][1].get<double>() == doctest::Approx(-2.0 * M_PI * (k + 1)).epsilon(1e-15));
  }
  CHECK(get(*c, "/v1/geometries/" + a1["geometry_id"].get<std::string>())["closure"] == a1["closure"]);
  // all_minima names every parameter copy of a foot point: at least the answer's translates
  // (u + 2πk, v - 2πk) in the box, each giving the foot point.
  const json answer = post(*c, "/v1/geometries/" + a1["geometry_id"].get<std::string>() + "/project",
                           R"J({"point":[0.3,1.1,-0.4],"options":{"all_minima":true}})J", 200);
  const json& nearest = answer["result"]["minima"][0];
  REQUIRE(nearest["parameter_copies"].size() >= 7);
  CHECK(nearest["copies_truncated"] == false);
  for (const json& t : nearest["parameter_copies"]) {
    const double u = t[0], v = t[1];
    CHECK(u + v == doctest::Approx(nearest["foot_point"][0].get<double>()).epsilon(1e-12));
    CHECK(std::sin(u) + 2 * std::cos(v) ==
          doctest::Approx(nearest["foot_point"][1].get<double>()).epsilon(1e-12));
  }

  const json circle =
      post(*c, "/v1/geometries",
           R"J({"type":"parametric_curve","x":"cos(t)","y":"sin(t)","domain":{"t":[0,)J" + kTwoPi + "]}}",
           201)["closure"];
  CHECK(circle["periodic"] == json::array({"t"}));
  REQUIRE(circle["seams"].size() == 1);
  CHECK(circle["seams"][0]["smooth"] == true);
  const json helix =
      post(*c, "/v1/geometries",
           R"J({"type":"parametric_curve","x":"cos(t)","y":"sin(t)","z":"t/4","domain":{"t":[0,12]}})J",
           201)["closure"];
  CHECK(helix["periodic"] == json::array());
  CHECK(helix["seams"] == json::array());

  const json implicit =
      post(*c, "/v1/geometries",
           R"J({"type":"implicit_curve","equations":["x^2+y^2-1"],"domain":{"x":[-2,2],"y":[-2,2]}})J", 201);
  CHECK(!implicit.contains("closure"));
}

TEST_CASE("periodic: declared, written back, part of the id only when present") {
  TestServer s;
  auto c = s.client();
  // The id of this definition, as it was before periodic existed (tests/core/compiled/sha256_test.cpp pins it
  // too).
  const std::string s1 = surface("u+v", "sin(u)+2*cos(v)", "sin(u+v)", "[-3,3]", "[-3,3]");
  CHECK(create(*c, s1) == "6eb4132bf22f865049048bc1e2fc6ee9");
  CHECK(create(*c, surface("u+v", "sin(u)+2*cos(v)", "sin(u+v)", "[-3,3]", "[-3,3]",
                           R"J(,"periodic":[])J")) == "6eb4132bf22f865049048bc1e2fc6ee9");

  const std::string plain = create(*c, kTorus);
  const std::string torus_vu = kTorus.substr(0, kTorus.size() - 1) + R"J(,"periodic":["v","u"]})J";
  const json declared = post(*c, "/v1/geometries", torus_vu, 201);
  const std::string id = declared["geometry_id"];
  CHECK(id != plain);
  CHECK(declared["closure"]["declared"] == json::array({"u", "v"}));
  CHECK(declared["closure"]["periodic"] == json::array({"u", "v"}));
  const json info = get(*c, "/v1/geometries/" + id);
  CHECK(info["definition"]["periodic"] == json::array({"u", "v"}));
  // The definition as GET returns it posts to the same id.
  CHECK(create(*c, info["definition"].dump()) == id);

  const json curve = post(*c, "/v1/geometries",
                          R"J({"type":"parametric_curve","x":"cos(t)","y":"sin(t)","domain":{"t":[0,)J" +
                              kTwoPi + R"J(]},"periodic":["t"]})J",
                          201);
  CHECK(curve["closure"]["declared"] == json::array({"t"}));
}

TEST_CASE("periodic refused: unknown or repeated names 400, edges that do not coincide 422") {
  TestServer s;
  auto c = s.client();
  const std::string plane = surface("u", "v", "u*v", "[-1,1]", "[-1,1]", R"J(,"periodic":["u"])J");
  const json not_periodic = post(*c, "/v1/geometries", plane, 422);
  check_error(not_periodic, "not_periodic", "periodic");
  CHECK(not_periodic["error"]["message"].get<std::string>().find("u = umin and u = umax are") !=
        std::string::npos);
  check_error(post(*c, "/v1/project", R"J({"geometry":)J" + plane + R"J(,"point":[0,0,1]})J", 422),
              "not_periodic", "geometry.periodic");
  const std::string helix =
      R"J({"type":"parametric_curve","x":"cos(t)","y":"sin(t)","z":"t","domain":{"t":[0,12]},"periodic":["t"]})J";
  check_error(post(*c, "/v1/geometries", helix, 422), "not_periodic", "periodic");

  const std::string torus = kTorus.substr(0, kTorus.size() - 1);
  check_error(post(*c, "/v1/geometries", torus + R"J(,"periodic":["w"]})J", 400), "unknown_parameter",
              "periodic[0]");
  check_error(post(*c, "/v1/geometries", torus + R"J(,"periodic":["u","t"]})J", 400), "unknown_parameter",
              "periodic[1]");
  check_error(post(*c, "/v1/geometries", torus + R"J(,"periodic":["u","u"]})J", 400), "duplicate_parameter",
              "periodic[1]");
  check_error(post(*c, "/v1/geometries", torus + R"J(,"periodic":["u","v","u"]})J", 400), "wrong_shape",
              "periodic");
  check_error(post(*c, "/v1/geometries", torus + R"J(,"periodic":"u"})J", 400), "wrong_type", "periodic");
  check_error(post(*c, "/v1/geometries", torus + R"J(,"periodic":[1]})J", 400), "wrong_type", "periodic[0]");
  check_error(post(*c, "/v1/geometries",
                   R"J({"type":"implicit_curve","equations":["x^2+y^2-1"],"domain":{"x":[-2,2],"y":[-2,2]},)J"
                   R"J("periodic":["x"]})J",
                   400),
              "unknown_field", "periodic");
  check_error(
      post(*c, "/v1/geometries",
           R"J({"type":"parametric_curve","x":"cos(t)","y":"sin(t)","domain":{"t":[0,1]},"periodic":["u"]})J",
           400),
      "unknown_parameter", "periodic[0]");
}

TEST_CASE("answers on a seam name the lower bound of the periodic direction, the minima too") {
  TestServer s;
  auto c = s.client();
  auto project = [&](const std::string& definition, const json& point) {
    const std::string path = "/v1/geometries/" + create(*c, definition) + "/project";
    return post(*c, path, json{{"point", point}, {"options", {{"all_minima", true}}}}.dump(), 200)["result"];
  };
  // The torus's outer equator meets both seams at (2.5, 0, 0): u = v = 0 (not 2π).
  const json torus = project(kTorus, {5, 0, 0});
  CHECK(torus["diagnostics"]["status"] == "converged");
  CHECK(torus["parameters"] == json{0.0, 0.0});
  CHECK(torus["minima"][0]["parameters"] == json{0.0, 0.0});
  CHECK(torus["minima"][0]["parameter_copies"].size() == 4);  // (0 or 2π, 0 or 2π)

  const std::string sphere =
      surface("cos(u)*sin(v)", "sin(u)*sin(v)", "cos(v)", "[0," + kTwoPi + "]", "[0,3.141592653589793]");
  const json on_sphere = project(sphere, {5, 0, 0});
  CHECK(on_sphere["diagnostics"]["status"] == "converged");
  CHECK(on_sphere["parameters"][0] == 0.0);
  CHECK(on_sphere["parameters"][1].get<double>() == doctest::Approx(M_PI / 2).epsilon(1e-12));

  const json circle = project(
      R"J({"type":"parametric_curve","x":"cos(t)","y":"sin(t)","domain":{"t":[0,"2*_pi"]}})J", {2, 0});
  CHECK(circle["diagnostics"]["status"] == "converged");
  CHECK(circle["parameters"] == json{0.0});
  CHECK(circle["minima"][0]["parameters"] == json{0.0});
}
