// The compiled parametric curve (core/compiled/parametric_curve_geometry.hpp): what it is at a
// parameter (evaluate: point, c', c'', principal normal against the helix's and the line's closed
// forms), its foot normal and signed distance (a planar curve's tangent turned by +90 degrees; none
// in space), its closure, its samples (points of the curve, ends included), its method table and
// the dispatch through it (each method's answer the circle's closed form, certify honoured), its
// size accounting, and the definitions it refuses with which error.
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "compile_definition.hpp"
#include "compiled/parametric_curve_geometry.hpp"
#include "geometry_checks.hpp"

using namespace footpoint;

namespace parametric_curve_geometry_test {

const ParametricCurve& as_curve(const std::shared_ptr<const CompiledGeometry>& g) {
  return dynamic_cast<const ParametricCurve&>(*g);
}

}  // namespace parametric_curve_geometry_test

TEST_CASE("parametric curve: evaluate gives the helix's point, derivatives and principal normal") {
  // c(t) = (2 cos t, 2 sin t, t/2): c' = (-2 sin t, 2 cos t, 1/2), c'' = (-2 cos t, -2 sin t, 0),
  // orthogonal to c', so the principal normal is c'' / |c''| = (-cos t, -sin t, 0).
  const auto g =
      test::compile_definition(GeometryType::parametric_curve,
                               {{"x", "2*cos(t)"}, {"y", "2*sin(t)"}, {"z", "t/2"}}, {{"t", {0.0, 10.0}}});
  for (const double t : {0.0, 0.3, 2.9, 7.5, 10.0, 11.0, -0.5}) {
    CAPTURE(t);
    Evaluation e;
    REQUIRE(g->evaluate(&t, e));
    test::check_vec_close(e.point, {2 * std::cos(t), 2 * std::sin(t), t / 2});
    test::check_vec_close(e.first[0], {-2 * std::sin(t), 2 * std::cos(t), 0.5});
    test::check_vec_close(e.second[0], {-2 * std::cos(t), -2 * std::sin(t), 0.0});
    CHECK(e.normal_defined);
    test::check_vec_close(e.normal, {-std::cos(t), -std::sin(t), 0.0});
    CHECK(e.inside_domain == (t >= 0.0 && t <= 10.0));
  }
  // A straight line has no curvature: no principal normal.
  const auto line = test::compile_definition(GeometryType::parametric_curve, {{"x", "1+2*t"}, {"y", "3-t"}},
                                             {{"t", {-1.0, 1.0}}});
  Evaluation e;
  const double t = 0.25;
  REQUIRE(line->evaluate(&t, e));
  test::check_vec_close(e.point, {1.5, 2.75, 0.0});
  test::check_vec_close(e.first[0], {2.0, -1.0, 0.0});
  CHECK_FALSE(e.normal_defined);
}

TEST_CASE("parametric curve: a planar curve's foot normal is its tangent turned +90 degrees; none in space") {
  // The ellipse (3 cos t, sin t) runs counter-clockwise: (-y', x') / |c'| points inward. From
  // (0, 2) and (0, 0.5) the foot is (0, 1) (t = pi/2, c' = (-3, 0), normal (0, -1)): outside the
  // signed distance is -1, inside +0.5.
  const auto ellipse = test::compile_definition(GeometryType::parametric_curve,
                                                {{"x", "3*cos(t)"}, {"y", "sin(t)"}}, {{"t", {0.0, 3.0}}});
  for (const auto& [y, signed_distance] : {std::pair{2.0, -1.0}, std::pair{0.5, 0.5}}) {
    const std::array<double, 2> p{0.0, y};
    const ProjectionResult r = ellipse->project(p.data(), "auto", {}).value();
    REQUIRE(r.summary.status == Status::converged);
    CHECK(r.params[0] == doctest::Approx(std::numbers::pi / 2).epsilon(1e-12));
    REQUIRE(r.has_normal());
    CHECK(std::abs(r.normal[0]) <= 1e-12);
    CHECK(r.normal[1] == doctest::Approx(-1.0).epsilon(1e-12));
    CHECK(r.signed_distance == doctest::Approx(signed_distance).epsilon(1e-12));
  }
  const auto helix = test::compile_definition(
      GeometryType::parametric_curve, {{"x", "cos(t)"}, {"y", "sin(t)"}, {"z", "t"}}, {{"t", {0.0, 6.0}}});
  const std::array<double, 3> q{2.0, 0.5, 1.0};
  const ProjectionResult r = helix->project(q.data(), "auto", {}).value();
  CHECK(r.summary.status == Status::converged);
  CHECK_FALSE(r.has_normal());
  CHECK(std::isnan(r.signed_distance));
}

TEST_CASE("parametric curve: closure found or declared, samples on the curve with both ends") {
  const double two_pi = 2 * std::numbers::pi;
  const auto closed_curve = test::compile_definition(
      GeometryType::parametric_curve, {{"x", "3*cos(t)"}, {"y", "sin(t)"}}, {{"t", {0.0, two_pi}}});
  const ParametricCurve& closed = parametric_curve_geometry_test::as_curve(closed_curve);
  CHECK(closed.closure().closed);
  CHECK(closed.closure().smooth);
  CHECK_FALSE(closed.closure().declared);
  const auto open_curve = test::compile_definition(GeometryType::parametric_curve,
                                                   {{"x", "3*cos(t)"}, {"y", "sin(t)"}}, {{"t", {0.0, 3.0}}});
  const ParametricCurve& open = parametric_curve_geometry_test::as_curve(open_curve);
  CHECK_FALSE(open.closure().closed);
  // c(0) = (3, 0), c(3) = (3 cos 3, sin 3).
  CHECK(open.closure().gap ==
        doctest::Approx(std::hypot(3 * std::cos(3.0) - 3, std::sin(3.0))).epsilon(1e-12));
  // Declared periodic where the ends meet: accepted, and said so.
  GeometryDefinition def{
      GeometryType::parametric_curve, {{"x", "cos(t)"}, {"y", "sin(t)"}}, {{"t", {0.0, two_pi}}}, {}, {"t"}};
  CHECK(parametric_curve_geometry_test::as_curve(compile_parametric_curve(def, {})).closure().declared);

  // The samples are points of the curve at their parameters, over the whole domain.
  const CurveSamples& s = open.samples();
  REQUIRE(s.params.size() == s.points.size());
  REQUIRE(s.points.size() > 10);
  double lo = 10.0, hi = -10.0;
  for (std::size_t i = 0; i < s.points.size(); ++i) {
    const double t = s.params[i];
    lo = std::min(lo, t);
    hi = std::max(hi, t);
    test::check_vec_close(s.points[i], {3 * std::cos(t), std::sin(t), 0.0});
  }
  CHECK(lo == 0.0);
  CHECK(hi == 3.0);
}

TEST_CASE("parametric curve: the method table, dispatch by name, certify on the local methods") {
  const auto circle = test::compile_definition(GeometryType::parametric_curve,
                                               {{"x", "2*cos(t)"}, {"y", "2*sin(t)"}}, {{"t", {-3.0, 3.0}}});
  // The same table for planar and spatial curves, the one methods_of lists.
  test::check_method_table(*circle, GeometryType::parametric_curve, "gsa",
                           "unknown method 'gsa' for a parametric_curve (auto, newton, curvature_circle)");
  const std::array<double, 2> p{1.0, 0.5};  // foot 2 p / |p|, distance 2 - |p|
  const double r = std::hypot(1.0, 0.5);
  for (const MethodInfo& info : circle->methods()) {
    CAPTURE(info.name);
    const auto method = circle->method(info.name);
    REQUIRE(method);
    CHECK(method->info().name == info.name);
    const ProjectionResult answer = method->project(p.data(), {});
    CHECK(answer.summary.method == info.name);
    CHECK(answer.summary.status == Status::converged);
    CHECK(answer.distance == doctest::Approx(2.0 - r).epsilon(1e-12));
    CHECK(answer.foot[0] == doctest::Approx(2.0 / r).epsilon(1e-12));
    CHECK(answer.foot[1] == doctest::Approx(1.0 / r).epsilon(1e-12));
    CHECK(answer.params[0] == doctest::Approx(std::atan2(0.5, 1.0)).epsilon(1e-12));
  }
  test::check_certify_option(*circle, p.data(), {});
}

TEST_CASE("parametric curve: memory counts formulas, samples, their tree and cells, growing with the curve") {
  // (cos t, sin(k t)) over [0, 2 pi]: the same bounding box (the samples' spacing is relative to
  // it), about k times the length for k = 10 than for k = 1.
  const auto lissajous = [](const char* y) {
    return test::compile_definition(GeometryType::parametric_curve, {{"x", "cos(t)"}, {"y", y}},
                                    {{"t", {0.0, 2 * std::numbers::pi}}});
  };
  const auto short_compiled = lissajous("sin(t)"), long_compiled = lissajous("sin(10*t)");
  const ParametricCurve& short_curve = parametric_curve_geometry_test::as_curve(short_compiled);
  const ParametricCurve& long_curve = parametric_curve_geometry_test::as_curve(long_compiled);
  for (const ParametricCurve* c : {&short_curve, &long_curve})
    CHECK(c->memory_bytes() >= sizeof(ParametricCurve) + c->formulas().program().memory_bytes() +
                                   c->samples().memory_bytes() + c->sample_index().memory_bytes() +
                                   c->cells().memory_bytes());
  const std::size_t more = long_curve.samples().points.size() - short_curve.samples().points.size();
  CHECK(long_curve.samples().points.size() > 3 * short_curve.samples().points.size());
  // Each sample commits the curve to at least its own bytes.
  CHECK(long_curve.memory_bytes() - short_curve.memory_bytes() >= more * ParametricSampling::kSampleBytes);
}

TEST_CASE("parametric curve: the definitions it refuses, with the field at fault") {
  using test::compile_error_code;
  std::string field;
  GeometryDefinition def{
      GeometryType::parametric_curve, {{"y", "t"}, {"x", "t"}}, {{"t", {0.0, 1.0}}}, {}, {}};
  CHECK(compile_error_code(def, &field) == "wrong_shape");
  CHECK(field == "y");
  def.formulas = {{"x", "t"}, {"y", "t"}, {"z", "t"}, {"w", "t"}};
  CHECK(compile_error_code(def, &field) == "wrong_shape");
  CHECK(field == "formulas");
  def.formulas = {{"x", "t"}, {"y", "t*t"}};
  def.domain = {{"s", {0.0, 1.0}}};
  CHECK(compile_error_code(def, &field) == "bad_domain");
  CHECK(field == "domain.t");
  def.domain = {{"t", {0.0, std::numeric_limits<double>::infinity()}}};
  CHECK(compile_error_code(def, &field) == "bad_domain");
  def.domain = {{"t", {0.0, 1.0}}};
  def.formulas = {{"x", "t"}, {"y", "u*t"}};  // u is no variable of a curve
  CHECK(compile_error_code(def, &field) == "unknown_variable");
  CHECK(field == "y");
  def.formulas = {{"x", "t"}, {"y", "t*t"}};
  def.periodic = {"u"};
  CHECK(compile_error_code(def, &field) == "unknown_parameter");
  CHECK(field == "periodic");
  // Declared periodic, but c(0) = (0, 0) and c(1) = (1, 1) do not meet.
  def.periodic = {"t"};
  CHECK(compile_error_code(def, &field) == "not_periodic");
  CHECK(field == "periodic");
  def.periodic = {};
  CHECK(compile_error_code(def).empty());
  test::check_limits_refuse(def);
}
