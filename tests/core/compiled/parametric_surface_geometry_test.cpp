// The compiled parametric surface (core/compiled/parametric_surface_geometry.hpp): what it is at
// parameters (evaluate: the torus's point, first and second derivatives and unit normal in closed
// form; none at a cone's apex), its foot normal and signed distance, its seams, poles and
// self-covering found at compile time, its method table and the dispatch through it (each
// method's answer the torus's closed-form foot, certify honoured), its size accounting, and the
// definitions it refuses with which error.
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <string>

#include "closed_forms.hpp"
#include "compile_definition.hpp"
#include "compiled/parametric_surface_geometry.hpp"
#include "geometry_checks.hpp"

using namespace footpoint;

namespace parametric_surface_geometry_test {

const double kTwoPi = 2 * std::numbers::pi;

// The torus of radii 3 and 1 about the z axis.
std::shared_ptr<const CompiledGeometry> torus(double umax = kTwoPi) {
  return test::compile_definition(GeometryType::parametric_surface,
                                  {{"x", "(3+cos(v))*cos(u)"}, {"y", "(3+cos(v))*sin(u)"}, {"z", "sin(v)"}},
                                  {{"u", {0.0, umax}}, {"v", {0.0, kTwoPi}}});
}

// The cone z = sqrt(x^2 + y^2), z in [0, 1]: its apex is the edge v = 0.
std::shared_ptr<const CompiledGeometry> cone() {
  return test::compile_definition(GeometryType::parametric_surface,
                                  {{"x", "v*cos(u)"}, {"y", "v*sin(u)"}, {"z", "v"}},
                                  {{"u", {0.0, kTwoPi}}, {"v", {0.0, 1.0}}});
}

const ParametricSurface& as_surface(const std::shared_ptr<const CompiledGeometry>& g) {
  return dynamic_cast<const ParametricSurface&>(*g);
}

}  // namespace parametric_surface_geometry_test

TEST_CASE(
    "parametric surface: evaluate gives the torus's derivatives and normal; no normal at a cone's apex") {
  const auto g = parametric_surface_geometry_test::torus();
  for (const std::array<double, 2> t :
       {std::array<double, 2>{0.0, 0.0}, {0.7, 2.1}, {3.5, 4.4}, {6.0, 0.3}, {-0.5, 1.0}}) {
    const double u = t[0], v = t[1], w = 3 + std::cos(v);
    CAPTURE(u);
    CAPTURE(v);
    const double cu = std::cos(u), su = std::sin(u), cv = std::cos(v), sv = std::sin(v);
    Evaluation e;
    REQUIRE(g->evaluate(t.data(), e));
    test::check_vec_close(e.point, {w * cu, w * su, sv});
    test::check_vec_close(e.first[0], {-w * su, w * cu, 0.0});
    test::check_vec_close(e.first[1], {-sv * cu, -sv * su, cv});
    test::check_vec_close(e.second[0], {-w * cu, -w * su, 0.0});
    test::check_vec_close(e.second[1], {sv * su, -sv * cu, 0.0});
    test::check_vec_close(e.second[2], {-cv * cu, -cv * su, -sv});
    // s_u x s_v = w (cos u cos v, sin u cos v, sin v): the outward unit normal.
    CHECK(e.normal_defined);
    test::check_vec_close(e.normal, {cu * cv, su * cv, sv});
    CHECK(e.inside_domain == (u >= 0.0));
  }
  // At the apex s_u = 0: no normal.
  const auto c = parametric_surface_geometry_test::cone();
  Evaluation e;
  const std::array<double, 2> apex{1.0, 0.0};
  REQUIRE(c->evaluate(apex.data(), e));
  CHECK_FALSE(e.normal_defined);
  test::check_vec_close(e.first[1], {std::cos(1.0), std::sin(1.0), 1.0});
}

TEST_CASE("parametric surface: the foot normal and signed distance; none at a pole") {
  const auto g = parametric_surface_geometry_test::torus();
  for (const Vec3 p : {Vec3{5.0, 1.0, 0.5}, Vec3{-2.0, 2.5, -0.3}, Vec3{0.5, -3.0, 1.5}}) {
    CAPTURE(p.x);
    const Vec3 foot = test::torus_foot(3, 1, p);
    const double signed_distance = test::torus_signed_distance(3, 1, p);
    const std::array<double, 3> at{p.x, p.y, p.z};
    const ProjectionResult r = g->project(at.data(), "auto", {}).value();
    REQUIRE(r.summary.status == Status::converged);
    CHECK(r.distance == doctest::Approx(std::abs(signed_distance)).epsilon(1e-12));
    REQUIRE(r.has_normal());
    // The outward normal at the foot is (foot - c) / 1, the sign that of |p - c| - 1.
    const Vec3 c{3 * p.x / std::hypot(p.x, p.y), 3 * p.y / std::hypot(p.x, p.y), 0.0};
    test::check_vec_close({r.normal[0], r.normal[1], r.normal[2]}, foot - c);
    CHECK(r.signed_distance == doctest::Approx(signed_distance).epsilon(1e-12));
  }
  // Below the cone's apex on its axis: the apex at distance 1 (|p - s|^2 = r^2 + (r + 1)^2 grows
  // with r = v), a pole, no normal.
  const auto c = parametric_surface_geometry_test::cone();
  const std::array<double, 3> below{0.0, 0.0, -1.0};
  const ProjectionResult r = c->project(below.data(), "auto", {}).value();
  CHECK(r.distance == doctest::Approx(1.0).epsilon(1e-12));
  CHECK(r.summary.location == Location::pole);
  CHECK_FALSE(r.has_normal());
}

TEST_CASE("parametric surface: seams, poles and self-covering found at compile time") {
  const auto torus_compiled = parametric_surface_geometry_test::torus();
  const auto& torus = parametric_surface_geometry_test::as_surface(torus_compiled);
  CHECK(torus.closure().periodic(0));
  CHECK(torus.closure().periodic(1));
  for (const BoxEdge edge : {BoxEdge::umin, BoxEdge::umax, BoxEdge::vmin, BoxEdge::vmax})
    CHECK_FALSE(torus.closure().pole(edge));
  CHECK(torus.self_covering().translations.empty());
  // Two turns in u: the formulas repeat under (2 pi, 0).
  const auto twice_compiled =
      parametric_surface_geometry_test::torus(2 * parametric_surface_geometry_test::kTwoPi);
  const auto& twice = parametric_surface_geometry_test::as_surface(twice_compiled);
  REQUIRE_FALSE(twice.self_covering().translations.empty());
  CHECK(twice.self_covering().translations[0][0] ==
        doctest::Approx(parametric_surface_geometry_test::kTwoPi).epsilon(1e-12));
  CHECK(twice.self_covering().translations[0][1] == 0.0);

  const auto cone_compiled = parametric_surface_geometry_test::cone();
  const auto& cone = parametric_surface_geometry_test::as_surface(cone_compiled);
  CHECK(cone.closure().periodic(0));
  CHECK_FALSE(cone.closure().seams[1].closed);
  CHECK(cone.closure().pole(BoxEdge::vmin));
  CHECK_FALSE(cone.closure().pole(BoxEdge::vmax));
  test::check_vec_close(cone.closure().poles[static_cast<std::size_t>(BoxEdge::vmin)].point, {0.0, 0.0, 0.0});
}

TEST_CASE("parametric surface: the method table, dispatch by name, certify on the papers' methods") {
  const auto g = parametric_surface_geometry_test::torus();
  test::check_method_table(
      *g, GeometryType::parametric_surface, "curvature_circle",
      "unknown method 'curvature_circle' for a parametric_surface (auto, gsa, first_order, hybrid, newton)");
  // p = (4.5 cos 1, 4.5 sin 1, 0.5) has its foot at u = 1, v = atan(1/3): every method from
  // (1.1, 0.4), inside the domain.
  const Vec3 p{4.5 * std::cos(1.0), 4.5 * std::sin(1.0), 0.5};
  const Vec3 foot = test::torus_foot(3, 1, p);
  const double signed_distance = test::torus_signed_distance(3, 1, p);
  const std::array<double, 3> at{p.x, p.y, p.z};
  Options options;
  options.initial = std::array<double, 3>{1.1, 0.4, 0.0};
  for (const MethodInfo& info : g->methods()) {
    CAPTURE(info.name);
    const ProjectionResult r = g->project(at.data(), info.name, options).value();
    CHECK(r.summary.method == info.name);
    REQUIRE(r.summary.status == Status::converged);
    CHECK(r.distance == doctest::Approx(signed_distance).epsilon(1e-12));
    test::check_vec_close({r.foot[0], r.foot[1], r.foot[2]}, foot);
    CHECK(r.params[0] == doctest::Approx(1.0).epsilon(1e-12));
    CHECK(r.params[1] == doctest::Approx(std::atan(1.0 / 3.0)).epsilon(1e-12));
  }
  test::check_certify_option(*g, at.data(), options);
}

TEST_CASE("parametric surface: memory counts the formulas and the cells, growing with the domain") {
  const auto small = test::compile_definition(GeometryType::parametric_surface,
                                              {{"x", "u"}, {"y", "v"}, {"z", "sin(u)*sin(v)"}},
                                              {{"u", {-2.0, 2.0}}, {"v", {-2.0, 2.0}}});
  const auto large = test::compile_definition(GeometryType::parametric_surface,
                                              {{"x", "u"}, {"y", "v"}, {"z", "sin(u)*sin(v)"}},
                                              {{"u", {-20.0, 20.0}}, {"v", {-20.0, 20.0}}});
  for (const auto& g : {small, large}) {
    const auto& s = parametric_surface_geometry_test::as_surface(g);
    CHECK(s.memory_bytes() >=
          sizeof(ParametricSurface) + s.formulas().program().memory_bytes() + s.cells().memory_bytes());
  }
  // A hundred times the area, a hundred times the bumps: more cells.
  CHECK(large->memory_bytes() > 4 * small->memory_bytes());
}

TEST_CASE("parametric surface: the definitions it refuses, with the field at fault") {
  using test::compile_error_code;
  std::string field;
  GeometryDefinition def{GeometryType::parametric_surface,
                         {{"x", "u"}, {"y", "v"}},
                         {{"u", {0.0, 1.0}}, {"v", {0.0, 1.0}}},
                         {},
                         {}};
  CHECK(compile_error_code(def, &field) == "bad_formulas");
  def.formulas = {{"x", "u"}, {"z", "v"}, {"y", "u*v"}};
  CHECK(compile_error_code(def, &field) == "bad_formulas");
  CHECK(field == "y");
  def.formulas = {{"x", "u"}, {"y", "v"}, {"z", "u*v"}};
  def.domain = {{"u", {0.0, 1.0}}};
  CHECK(compile_error_code(def, &field) == "bad_domain");
  CHECK(field == "domain.v");
  def.domain = {{"u", {0.0, 1.0}}, {"v", {1.0, 1.0}}};
  CHECK(compile_error_code(def, &field) == "bad_domain");
  CHECK(field == "domain.v");
  def.domain = {{"u", {0.0, 1.0}}, {"v", {0.0, 1.0}}};
  def.formulas = {{"x", "u"}, {"y", "v"}, {"z", "u*t"}};
  CHECK(compile_error_code(def, &field) == "unknown_variable");
  CHECK(field == "z");
  def.formulas = {{"x", "u"}, {"y", "v"}, {"z", "u*v"}};
  def.periodic = {"t"};
  CHECK(compile_error_code(def, &field) == "unknown_parameter");
  // The saddle's edges u = 0 and u = 1 are different lines: u is not periodic.
  def.periodic = {"u"};
  CHECK(compile_error_code(def, &field) == "not_periodic");
  CHECK(field == "periodic");
  def.periodic = {};
  CHECK(compile_error_code(def).empty());
  test::check_limits_refuse(def);
}
