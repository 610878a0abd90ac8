// parse_canonical is the inverse of GeometryDefinition::canonical(): every reference geometry of
// the test data and the papers' cases goes text -> definition -> text unchanged and compiles from
// the parsed definition to the same projections, bit for bit; texts that are not canonical are
// refused.
#include <doctest/doctest.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "compiled/compiled_geometry.hpp"

using namespace footpoint;
using json = nlohmann::json;

namespace {

json canonical_read_json(const std::string& path) {
  std::ifstream in(path);
  REQUIRE_MESSAGE(in.good(), "cannot read " << path);
  std::stringstream ss;
  ss << in.rdbuf();
  return json::parse(ss.str());
}

std::vector<std::pair<std::string, std::array<double, 2>>> domain_of(const json& domain,
                                                                     const std::vector<std::string>& names) {
  std::vector<std::pair<std::string, std::array<double, 2>>> d;
  for (const auto& n : names)
    d.push_back({n, {domain.at(n)[0].get<double>(), domain.at(n)[1].get<double>()}});
  return d;
}

// A reference case as the definition a client would post for it.
GeometryDefinition definition_of(const json& c, const std::string& kind) {
  GeometryDefinition d;
  const json& f = c.at("formulas");
  if (kind == "surface") {
    d.type = GeometryType::parametric_surface;
    d.formulas = {{"x", f.at("x")}, {"y", f.at("y")}, {"z", f.at("z")}};
    d.domain = domain_of(c.at("domain"), {"u", "v"});
  } else if (kind == "paramcurve") {
    d.type = GeometryType::parametric_curve;
    d.formulas = {{"x", f.at("x")}, {"y", f.at("y")}};
    if (f.contains("z")) d.formulas.push_back({"z", f.at("z")});
    d.domain = domain_of(c.at("domain"), {"t"});
  } else if (kind == "implicit2d") {
    d.type = GeometryType::implicit_curve;
    d.formulas = {{"equations[0]", f.at("f")}};
    d.domain = domain_of(c.at("domain"), {"x", "y"});
  } else {
    REQUIRE_MESSAGE((kind == "curve3d" || kind == "curve3d_implicit"), "unknown kind " << kind);
    d.type = GeometryType::implicit_curve;
    d.formulas = {{"equations[0]", f.at("f1")}, {"equations[1]", f.at("f2")}};
    const json& box = c.contains("domain") ? c.at("domain") : c.at("box");
    d.domain = domain_of(box, {"x", "y", "z"});
  }
  if (c.contains("constants"))
    for (const auto& [name, value] : c.at("constants").items()) d.constants[name] = value.get<double>();
  return d;
}

std::vector<GeometryDefinition> reference_geometries() {
  std::vector<GeometryDefinition> all;
  const std::string data = std::string(FOOTPOINT_TESTS_DIR) + "/data/";
  for (const char* name : {"A1", "S1", "S2", "S3", "S3_edge", "cone", "fold", "fold_near", "monkey_saddle",
                           "plane", "ripple", "sphere", "torus", "wavy"})
    all.push_back(definition_of(canonical_read_json(data + "surface_" + name + ".json"), "surface"));
  for (const char* file :
       {"curve_parametric_cases.json", "curve_planar_implicit_cases.json", "curve_spatial_cases.json"}) {
    const json cases = canonical_read_json(data + file);
    for (const auto& c : cases.at("cases")) all.push_back(definition_of(c, c.at("kind")));
  }
  if (std::ifstream(FOOTPOINT_CASES_FILE).good()) {
    const json cases = canonical_read_json(FOOTPOINT_CASES_FILE);
    for (const auto& c : cases.at("cases"))
      if (c.contains("formulas")) all.push_back(definition_of(c, c.at("kind")));
  }
  // Constants, spaces the canonical form drops, numbers that need an exponent or a sign.
  GeometryDefinition torus;
  torus.type = GeometryType::parametric_surface;
  torus.formulas = {{"x", " (R + r*cos(v)) * cos(u) "}, {"y", "(R+r*cos(v))*sin(u)"}, {"z", "r * sin(v)"}};
  torus.domain = {{"u", {-0.0, 6.283185307179586}}, {"v", {-3.141592653589793, 1e-300}}};
  torus.constants = {{"R", 2.0}, {"r", 0.5}, {"big", -1.5e300}};
  all.push_back(torus);
  // Declared periodic directions, in any order and repeated.
  GeometryDefinition periodic_torus = torus;
  periodic_torus.domain[1].second = {0.0, 6.283185307179586};
  periodic_torus.constants.erase("big");
  periodic_torus.periodic = {"v", "u", "v"};
  all.push_back(periodic_torus);
  GeometryDefinition helix;
  helix.type = GeometryType::parametric_curve;
  helix.formulas = {{"x", "cos(t)"}, {"y", "sin(t)"}, {"z", "t/4 + (t <= 1)"}};  // "=" inside a formula
  helix.domain = {{"t", {0.0, 12.566370614359172}}};
  all.push_back(helix);
  GeometryDefinition circle;
  circle.type = GeometryType::parametric_curve;
  circle.formulas = {{"x", "cos(t)"}, {"y", "sin(t)"}};
  circle.domain = {{"t", {0.0, 6.283185307179586}}};
  circle.periodic = {"t"};
  all.push_back(circle);
  return all;
}

}  // namespace

TEST_CASE("parse_canonical inverts canonical() on every reference geometry") {
  const auto geometries = reference_geometries();
  CHECK(geometries.size() >= 30);
  for (const auto& d : geometries) {
    const std::string text = d.canonical();
    INFO(text);
    const GeometryDefinition parsed = parse_canonical(text);
    CHECK(parsed.canonical() == text);
    CHECK(parsed.id() == d.id());
    CHECK(parsed.type == d.type);
    REQUIRE(parsed.formulas.size() == d.formulas.size());
    for (std::size_t i = 0; i < d.formulas.size(); ++i) CHECK(parsed.formulas[i].name == d.formulas[i].name);
    CHECK(parsed.domain.size() == d.domain.size());
    for (std::size_t i = 0; i < d.domain.size(); ++i) {
      CHECK(parsed.domain[i].first == d.domain[i].first);
      // bit for bit, the sign of zero included
      CHECK(std::memcmp(parsed.domain[i].second.data(), d.domain[i].second.data(), sizeof(double) * 2) == 0);
    }
    CHECK(parsed.constants == d.constants);
    std::vector<std::string> periodic = d.periodic;
    std::sort(periodic.begin(), periodic.end());
    periodic.erase(std::unique(periodic.begin(), periodic.end()), periodic.end());
    CHECK(parsed.periodic == periodic);
  }
}

TEST_CASE("a definition compiled from its canonical text projects bit for bit like the posted one") {
  for (const auto& d : reference_geometries()) {
    const std::string text = d.canonical();
    INFO(text);
    const auto posted = compile_geometry(d);
    const auto parsed = compile_geometry(parse_canonical(text));
    REQUIRE(parsed->methods().size() == posted->methods().size());
    const int n = posted->point_dim();
    for (const double scale : {0.3, 1.7}) {
      double p[3];
      for (int k = 0; k < n; ++k) p[k] = scale * (k + 1) - 1.0;
      const ProjectionResult a = posted->project(p, "auto", Options{}).value();
      const ProjectionResult b = parsed->project(p, "auto", Options{}).value();
      CHECK(std::memcmp(&a.distance, &b.distance, sizeof(double)) == 0);
      CHECK(std::memcmp(a.foot.data(), b.foot.data(), sizeof a.foot) == 0);
    }
  }
}

TEST_CASE("parse_canonical refuses every text that is not a canonical definition") {
  GeometryDefinition d;
  d.type = GeometryType::parametric_surface;
  d.formulas = {{"x", "u"}, {"y", "v"}, {"z", "u*v"}};
  d.domain = {{"u", {-1.0, 1.0}}, {"v", {0.0, 2.5}}};
  d.constants = {{"a", 3.0}};
  const std::string good = d.canonical();
  REQUIRE(good ==
          "footpoint/1;type=parametric_surface;x=u;y=v;z=u*v;domain.u=[-1,1];domain.v=[0,2.5];constants.a=3");
  CHECK(parse_canonical(good).canonical() == good);
  for (const std::string& bad : {
           std::string(""),
           std::string("footpoint/2;type=parametric_surface;x=u;y=v;z=u*v;domain.u=[-1,1];domain.v=[0,2.5]"),
           std::string("footpoint/1;type=surface;x=u;y=v;z=u*v;domain.u=[-1,1];domain.v=[0,2.5]"),
           std::string("footpoint/1;type=parametric_surface;y=v;x=u;z=u*v;domain.u=[-1,1];domain.v=[0,2.5]"),
           std::string("footpoint/1;type=parametric_surface;x=u;y=v;domain.u=[-1,1];domain.v=[0,2.5]"),
           std::string(
               "footpoint/1;type=parametric_surface;x=u;y=v;z=u * v;domain.u=[-1,1];domain.v=[0,2.5]"),
           std::string(
               "footpoint/1;type=parametric_surface;x=u;y=v;z=u*v;domain.u=[-1.0,1];domain.v=[0,2.5]"),
           std::string("footpoint/1;type=parametric_surface;x=u;y=v;z=u*v;domain.v=[0,2.5];domain.u=[-1,1]"),
           std::string("footpoint/1;type=parametric_surface;x=u;y=v;z=u*v;domain.u=[-1,1]"),
           std::string("footpoint/1;type=parametric_surface;x=u;y=v;z=u*v;domain.u=[-1,1];domain.v=[0,2.5;"),
           std::string("footpoint/1;type=parametric_surface;x=u;y=v;z=u*v;domain.u=[-1,1];domain.v=[0,2.5];"
                       "constants.a=3;constants.a=3"),
           std::string(
               "footpoint/1;type=parametric_surface;x=u;y=v;z=u*v;domain.u=[-1,1];domain.v=[0,2.5];w=1"),
           std::string("footpoint/1;type=parametric_curve;x=t;y=t;z=t;w=t;domain.t=[0,1]"),
           std::string("footpoint/1;type=implicit_curve;equations[1]=x;domain.x=[0,1];domain.y=[0,1]"),
           std::string("footpoint/1;type=implicit_curve;equations[0]=x^2+y^2-1;domain.x=[0,1];domain.y=[0,1];"
                       "domain.z=[0,1]"),
           good + "x",
           good.substr(0, good.size() - 1),
           // periodic: parameters of the type only, sorted, once each, after the constants
           good + ";periodic=w",
           good + ";periodic=v,u",
           good + ";periodic=u,u",
           good + ";periodic=",
           good + ";periodic=u;periodic=v",
           std::string("footpoint/1;type=parametric_surface;x=u;y=v;z=u*v;domain.u=[-1,1];domain.v=[0,2.5];"
                       "periodic=u;constants.a=3"),
           std::string("footpoint/1;type=parametric_curve;x=t;y=t;domain.t=[0,1];periodic=u"),
           std::string("footpoint/1;type=implicit_curve;equations[0]=x^2+y^2-1;domain.x=[0,1];domain.y=[0,1];"
                       "periodic=x"),
       }) {
    INFO(bad);
    try {
      parse_canonical(bad);
      FAIL("accepted");
    } catch (const GeometryError& e) {
      CHECK(e.code == "bad_canonical");
    }
  }
}
