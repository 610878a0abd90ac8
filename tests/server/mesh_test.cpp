// GET /v1/geometries/{id}/mesh end to end: the JSON mesh is the core's mesh, number for number
// (shortest round-trip doubles), the OBJ file holds the same vertices, normals, faces and
// polylines, a sphere's mesh read back from JSON has the sphere's area, and every bad query gets
// its 400 (unknown or repeated parameter, resolution not an integer or out of range, unknown
// format), an unknown id 404, a POST 405.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "mesh/mesh.hpp"
#include "server_support.hpp"

using namespace footpoint;
using namespace footpoint::server;
using namespace footpoint::server::testing;
using json = nlohmann::json;

namespace {

const char* const kSphere =
    R"J({"type":"parametric_surface","x":"R*sin(u)*cos(v)","y":"R*sin(u)*sin(v)","z":"R*cos(u)",)J"
    R"J("domain":{"u":[0,3.141592653589793],"v":[0,6.283185307179586]},"constants":{"R":1.5}})J";
const char* const kLemniscate =
    R"J({"type":"implicit_curve","equations":["(x^2+y^2)^2-2*(x^2-y^2)"],"domain":{"x":[-2,2],"y":[-1.5,1.5]}})J";
const char* const kHelix =
    R"J({"type":"parametric_curve","x":"cos(t)","y":"sin(t)","z":"t/4","domain":{"t":[0,12.566370614359172]}})J";

json get_json(httplib::Client& c, const std::string& path, int expected = 200) {
  auto r = c.Get(path.c_str());
  REQUIRE(r);
  INFO(path << " -> " << r->body.substr(0, 400));
  REQUIRE(r->status == expected);
  CHECK(r->get_header_value("Content-Type") == "application/json");
  return json::parse(r->body);
}

Mesh core_mesh(const std::string& definition_text, int resolution) {
  // The same definition compiled in-process: the server's mesh must be this one.
  const json d = json::parse(definition_text);
  GeometryDefinition def;
  if (d["type"] == "parametric_surface") {
    def.type = GeometryType::parametric_surface;
    def.formulas = {{"x", d["x"]}, {"y", d["y"]}, {"z", d["z"]}};
    def.domain = {{"u", {d["domain"]["u"][0], d["domain"]["u"][1]}},
                  {"v", {d["domain"]["v"][0], d["domain"]["v"][1]}}};
  } else {
    def.type = GeometryType::implicit_curve;
    def.formulas = {{"equations[0]", d["equations"][0]}};
    def.domain = {{"x", {d["domain"]["x"][0], d["domain"]["x"][1]}},
                  {"y", {d["domain"]["y"][0], d["domain"]["y"][1]}}};
  }
  if (d.contains("constants"))
    for (const auto& [k, v] : d["constants"].items()) def.constants[k] = v;
  return mesh_geometry(*compile_geometry(def), MeshOptions{resolution});
}

}  // namespace

TEST_CASE("mesh JSON: the core's mesh number for number; the sphere's area within 1 %") {
  TestServer s;
  auto c = s.client();
  const std::string id = create(*c, kSphere);
  const json m = get_json(*c, "/v1/geometries/" + id + "/mesh?resolution=48");
  CHECK(m["geometry_id"] == id);
  CHECK(m["type"] == "parametric_surface");
  CHECK(m["point_dim"] == 3);
  CHECK(m["resolution"] == 48);
  const Mesh expected = core_mesh(kSphere, 48);
  REQUIRE(m["vertices"].size() == 3 * expected.vertices.size());
  REQUIRE(m["normals"].size() == 3 * expected.normals.size());
  REQUIRE(m["parameters"].size() == 2 * expected.vertices.size());
  REQUIRE(m["triangles"].size() == 3 * expected.triangles.size());
  CHECK(m["polylines"].empty());
  CHECK(m["singular_points"].empty());
  CHECK_FALSE(m.contains("tangents"));
  for (std::size_t k = 0; k < expected.vertices.size(); ++k)
    for (int c3 = 0; c3 < 3; ++c3) {
      CHECK(m["vertices"][3 * k + c3].get<double>() == expected.vertices[k][c3]);
      CHECK(m["normals"][3 * k + c3].get<double>() == expected.normals[k][c3]);
    }
  double area = 0.0;
  const auto& v = m["vertices"];
  const auto& t = m["triangles"];
  for (std::size_t i = 0; i < t.size(); i += 3) {
    auto at = [&](std::size_t j) {
      const std::size_t k = t[i + j].get<std::size_t>();
      return Vec3{v[3 * k].get<double>(), v[3 * k + 1].get<double>(), v[3 * k + 2].get<double>()};
    };
    area += 0.5 * norm(cross(at(1) - at(0), at(2) - at(0)));
  }
  const double exact = 4 * std::numbers::pi * 1.5 * 1.5;
  CHECK(std::abs(area - exact) <= 0.01 * exact);
}

TEST_CASE("mesh JSON of curves: polylines, tangents, parameters and singular points") {
  TestServer s;
  auto c = s.client();
  const json lemniscate = get_json(*c, "/v1/geometries/" + create(*c, kLemniscate) + "/mesh?resolution=300");
  const Mesh expected = core_mesh(kLemniscate, 300);
  CHECK(lemniscate["point_dim"] == 2);
  CHECK(lemniscate["triangles"].empty());
  CHECK_FALSE(lemniscate.contains("parameters"));
  CHECK_FALSE(lemniscate.contains("normals"));
  REQUIRE(lemniscate["polylines"].size() == expected.polylines.size());
  for (std::size_t i = 0; i < expected.polylines.size(); ++i) {
    CHECK(lemniscate["polylines"][i]["closed"] == expected.polylines[i].closed);
    CHECK(lemniscate["polylines"][i]["vertices"].get<std::vector<std::int32_t>>() ==
          expected.polylines[i].vertices);
  }
  CHECK(lemniscate["singular_points"].get<std::vector<std::int32_t>>() == expected.singular_points);
  CHECK(lemniscate["tangents"].size() == lemniscate["vertices"].size());

  const json helix = get_json(*c, "/v1/geometries/" + create(*c, kHelix) + "/mesh");
  CHECK(helix["resolution"] == 512);  // a curve's default
  CHECK(helix["parameters"].size() == 513);
  CHECK(helix["polylines"][0]["vertices"].size() == 513);
  for (std::size_t k = 0; k < 513; ++k) {
    const double t = helix["parameters"][k];
    CHECK(helix["vertices"][3 * k].get<double>() == doctest::Approx(std::cos(t)).epsilon(1e-15));
    CHECK(helix["vertices"][3 * k + 2].get<double>() == doctest::Approx(t / 4).epsilon(1e-15));
  }
}

TEST_CASE("mesh OBJ: the JSON mesh's vertices, normals, faces and polylines") {
  TestServer s;
  auto c = s.client();
  const std::string id = create(*c, kSphere);
  const json m = get_json(*c, "/v1/geometries/" + id + "/mesh?resolution=12");
  auto r = c->Get(("/v1/geometries/" + id + "/mesh?format=obj&resolution=12").c_str());
  REQUIRE(r);
  REQUIRE(r->status == 200);
  CHECK(r->get_header_value("Content-Type") == "model/obj");
  CHECK(r->get_header_value("Content-Disposition") == "attachment; filename=\"footpoint-" + id + ".obj\"");
  std::istringstream in(r->body);
  std::string line;
  std::vector<double> v, vn;
  std::vector<std::size_t> f;
  while (std::getline(in, line)) {
    std::istringstream words(line);
    std::string tag;
    words >> tag;
    if (tag == "v" || tag == "vn") {
      for (int k = 0; k < 3; ++k) {
        std::string x;
        words >> x;
        (tag == "v" ? v : vn).push_back(std::stod(x));
      }
    } else if (tag == "f") {
      for (int k = 0; k < 3; ++k) {
        std::string ref;
        words >> ref;
        const auto slashes = ref.find("//");
        REQUIRE(slashes != std::string::npos);
        CHECK(ref.substr(0, slashes) == ref.substr(slashes + 2));  // the vertex's own normal
        f.push_back(std::stoul(ref.substr(0, slashes)) - 1);       // 1-based
      }
    } else {
      CHECK((tag == "#" || tag == "o"));
    }
  }
  CHECK(v == m["vertices"].get<std::vector<double>>());
  CHECK(vn == m["normals"].get<std::vector<double>>());
  CHECK(f == m["triangles"].get<std::vector<std::size_t>>());

  // A closed polyline repeats its first vertex; singular points are `p` lines.
  auto lemniscate =
      c->Get(("/v1/geometries/" + create(*c, kLemniscate) + "/mesh?format=obj&resolution=64").c_str());
  REQUIRE(lemniscate);
  const std::string& obj = lemniscate->body;
  CHECK(obj.find("\nl ") != std::string::npos);
  CHECK(obj.find("\np ") != std::string::npos);
  CHECK(obj.find("\nf ") == std::string::npos);
  CHECK(obj.find("\nvn ") == std::string::npos);
}

TEST_CASE("mesh: every bad query its 400, an unknown id 404, POST 405, the resolution bound") {
  ServerConfig config;
  config.max_mesh_resolution = 40;
  TestServer s(config);
  auto c = s.client();
  const std::string base = "/v1/geometries/" + create(*c, kSphere) + "/mesh";
  const struct {
    const char* query;
    const char* code;
    const char* field;
  } bad[] = {
      {"?resolution=1", "number_out_of_range", "resolution"},
      {"?resolution=41", "number_out_of_range", "resolution"},
      {"?resolution=-5", "number_out_of_range", "resolution"},
      {"?resolution=99999999999999999999", "number_out_of_range", "resolution"},
      {"?resolution=abc", "wrong_type", "resolution"},
      {"?resolution=3.5", "wrong_type", "resolution"},
      {"?resolution=", "wrong_type", "resolution"},
      {"?resolution=4&resolution=5", "duplicate_field", "resolution"},
      {"?format=ply", "unknown_format", "format"},
      {"?format=obj&format=json", "duplicate_field", "format"},
      {"?colour=red", "unknown_field", "colour"},
      {"?%72esolution=1", "number_out_of_range", "resolution"},  // percent-decoded
  };
  for (const auto& b : bad) {
    const json e = get_json(*c, base + b.query, 400);
    CHECK(e["error"]["code"] == b.code);
    CHECK(e["error"]["field"] == b.field);
  }
  // Without a resolution: the default, capped by the bound.
  CHECK(get_json(*c, base)["resolution"] == 40);
  CHECK(get_json(*c, base + "?format=json&resolution=40")["resolution"] == 40);
  CHECK(get_json(*c, "/v1/geometries/00000000000000000000000000000000/mesh", 404)["error"]["code"] ==
        "geometry_not_found");
  auto post = c->Post(base.c_str(), "{}", "application/json");
  REQUIRE(post);
  CHECK(post->status == 405);
  CHECK(post->get_header_value("Allow") == "GET, HEAD");
  auto head = c->Head(base.c_str());
  REQUIRE(head);
  CHECK(head->status == 200);
  CHECK(head->body.empty());
}
