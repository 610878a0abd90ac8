// parametric/solvers/bezier_patch_nearest: a polynomial Bézier patch's nearest point by its own
// branch and bound, against a closed form (a parabolic trough with two feet at the same distance:
// no unique answer may be claimed, and the B-spline `auto` reports the tie) and against the
// parametric engine's certified `auto` on the same pieces (options.trace keeps the B-spline
// surface on the engine's path), an implementation that shares no code with it.
#include <doctest/doctest.h>

#include <cmath>
#include <random>
#include <vector>

#include "compiled/compiled_geometry.hpp"
#include "compiled/geometry_definition.hpp"
#include "parametric/solvers/bezier_patch_nearest.hpp"

using namespace footpoint;

namespace {

// z = x² over x in [-1, 1], y in [0, 1]: x = -1 + 2s has Bézier points -1, 0, 1 and x² the points
// 1, -1, 1 (the Bernstein coefficients of 4s² - 4s + 1); degree 1 in y.
GeometryDefinition trough() {
  GeometryDefinition def;
  def.type = GeometryType::bspline_surface;
  def.bspline.degree = {2, 1};
  def.bspline.knots = {{0, 0, 0, 1, 1, 1}, {0, 0, 1, 1}};
  const double x[3] = {-1.0, 0.0, 1.0}, z[3] = {1.0, -1.0, 1.0};
  for (int i = 0; i < 3; ++i) def.bspline.control_points.push_back({{x[i], 0.0, z[i]}, {x[i], 1.0, z[i]}});
  return def;
}

// A bicubic B-spline of 4 x 4 pieces on [0, 2]², heights a smooth bump plus noise (fixed seed).
GeometryDefinition bumpy(std::mt19937& rng) {
  std::uniform_real_distribution<double> noise(-0.1, 0.1);
  GeometryDefinition def;
  def.type = GeometryType::bspline_surface;
  def.bspline.degree = {3, 3};
  const std::vector<double> knots = {0, 0, 0, 0, 0.5, 1, 1.5, 2, 2, 2, 2};
  def.bspline.knots = {knots, knots};
  for (int i = 0; i < 7; ++i) {
    std::vector<std::vector<double>> row;
    for (int j = 0; j < 7; ++j) {
      const double x = i / 3.0, y = j / 3.0;
      row.push_back({x, y, 0.4 * std::sin(2.0 * x) * std::cos(1.5 * y) + noise(rng)});
    }
    def.bspline.control_points.push_back(row);
  }
  return def;
}

}  // namespace

TEST_CASE("a parabolic trough's two feet: no unique foot claimed; the B-spline auto finds the tie") {
  // p = (0, y, 1): f(x) = x² + (x² - 1)² is least at x² = 1/2, two feet at distance sqrt(3/4).
  const BezierPatch patch(2, 1, {{-1, 0, 1}, {-1, 1, 1}, {0, 0, -1}, {0, 1, -1}, {1, 0, 1}, {1, 1, 1}});
  const Vec3 p{0.0, 0.5, 1.0};
  const PatchNearest n = nearest_on_patch(patch, p);
  CHECK_FALSE(n.proved);

  const auto g = compile_geometry(trough());
  const double x[3] = {p.x, p.y, p.z};
  const ProjectionResult r = g->project(x, "auto", {}).value();
  CHECK(std::abs(r.distance - std::sqrt(0.75)) <= 1e-12);
  CHECK(r.summary.certificate.certified);
  CHECK(r.summary.multiplicity.kind == Multiplicity::tied);
  CHECK(r.summary.multiplicity.count == 2);
  CHECK(std::abs(std::abs(r.foot[0]) - std::sqrt(0.5)) <= 1e-9);

  // Off the axis the foot is unique, and the patch proves it: the nearer of the two.
  const Vec3 q{0.2, 0.5, 1.0};
  const PatchNearest m = nearest_on_patch(patch, q);
  REQUIRE(m.proved);
  CHECK(m.jet.s.x > 0.0);
  CHECK(m.lower_bound <= m.distance);
  CHECK(m.distance - m.lower_bound <= 1e-9 * m.distance);
}

TEST_CASE("the patches' branch and bound agrees with the engine's certified auto on every piece") {
  std::mt19937 rng(35);
  const auto g = compile_geometry(bumpy(rng));
  std::uniform_real_distribution<double> box(-0.8, 2.8), height(-1.2, 1.2);
  Options engine;
  engine.trace = true;  // the pieces' own `auto`, not their patches
  int points = 0;
  for (int i = 0; i < 150; ++i) {
    const double x[3] = {box(rng), box(rng), height(rng)};
    const ProjectionResult fast = g->project(x, "auto", {}).value();
    const ProjectionResult slow = g->project(x, "auto", engine).value();
    CAPTURE(x[0]);
    CAPTURE(x[1]);
    CAPTURE(x[2]);
    REQUIRE(slow.summary.certificate.certified);
    CHECK(fast.summary.certificate.certified);
    CHECK(std::abs(fast.distance - slow.distance) <= 1e-12 * (1.0 + slow.distance));
    // Each lower bound holds for the other's answer.
    CHECK(fast.summary.certificate.lower_bound <= slow.distance * (1.0 + 1e-15));
    CHECK(fast.summary.multiplicity.kind == slow.summary.multiplicity.kind);
    CHECK(fast.summary.location == slow.summary.location);
    for (int k = 0; k < 3; ++k) CHECK(std::abs(fast.foot[k] - slow.foot[k]) <= 1e-9 * (1.0 + slow.distance));
    ++points;
  }
  CHECK(points == 150);
}
