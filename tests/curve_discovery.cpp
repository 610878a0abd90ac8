// What `auto` precomputes for implicit curves (seeding/curve_discovery): the pieces, box-face
// crossings and singular points found, against the oracle's (tests/data/curve_*_cases.json,
// curve_info), and the sample spacing that the global search relies on.
#include <doctest/doctest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "geometry/implicit_curve.hpp"

using namespace footpoint;
using nlohmann::json;

namespace {

const json& case_of(const std::string& file, const std::string& id) {
  static std::map<std::string, json> files;
  if (!files.count(file)) {
    std::ifstream in(std::string(FOOTPOINT_TESTS_DIR) + "/data/" + file);
    REQUIRE(in.good());
    files[file] = json::parse(in);
  }
  for (const json& c : files[file]["cases"])
    if (c["id"] == id) return c;
  FAIL("no case " << id);
  return files[file];
}

std::shared_ptr<const CompiledGeometry> compile(const json& c) {
  GeometryDefinition def;
  def.type = GeometryType::implicit_curve;
  const json& f = c["formulas"];
  const json& d = c["domain"];
  if (f.contains("f")) {
    def.formulas = {{"equations[0]", f["f"]}};
    def.domain = {{"x", {d["x"][0], d["x"][1]}}, {"y", {d["y"][0], d["y"][1]}}};
  } else {
    def.formulas = {{"equations[0]", f["f1"]}, {"equations[1]", f["f2"]}};
    def.domain = {{"x", {d["x"][0], d["x"][1]}}, {"y", {d["y"][0], d["y"][1]}}, {"z", {d["z"][0], d["z"][1]}}};
  }
  return compile_implicit_curve(def, {});
}

// The samples of the given kind match the oracle's points one to one (to 1e-12).
void check_special(const CurveSamples& s, SampleKind kind, const json& expected) {
  std::vector<Vec3> mine;
  for (std::size_t i = 0; i < s.size(); ++i)
    if (s.kind[i] == kind) mine.push_back(s.points[i]);
  REQUIRE(mine.size() == expected.size());
  for (const json& e : expected) {
    const Vec3 x{e[0], e[1], e.size() > 2 ? e[2].get<double>() : 0.0};
    double best = 1e300;
    for (const Vec3& m : mine) best = std::min(best, norm(m - x));
    CHECK(best <= 1e-12 * std::max(1.0, norm(x)));
  }
}

// Every link is at most the spacing long, and every sample lies on the curve.
void check_samples(const ImplicitCurve& curve) {
  const CurveSamples& s = curve.discovery().samples;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s.next[i] >= 0) CHECK(norm(s.points[static_cast<std::size_t>(s.next[i])] - s.points[i]) <= s.spacing);
    const ImplicitJet j = curve.equations().jet(s.points[i]);
    const double size = std::max(1.0, norm(s.points[i]));
    CHECK(std::fabs(j.f[0]) <= 1e-12 * size * std::max(1.0, norm(j.grad[0])));
    CHECK(std::fabs(j.f[1]) <= 1e-12 * size * std::max(1.0, norm(j.grad[1])));
    CHECK(curve.box().contains(s.points[i], 1e-12 * size));
  }
}

}  // namespace

TEST_CASE("discovery: Viviani's curve, one piece through its double point, which is found") {
  const json& c = case_of("curve_spatial_cases.json", "viviani");
  const auto g = compile(c);
  const auto& curve = dynamic_cast<const ImplicitCurve&>(*g);
  check_special(curve.discovery().samples, SampleKind::singular_point, c["curve_info"]["singular_points"]);
  CHECK(curve.discovery().stats.face_crossings == 0);
  check_samples(curve);
}

TEST_CASE("discovery: three circles are three pieces") {
  const json& c = case_of("curve_spatial_cases.json", "three_circles");
  const auto g = compile(c);
  const auto& curve = dynamic_cast<const ImplicitCurve&>(*g);
  CHECK(curve.discovery().stats.traces == 3);
  CHECK(curve.discovery().stats.singular_points == 0);
  check_samples(curve);
}

TEST_CASE("discovery: curves leaving the box end at the exact face crossings") {
  for (const char* id : {"ex1_clipped", "helix_clipped"}) {
    CAPTURE(id);
    const json& c = case_of("curve_spatial_cases.json", id);
    const auto g = compile(c);
    const auto& curve = dynamic_cast<const ImplicitCurve&>(*g);
    check_special(curve.discovery().samples, SampleKind::box_face, c["curve_info"]["endpoints"]);
    check_samples(curve);
  }
  const json& c = case_of("curve_planar_implicit_cases.json", "parabola_clipped");
  const auto g = compile(c);
  const auto& curve = dynamic_cast<const ImplicitCurve&>(*g);
  check_special(curve.discovery().samples, SampleKind::box_face, c["curve_info"]["endpoints"]);
  check_samples(curve);
}

TEST_CASE("discovery: planar singular points (a cusp, the lemniscate's crossing)") {
  for (const char* id : {"cusp", "lemniscate"}) {
    CAPTURE(id);
    const json& c = case_of("curve_planar_implicit_cases.json", id);
    const auto g = compile(c);
    const auto& curve = dynamic_cast<const ImplicitCurve&>(*g);
    check_special(curve.discovery().samples, SampleKind::singular_point, c["curve_info"]["singular_points"]);
    check_samples(curve);
  }
}

TEST_CASE("discovery: no curve in the box") {
  GeometryDefinition def;
  def.type = GeometryType::implicit_curve;
  def.formulas = {{"equations[0]", "x^2+y^2+z^2-1"}, {"equations[1]", "z-5"}};
  def.domain = {{"x", {-3.0, 3.0}}, {"y", {-3.0, 3.0}}, {"z", {-3.0, 3.0}}};
  // The sphere and the plane z = 5 do not meet inside the box: compiling reports it (HTTP 422).
  try {
    compile_implicit_curve(def, {});
    FAIL("expected a GeometryError");
  } catch (const GeometryError& e) {
    CHECK(e.code == "empty_curve");
  }
}
