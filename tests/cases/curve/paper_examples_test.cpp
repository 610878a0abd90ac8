// [Curve] Examples 1 and 2 (tests/data/papers/public_cases.json, paperC_ex1 and
// paperC_ex2, box [-300, 300]^3): `auto` finds the global nearest point for all 16 test points of
// each, to 1e-12 relative in distance; discovery finds the one closed loop of each; the options
// (all_minima, trace, max_distance) behave.
#include <doctest/doctest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "compiled/implicit_curve_geometry.hpp"

using namespace footpoint;
using nlohmann::json;

namespace {

const json& cases() {
  static const json j = [] {
    std::ifstream in(FOOTPOINT_CASES_FILE);
    REQUIRE(in.good());
    return json::parse(in);
  }();
  return j;
}

const json& paper_case(const std::string& id) {
  for (const json& c : cases()["cases"])
    if (c["id"] == id) return c;
  FAIL("no case " << id);
  return cases();
}

std::shared_ptr<const CompiledGeometry> compile_example(const json& c) {
  GeometryDefinition def;
  def.type = GeometryType::implicit_curve;
  def.formulas = {{"equations[0]", c["formulas"]["f1"]}, {"equations[1]", c["formulas"]["f2"]}};
  for (const char* k : {"x", "y", "z"}) def.domain.push_back({k, {c["box"][k][0], c["box"][k][1]}});
  return compile_implicit_curve(def, {});
}

void check_auto(const std::string& id) {
  const json& c = paper_case(id);
  const auto g = compile_example(c);
  REQUIRE(g->point_dim() == 3);
  REQUIRE(g->num_params() == 0);
  REQUIRE(c["points"].size() == 16);
  int k = 0;
  for (const json& pt : c["points"]) {
    CAPTURE(++k);
    const double p[3] = {pt["p"][0], pt["p"][1], pt["p"][2]};
    const ProjectionResult r = g->project(p, "auto", {}).value();
    const json& o = pt["oracle"];
    const double ref = o["distance"];
    CHECK(r.summary.status == Status::converged);
    CHECK(r.summary.method == "auto");
    CHECK(std::fabs(r.distance - ref) <= 1e-12 * ref);
    const double size = std::max(1.0, std::hypot(r.foot[0], r.foot[1], r.foot[2]));
    for (int i = 0; i < 3; ++i)
      CHECK(std::fabs(r.foot[static_cast<std::size_t>(i)] - o["foot"][i].get<double>()) <= 1e-9 * size);
    CHECK(std::fabs(std::hypot(p[0] - r.foot[0], p[1] - r.foot[1], p[2] - r.foot[2]) - r.distance) <=
          1e-13 * r.distance);
    // |f_i| / |grad f_i| and the orthogonality of eq. (7), relative.
    CHECK(r.summary.equation_residual[0] <= 1e-12 * size);
    CHECK(r.summary.equation_residual[1] <= 1e-12 * size);
    CHECK(r.summary.orthogonality[0] <= 1e-12);
    CHECK(r.summary.location == Location::interior);
    CHECK(r.summary.starts >= 1);
    CHECK(r.summary.iterations >= 1);
  }
}

}  // namespace

TEST_CASE("auto: Example 1, all 16 points are the global nearest points") { check_auto("paperC_ex1"); }

TEST_CASE("auto: Example 2, all 16 points are the global nearest points") { check_auto("paperC_ex2"); }

TEST_CASE("discovery: each example is one closed loop, inside the oracle's bounding box") {
  for (const char* id : {"paperC_ex1", "paperC_ex2"}) {
    CAPTURE(id);
    const json& c = paper_case(id);
    const auto g = compile_example(c);
    const auto& curve = dynamic_cast<const ImplicitCurve&>(*g);
    const CurveDiscovery& d = curve.discovery();
    CHECK(d.stats.pieces == 1);
    CHECK(d.stats.closed_pieces == 1);
    CHECK(d.stats.face_crossings == 0);
    CHECK(d.stats.singular_points == 0);
    CHECK(d.stats.unproved_boxes == 0);
    const CurveSamples& s = d.samples;
    REQUIRE(s.size() > 100);
    // A closed loop: every sample has both neighbours; the links are at most h apart; every sample
    // is on the curve; the samples reach the ends of the oracle's bounding box (to h / 2).
    const json& bbox = c["object_info"]["curve_bbox"];
    Vec3 lo = s.points[0], hi = s.points[0];
    for (std::size_t i = 0; i < s.size(); ++i) {
      CHECK(s.prev[i] >= 0);
      CHECK(s.next[i] >= 0);
      const Vec3 x = s.points[i];
      CHECK(norm(s.points[static_cast<std::size_t>(s.next[i])] - x) <= s.spacing);
      const auto f = curve.equations().values(x);
      const ImplicitJet j = curve.equations().jet(x);
      CHECK(std::fabs(f[0]) <= 1e-12 * norm(j.grad[0]) * std::max(1.0, norm(x)));
      CHECK(std::fabs(f[1]) <= 1e-12 * norm(j.grad[1]) * std::max(1.0, norm(x)));
      for (int k = 0; k < 3; ++k) {
        lo[k] = std::min(lo[k], x[k]);
        hi[k] = std::max(hi[k], x[k]);
      }
    }
    for (int k = 0; k < 3; ++k) {
      CHECK(lo[k] >= bbox[k][0].get<double>() - 1e-9);
      CHECK(hi[k] <= bbox[k][1].get<double>() + 1e-9);
      CHECK(lo[k] <= bbox[k][0].get<double>() + 0.5 * s.spacing);
      CHECK(hi[k] >= bbox[k][1].get<double>() - 0.5 * s.spacing);
    }
  }
}

TEST_CASE("auto options: all_minima, trace, max_distance") {
  const json& c = paper_case("paperC_ex1");
  const auto g = compile_example(c);
  const json& pt = c["points"][0];
  const double p[3] = {pt["p"][0], pt["p"][1], pt["p"][2]};
  const double ref = pt["oracle"]["distance"];

  SUBCASE("all_minima: Example 1's loop has one minimum of the distance per test point") {
    Options o;
    o.all_minima = true;
    const ProjectionResult r = g->project(p, "auto", o).value();
    REQUIRE(r.minima.size() == pt["oracle"]["local_minima"].size());
    CHECK(std::fabs(r.minima[0].distance - ref) <= 1e-12 * ref);
    CHECK(r.minima[0].location == Location::interior);
  }
  SUBCASE("trace: the Newton increments of the winning local solve, shrinking to rounding") {
    Options o;
    o.trace = true;
    const ProjectionResult r = g->project(p, "auto", o).value();
    REQUIRE(r.trace.size() == static_cast<std::size_t>(r.summary.iterations));
    const auto& last = r.trace.back();
    CHECK(std::hypot(last[0], last[1], last[2]) <= 1e-13);
    CHECK(g->project(p, "auto", {}).value().trace.empty());
  }
  SUBCASE("max_distance below the distance: beyond_max_distance") {
    Options o;
    o.max_distance = 0.5 * ref;
    CHECK(g->project(p, "auto", o).value().summary.status == Status::beyond_max_distance);
    o.max_distance = ref - 1e-6;
    CHECK(g->project(p, "auto", o).value().summary.status == Status::beyond_max_distance);
    o.max_distance = ref + 1e-6;
    const ProjectionResult r = g->project(p, "auto", o).value();
    CHECK(r.summary.status == Status::converged);
    CHECK(std::fabs(r.distance - ref) <= 1e-12 * ref);
  }
}
