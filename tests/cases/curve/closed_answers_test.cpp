// `auto` on curves as a geometer reads the answers: the ends of a curve that closes smoothly are one
// interior point, no endpoint; beyond max_distance there is no foot point, parameter or distance;
// all_minima is capped by max_minima and says when it cut; the multiplicity of the answer (unique,
// tied, a continuum) is told, on parametric and implicit curves. References in closed form: the unit
// closed_circle (cos t, sin t) is at distance ||p| - 1| from p, nearest at t = atan2(p_y, p_x) unless
// p = 0, where every point is nearest.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

#include "compiled/compiled_geometry.hpp"

using namespace footpoint;

namespace {

constexpr double kPi = std::numbers::pi;

std::shared_ptr<const CompiledGeometry> closed_circle(double tmin, double tmax) {
  GeometryDefinition def;
  def.type = GeometryType::parametric_curve;
  def.formulas = {{"x", "cos(t)"}, {"y", "sin(t)"}};
  def.domain = {{"t", {tmin, tmax}}};
  return compile_geometry(def);
}

std::shared_ptr<const CompiledGeometry> ellipse_implicit() {
  GeometryDefinition def;
  def.type = GeometryType::implicit_curve;
  def.formulas = {{"equations[0]", "x^2/4+y^2-1"}};
  def.domain = {{"x", {-3, 3}}, {"y", {-2, 2}}};
  return compile_geometry(def);
}

ProjectionResult project(const CompiledGeometry& g, std::array<double, 3> p, const Options& o = {}) {
  return g.project(p.data(), "auto", o).value();
}

}  // namespace

TEST_CASE("a closed curve's ends are one interior point") {
  const auto closed = closed_circle(0, 2 * kPi);
  const ProjectionResult r = project(*closed, {2, 0, 0});
  REQUIRE(r.summary.status == Status::converged);
  CHECK(r.distance == doctest::Approx(1.0).epsilon(1e-15));
  CHECK(r.summary.location == Location::interior);
  CHECK_FALSE(r.summary.on_boundary);
  CHECK(r.summary.residual() <= 1e-12);
  // the same point of an open arc ending there is its endpoint
  const auto arc = closed_circle(0, kPi);
  const ProjectionResult e = project(*arc, {2, -1, 0});
  CHECK(e.summary.location == Location::endpoint);
  CHECK(e.summary.on_boundary);
  CHECK(e.distance == doctest::Approx(std::sqrt(2.0)).epsilon(1e-15));
}

TEST_CASE("curves beyond max_distance: no foot point, parameter or distance") {
  Options o;
  o.max_distance = 2.0;
  const ProjectionResult far = project(*closed_circle(0, 2 * kPi), {10, 0, 0}, o);
  CHECK(far.summary.status == Status::beyond_max_distance);
  CHECK(std::isnan(far.distance));
  CHECK(std::isnan(far.foot[0]));
  CHECK(std::isnan(far.params[0]));
  // just beyond: the search solves and the answer (distance 2.5) is withheld all the same
  const ProjectionResult near_miss = project(*closed_circle(0, 2 * kPi), {3.5, 0, 0}, o);
  CHECK(near_miss.summary.status == Status::beyond_max_distance);
  CHECK(std::isnan(near_miss.distance));
  const ProjectionResult within = project(*closed_circle(0, 2 * kPi), {2.5, 0, 0}, o);
  CHECK(within.summary.status == Status::converged);
  CHECK(within.distance == doctest::Approx(1.5).epsilon(1e-15));
  // implicit curves alike: the ellipse x^2/4 + y^2 = 1 is 9 - 1 = 8 from (0, 9)
  const ProjectionResult implicit = project(*ellipse_implicit(), {0, 9, 0}, o);
  CHECK(implicit.summary.status == Status::beyond_max_distance);
  CHECK(std::isnan(implicit.distance));
  CHECK(std::isnan(implicit.foot[1]));
}

TEST_CASE("all_minima on a curve is capped by max_minima, and says when it cut") {
  // a six-petal rosette (1 + cos(6t)/5)(cos t, sin t) seen from its centre: six tied minima at
  // 4/5, at t = π/6 + kπ/3
  Options o;
  o.all_minima = true;
  GeometryDefinition def;
  def.type = GeometryType::parametric_curve;
  def.formulas = {{"x", "(1+cos(6*t)/5)*cos(t)"}, {"y", "(1+cos(6*t)/5)*sin(t)"}};
  def.domain = {{"t", {0, 2 * kPi}}};
  const auto g = compile_geometry(def);
  const ProjectionResult all = project(*g, {0, 0, 0}, o);
  CHECK(all.distance == doctest::Approx(0.8).epsilon(1e-15));
  CHECK(all.summary.multiplicity.kind == Multiplicity::tied);
  CHECK(all.summary.multiplicity.count == 6);
  o.max_minima = 3;
  const ProjectionResult capped = project(*g, {0, 0, 0}, o);
  REQUIRE(all.minima.size() >= 6);
  CHECK_FALSE(all.minima_truncated);
  CHECK(capped.minima.size() == 3);
  CHECK(capped.minima_truncated);
  for (std::size_t i = 0; i < 3; ++i) CHECK(capped.minima[i].distance == all.minima[i].distance);
  // two minima (an ellipse seen from its centre: (0, ±1)) fit under any cap but 1
  const ProjectionResult two = project(*ellipse_implicit(), {0, 0, 0}, o);
  CHECK(two.minima.size() == 2);
  CHECK_FALSE(two.minima_truncated);
  o.max_minima = 1;
  const ProjectionResult one = project(*ellipse_implicit(), {0, 0, 0}, o);
  CHECK(one.minima.size() == 1);
  CHECK(one.minima_truncated);
  CHECK(one.minima[0].distance == doctest::Approx(1.0).epsilon(1e-14));
}

TEST_CASE("the multiplicity of a curve's answer: unique, tied, or a continuum") {
  // from the closed_circle's centre every point is nearest: a continuum, one representative in all_minima
  Options o;
  o.all_minima = true;
  const ProjectionResult centre = project(*closed_circle(0, 2 * kPi), {0, 0, 0}, o);
  CHECK(centre.summary.status == Status::converged);
  CHECK(centre.summary.multiplicity.kind == Multiplicity::continuum);
  CHECK(centre.minima.size() == 1);
  CHECK(centre.distance == doctest::Approx(1.0).epsilon(1e-15));
  // the ellipse (2 cos t, sin t) from its centre: (0, ±1), tied
  GeometryDefinition def;
  def.type = GeometryType::parametric_curve;
  def.formulas = {{"x", "2*cos(t)"}, {"y", "sin(t)"}};
  def.domain = {{"t", {0, 2 * kPi}}};
  const auto ellipse = compile_geometry(def);
  const ProjectionResult two = project(*ellipse, {0, 0, 0});
  REQUIRE(two.summary.multiplicity.kind == Multiplicity::tied);
  CHECK(two.summary.multiplicity.count == 2);
  CHECK(std::abs(two.summary.multiplicity.feet[0][1] + two.summary.multiplicity.feet[1][1]) <= 1e-15);
  CHECK(std::abs(std::abs(two.summary.multiplicity.feet[1][1]) - 1.0) <= 1e-15);
  // off the axes: one nearest point
  const ProjectionResult one = project(*ellipse, {0.5, 0.3, 0});
  CHECK(one.summary.multiplicity.kind == Multiplicity::unique);
  CHECK(one.summary.multiplicity.feet.empty());
}

TEST_CASE("the multiplicity of an implicit curve's answer: unique, tied, or a continuum") {
  // x^2/4 + y^2 = 1 from its centre: (0, ±1) at distance 1, tied; off the axes, unique
  const ProjectionResult two = project(*ellipse_implicit(), {0, 0, 0});
  CHECK(two.summary.status == Status::converged);
  CHECK(two.distance == doctest::Approx(1.0).epsilon(1e-14));
  REQUIRE(two.summary.multiplicity.kind == Multiplicity::tied);
  CHECK(two.summary.multiplicity.count == 2);
  for (const auto& foot : two.summary.multiplicity.feet) {
    CHECK(std::abs(foot[0]) <= 1e-12);
    CHECK(std::abs(std::abs(foot[1]) - 1.0) <= 1e-12);
  }
  CHECK(std::abs(two.summary.multiplicity.feet[0][1] + two.summary.multiplicity.feet[1][1]) <= 1e-12);
  const ProjectionResult one = project(*ellipse_implicit(), {0.5, 0.3, 0});
  CHECK(one.summary.multiplicity.kind == Multiplicity::unique);
  CHECK(one.summary.multiplicity.computed);
  // the unit closed_circle from its centre: every point nearest, one representative in all_minima
  GeometryDefinition def;
  def.type = GeometryType::implicit_curve;
  def.formulas = {{"equations[0]", "x^2+y^2-1"}};
  def.domain = {{"x", {-2, 2}}, {"y", {-2, 2}}};
  Options o;
  o.all_minima = true;
  const ProjectionResult centre = project(*compile_geometry(def), {0, 0, 0}, o);
  CHECK(centre.summary.multiplicity.kind == Multiplicity::continuum);
  CHECK(centre.minima.size() == 1);
  CHECK(centre.distance == doctest::Approx(1.0).epsilon(1e-14));
  // the closed_circle x^2 + y^2 + z^2 = 4, z = 1 (radius √3) from a point of its axis: √(3 + 4^2), a
  // continuum; off the axis, unique
  GeometryDefinition spatial;
  spatial.type = GeometryType::implicit_curve;
  spatial.formulas = {{"equations[0]", "x^2+y^2+z^2-4"}, {"equations[1]", "z-1"}};
  spatial.domain = {{"x", {-3, 3}}, {"y", {-3, 3}}, {"z", {-3, 3}}};
  const auto ring = compile_geometry(spatial);
  const ProjectionResult axis = project(*ring, {0, 0, 5});
  CHECK(axis.summary.multiplicity.kind == Multiplicity::continuum);
  CHECK(axis.distance == doctest::Approx(std::sqrt(19.0)).epsilon(1e-14));
  CHECK(project(*ring, {0.2, 0, 5}).summary.multiplicity.kind == Multiplicity::unique);
}
