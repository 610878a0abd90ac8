// What `auto` precomputes for implicit curves (implicit/seeding/curve_discovery): the pieces, box-face
// crossings and singular points found, against the oracle's (tests/data/curve_*_cases.json,
// curve_info), and the sample spacing that the global search relies on.
#include <doctest/doctest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "compiled/implicit_curve_geometry.hpp"
#include "curve_cases.hpp"
#include "implicit/seeding/curve_enclosure.hpp"
#include "implicit_fixtures.hpp"

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
  const auto g = test::compile_curve_case(c);
  const auto& curve = dynamic_cast<const ImplicitCurve&>(*g);
  check_special(curve.discovery().samples, SampleKind::singular_point, c["curve_info"]["singular_points"]);
  CHECK(curve.discovery().stats.face_crossings == 0);
  check_samples(curve);
}

TEST_CASE("discovery: three circles are three pieces") {
  const json& c = case_of("curve_spatial_cases.json", "three_circles");
  const auto g = test::compile_curve_case(c);
  const auto& curve = dynamic_cast<const ImplicitCurve&>(*g);
  CHECK(curve.discovery().stats.pieces == 3);
  CHECK(curve.discovery().stats.closed_pieces == 3);
  CHECK(curve.discovery().stats.singular_points == 0);
  check_samples(curve);
}

TEST_CASE("discovery: curves leaving the box end at the exact face crossings") {
  for (const char* id : {"ex1_clipped", "helix_clipped"}) {
    CAPTURE(id);
    const json& c = case_of("curve_spatial_cases.json", id);
    const auto g = test::compile_curve_case(c);
    const auto& curve = dynamic_cast<const ImplicitCurve&>(*g);
    check_special(curve.discovery().samples, SampleKind::box_face, c["curve_info"]["endpoints"]);
    check_samples(curve);
  }
  const json& c = case_of("curve_planar_implicit_cases.json", "parabola_clipped");
  const auto g = test::compile_curve_case(c);
  const auto& curve = dynamic_cast<const ImplicitCurve&>(*g);
  check_special(curve.discovery().samples, SampleKind::box_face, c["curve_info"]["endpoints"]);
  check_samples(curve);
}

TEST_CASE("discovery: planar singular points (a cusp, the lemniscate's crossing)") {
  for (const char* id : {"cusp", "lemniscate"}) {
    CAPTURE(id);
    const json& c = case_of("curve_planar_implicit_cases.json", id);
    const auto g = test::compile_curve_case(c);
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

// A curve too intricate for its box (a reliability finding): f = sum_{k=1..119} sin(k x + (k mod 7) y)
// over [-300, 300]^2 has a piece through nearly every point of the plane (wavelengths down to
// 2 pi / 119). Discovery must not answer a far curve point as the nearest: either `auto` finds a
// point at least as near as a curve point proved to exist by a sign change of f, or compiling
// says the box is too large (geometry_too_complex, HTTP 422).
TEST_CASE("discovery: a curve too intricate for its box is refused, never answered wrongly") {
  std::string f;
  for (int k = 1; k < 120; ++k) {
    if (k > 1) f += '+';
    f += "sin(" + std::to_string(k) + "*x+" + std::to_string(k % 7) + "*y)";
  }
  GeometryDefinition def;
  def.type = GeometryType::implicit_curve;
  def.formulas = {{"equations[0]", f}};
  def.domain = {{"x", {-300.0, 300.0}}, {"y", {-300.0, 300.0}}};
  const double p[2] = {1.0, 2.0};

  // f changes sign between (1, 2) and (1.0019, 2): bisection to rounding gives a curve point at
  // distance `bound` from p, so the nearest curve point is at most that far.
  auto value = [&](double x) {
    double s = 0.0;
    for (int k = 1; k < 120; ++k) s += std::sin(k * x + (k % 7) * 2.0);
    return s;
  };
  double a = 1.0, b = 1.0019;
  REQUIRE(value(a) * value(b) < 0.0);
  for (int i = 0; i < 200 && b - a > 1e-15; ++i) {
    const double m = 0.5 * (a + b);
    (value(a) * value(m) <= 0.0 ? b : a) = m;
  }
  const double bound = b - 1.0;
  CHECK(bound < 1e-3);

  // In a small box the same curve is resolved (cells bisected until f is nearly flat across each):
  // `auto` finds a point at least as near as that one.
  def.domain = {{"x", {0.99, 1.01}}, {"y", {1.99, 2.01}}};
  const ProjectionResult small = compile_implicit_curve(def, {})->project(p, "auto", {}).value();
  CHECK(small.distance <= bound * (1.0 + 1e-9));

  // In the large box, compiling refuses the curve as too intricate (geometry_too_complex, past
  // SubdivisionSettings::max_cells: ~20 s in Release) or at the compile deadline given here
  // (compile_timeout: the server's budget for compiling), whichever comes first.
  def.domain = {{"x", {-300.0, 300.0}}, {"y", {-300.0, 300.0}}};
  formula::CompileLimits limits;
  limits.deadline = std::chrono::steady_clock::now() + std::chrono::seconds(2);
  std::shared_ptr<const CompiledGeometry> g;
  try {
    g = compile_geometry(def, limits);
  } catch (const GeometryError& e) {
    CHECK((e.code == "geometry_too_complex" || e.code == "compile_timeout"));
    if (e.code == "geometry_too_complex") CHECK(e.field == "domain");
    return;
  }
  const ProjectionResult r = g->project(p, "auto", {}).value();
  CHECK(r.distance <= bound * (1.0 + 1e-9));
}

namespace {

std::shared_ptr<const CompiledGeometry> planar_curve(const std::string& f, Box3 box) {
  GeometryDefinition def;
  def.type = GeometryType::implicit_curve;
  def.formulas = {{"equations[0]", f}};
  def.domain = {{"x", {box.lo.x, box.hi.x}}, {"y", {box.lo.y, box.hi.y}}};
  return compile_implicit_curve(def, {});
}

// Every point of the circle c + r (cos t, sin t) lies in a proved cell or an unproved box.
void check_covered(const ImplicitCurve& curve, Vec3 c, double r) {
  const CurveCells& cells = curve.discovery().cells;
  for (int k = 0; k < 2000; ++k) {
    const double t = 2.0 * M_PI * k / 2000;
    const Vec3 x = c + Vec3{r * std::cos(t), r * std::sin(t), 0.0};
    bool in = false;
    for (const ProvedCell& cell : cells.cells) in = in || cell.box.contains(x, 1e-12);
    for (const UnprovedBox& u : cells.unproved) in = in || u.box.contains(x, 1e-12);
    CHECK(in);
  }
}

}  // namespace

TEST_CASE("discovery: a tiny oval at a grid corner, on a cell's edge, at a cell's centre is its own piece") {
  // The enclosure grid of [-2, 2]^2 at its final level has a corner at (1.5246, 1.221575) and cells
  // of 0.063875 x 0.064525: the oval of radius 0.04 (1 % of the box) sits on that corner, on the
  // vertical edge above it, or in the middle of the cell.
  const Vec3 centres[] = {{1.5246, 1.221575, 0}, {1.5246, 1.2538375, 0}, {1.5565375, 1.2538375, 0}};
  for (const Vec3& c : centres) {
    CAPTURE(c.x);
    CAPTURE(c.y);
    char f[160];
    std::snprintf(f, sizeof f, "(x^2+y^2-1)*((x-%.17g)^2+(y-%.17g)^2-0.0016)", c.x, c.y);
    const auto g = planar_curve(f, {{-2, -2, 0}, {2, 2, 0}});
    const auto& curve = dynamic_cast<const ImplicitCurve&>(*g);
    const CellGrid grid = enclosure_grid(curve.box());
    CHECK(curve.discovery().stats.levels == 6);
    CHECK(std::fabs(grid.box.lo.x + 56.0 * std::ldexp(grid.box.hi.x - grid.box.lo.x, -6) - 1.5246) < 1e-12);
    CHECK(curve.discovery().stats.pieces == 2);
    CHECK(curve.discovery().stats.closed_pieces == 2);
    CHECK(curve.discovery().stats.unproved_boxes == 0);
    check_covered(curve, c, 0.04);
    check_covered(curve, {0, 0, 0}, 1.0);
    check_samples(curve);
    // Samples on the oval, every one of its arcs: none farther than the spacing from the next.
    int on_oval = 0;
    for (const Vec3& x : curve.discovery().samples.points) on_oval += norm(x - c) < 0.05 ? 1 : 0;
    CHECK(on_oval >= 8);
  }
}

TEST_CASE("discovery: circles 1e-3 apart are two pieces, subdivided until separated") {
  const auto g = planar_curve("(x^2+y^2-1)*((x-2.001)^2+y^2-1)", {{-2, -2, 0}, {4, 2, 0}});
  const auto& curve = dynamic_cast<const ImplicitCurve&>(*g);
  CHECK(curve.discovery().stats.pieces == 2);
  CHECK(curve.discovery().stats.closed_pieces == 2);
  CHECK(curve.discovery().stats.unproved_boxes == 0);
  CHECK(curve.discovery().stats.deepest >= 4);
  check_covered(curve, {0, 0, 0}, 1.0);
  check_covered(curve, {2.001, 0, 0}, 1.0);
  check_samples(curve);
}

TEST_CASE("discovery: singular points of any order are bounded, never refused") {
  // A node (isolated by Krawczyk's test), a tacnode y^2 = x^4 and a cusp (bounded in small
  // unproved boxes): each found as a singular point, in a box of at most 1e-5.
  struct Case {
    const char* f;
    Box3 box;
    Vec3 singular;
    bool isolated;
  };
  const Case cases[] = {{"y^2-x^2*(x+0.04)", {{-1, -1, 0}, {1, 1, 0}}, {0, 0, 0}, true},
                        {"y^2-x^4", {{-1, -1.2, 0}, {1.1, 1, 0}}, {0, 0, 0}, false},
                        {"(y-0.13)^2-(x+0.07)^3", {{-1, -1, 0}, {1, 1, 0}}, {-0.07, 0.13, 0}, false}};
  for (const Case& c : cases) {
    CAPTURE(c.f);
    const auto g = planar_curve(c.f, c.box);
    const auto& curve = dynamic_cast<const ImplicitCurve&>(*g);
    const DiscoveryStats& s = curve.discovery().stats;
    CHECK(s.singular_points == 1);
    CHECK(s.isolated_singular_points == (c.isolated ? 1 : 0));
    REQUIRE(s.unproved_boxes >= 1);
    for (const UnprovedBox& u : curve.discovery().cells.unproved) {
      if (!u.box.contains(c.singular, 1e-6)) continue;
      CHECK(u.box.max_edge() <= 1e-5);
    }
    bool found = false;
    for (std::size_t i = 0; i < curve.discovery().samples.size(); ++i)
      if (curve.discovery().samples.kind[i] == SampleKind::singular_point)
        found = found || norm(curve.discovery().samples.points[i] - c.singular) <= 1e-7;
    CHECK(found);
  }
}

TEST_CASE("discovery: a curve that is one isolated point is bounded at the finest grid, not refined on") {
  // x^2 + y^2 = 0 is the origin alone: one cell stays unproved at every level (the request fuzzer's
  // find: refining on overflowed the grid's int32 cell indices). It is kept as an unproved box, and
  // a point is answered with the origin.
  const auto g = planar_curve("x^2+y^2-0", {{-2, -2, 0}, {2, 2, 0}});
  REQUIRE(g);
  const auto& curve = dynamic_cast<const ImplicitCurve&>(*g);
  REQUIRE(curve.discovery().stats.unproved_boxes >= 1);
  for (const UnprovedBox& u : curve.discovery().cells.unproved) CHECK(u.box.contains({0, 0, 0}, 1e-6));
  const double p[2] = {0.3, 0.4};
  const ProjectionResult r = g->project(p, "auto", Options{}).value();
  CHECK(r.distance == doctest::Approx(0.5).epsilon(1e-6));
  CHECK(r.summary.certificate.lower_bound <= 0.5);
}

TEST_CASE("discovery: every point of the curve lies within h/2 of a sample") {
  // Viviani's curve (1 + cos t, sin t, 2 sin(t/2)), t in [0, 4 pi): the bound `auto`'s search
  // relies on (curve_samples.hpp), against the parametrisation.
  const json& c = case_of("curve_spatial_cases.json", "viviani");
  const auto g = test::compile_curve_case(c);
  const auto& curve = dynamic_cast<const ImplicitCurve&>(*g);
  const CurveSamples& s = curve.discovery().samples;
  double worst = 0.0;
  for (int k = 0; k < 4000; ++k) {
    const double t = 4.0 * M_PI * k / 4000;
    const Vec3 x{1.0 + std::cos(t), std::sin(t), 2.0 * std::sin(0.5 * t)};
    double nearest = 1e300;
    for (const Vec3& y : s.points) nearest = std::min(nearest, norm(x - y));
    worst = std::max(worst, nearest);
  }
  CHECK(worst <= 0.5 * s.spacing);
}

TEST_CASE("discovery: samples are no denser than the spacing and the turning ask") {
  // Along a piece, a link spans at least 0.9 max_step (h / 1.01) unless the turn of the chord,
  // not its length, stopped it (0.15 rad), or it ends the piece, as the thinning keeps the
  // farthest point the last kept one reaches or a point placed on the curve at 0.97 max_step
  // (curve_arc_samples): links <= 1.25 (1.01 L / h + T / 0.15) + 2 per piece, with L the chords'
  // length and T their turning, the margin for the chords' approximation of the arc and the
  // points kept next to the cusp. Small cells (near the tacnode's tangency, the lemniscate's node,
  // the cusp, Example 2's large box) must not mean dense samples: each crossing of a cell face is
  // not a sample of its own, and the crossings are no grid the samples keep to.
  const std::vector<std::pair<std::vector<std::string>, std::vector<std::array<double, 2>>>> curves = {
      {{"x^2/9+y^2/16+z^2/9+4*x*y-1", "x^2+y^2+x-4*z"}, {{-300, 300}, {-300, 300}, {-300, 300}}},
      {{"(x^2+y^2)^2-2*(x^2-y^2)"}, {{-2, 2}, {-2, 2}}},
      {{"(x^2+y^2-1)*((x-2)^2+y^2-1)"}, {{-2, 4}, {-2, 2}}},
      {{"y^2-x^3"}, {{-1, 2}, {-2, 2}}},
  };
  for (const auto& definition : curves) {
    const std::vector<std::string>& equations = definition.first;
    CAPTURE(equations[0]);
    const auto g = test::implicit_curve(equations, definition.second);
    const auto& curve = dynamic_cast<const ImplicitCurve&>(*g);
    const CurveSamples& s = curve.discovery().samples;
    double length = 0.0, turning = 0.0;
    int links = 0;
    for (std::size_t i = 0; i < s.size(); ++i) {
      const std::int32_t next = s.next[i], prev = s.prev[i];
      if (next < 0) continue;
      const Vec3 b = s.points[static_cast<std::size_t>(next)] - s.points[i];
      length += norm(b);
      ++links;
      if (prev < 0) continue;
      const Vec3 a = s.points[i] - s.points[static_cast<std::size_t>(prev)];
      turning += std::atan2(norm(cross(a, b)), dot(a, b));
    }
    const double bound =
        1.25 * (1.01 * length / s.spacing + turning / 0.15) + 2.0 * curve.discovery().stats.pieces;
    CHECK(links <= bound);
    check_samples(curve);
  }
}
