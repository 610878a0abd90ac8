// The compiled implicit surface (core/compiled/implicit_surface_geometry.hpp): its equation at a
// point (evaluate_equations: value, gradient and Hessian against an ellipsoid's closed forms, the
// unit normal of the square-free equation where the written gradient vanishes), its foot normals
// and signed distances (none at a cone's apex), the factor surfaces it splits into (a product's
// factors with cells in the box, the others dropped), its method table and the dispatch through it
// (each method's answer the sphere's closed form, certify honoured), its size accounting, and the
// definitions it refuses with which error.
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <string>

#include "compile_definition.hpp"
#include "compiled/implicit_surface_geometry.hpp"
#include "geometry_checks.hpp"

using namespace footpoint;

namespace implicit_surface_geometry_test {

std::shared_ptr<const CompiledGeometry> in_cube(const std::string& f, double half = 2.0) {
  return test::compile_definition(GeometryType::implicit_surface, {{"equation", f}},
                                  {{"x", {-half, half}}, {"y", {-half, half}}, {"z", {-half, half}}});
}

const ImplicitSurface& as_surface(const std::shared_ptr<const CompiledGeometry>& g) {
  return dynamic_cast<const ImplicitSurface&>(*g);
}

}  // namespace implicit_surface_geometry_test

TEST_CASE("implicit surface: evaluate_equations gives the ellipsoid's value, gradient, Hessian and normal") {
  // f = x^2/4 + y^2 + 4 z^2 - 1: grad f = (x/2, 2y, 8z), Hessian diag(1/2, 2, 8).
  const auto g = implicit_surface_geometry_test::in_cube("x^2/4+y^2+4*z^2-1");
  for (const Vec3 x : {Vec3{2.0, 0.0, 0.0}, Vec3{0.3, -0.7, 0.25}, Vec3{-1.0, 3.0, 0.5}}) {
    CAPTURE(x.y);
    const std::array<double, 3> at{x.x, x.y, x.z};
    EquationEvaluation e;
    REQUIRE(g->evaluate_equations(at.data(), e));
    CHECK(e.equations == 1);
    CHECK(e.value[0] == doctest::Approx(x.x * x.x / 4 + x.y * x.y + 4 * x.z * x.z - 1).epsilon(1e-12));
    const Vec3 grad{x.x / 2, 2 * x.y, 8 * x.z};
    test::check_vec_close(e.gradient[0], grad);
    test::check_vec_close(e.hessian[0][0], {0.5, 0.0, 0.0});
    test::check_vec_close(e.hessian[0][1], {0.0, 2.0, 0.0});
    test::check_vec_close(e.hessian[0][2], {0.0, 0.0, 8.0});
    REQUIRE(e.normal_defined);
    test::check_vec_close(e.normal, grad / norm(grad));
    CHECK(e.inside_box == (std::abs(x.y) <= 2.0));
  }
  // A parametric geometry's evaluation is not an implicit one's.
  Evaluation none;
  const std::array<double, 2> t{0.0, 0.0};
  CHECK_FALSE(g->evaluate(t.data(), none));
}

TEST_CASE("implicit surface: a squared sphere keeps its normal; foot normals and signed distances") {
  // (x^2 + y^2 + z^2 - 1)^2: the written gradient vanishes on the sphere, the square-free one is
  // 2 x, the outward normal x.
  const auto g = implicit_surface_geometry_test::in_cube("(x^2+y^2+z^2-1)^2");
  const auto& s = implicit_surface_geometry_test::as_surface(g);
  CHECK_FALSE(s.written_equation().program().same_tape(s.equation().program()));
  const std::array<double, 3> on{0.48, 0.6, 0.64};  // 0.2304 + 0.36 + 0.4096 = 1
  EquationEvaluation e;
  REQUIRE(g->evaluate_equations(on.data(), e));
  CHECK(norm(e.gradient[0]) <= 1e-14);
  REQUIRE(e.normal_defined);
  test::check_vec_close(e.normal, {0.48, 0.6, 0.64});
  // From outside and inside: the foot p / |p|, the distance signed by the outward normal.
  for (const auto& [p, signed_distance] : {std::pair{std::array<double, 3>{0.96, 1.2, 1.28}, 1.0},
                                           std::pair{std::array<double, 3>{0.0, -0.5, 0.0}, -0.5}}) {
    const ProjectionResult r = g->project(p.data(), "auto", {}).value();
    REQUIRE(r.summary.status == Status::converged);
    const double len = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    test::check_vec_close({r.foot[0], r.foot[1], r.foot[2]}, {p[0] / len, p[1] / len, p[2] / len});
    REQUIRE(r.has_normal());
    test::check_vec_close({r.normal[0], r.normal[1], r.normal[2]}, {p[0] / len, p[1] / len, p[2] / len});
    CHECK(r.signed_distance == doctest::Approx(signed_distance).epsilon(1e-12));
  }
  // The cone x^2 + y^2 - z^2 = 0 at its apex: a singular point, no normal.
  const auto cone = implicit_surface_geometry_test::in_cube("x^2+y^2-z^2", 1.0);
  const std::array<double, 3> apex{0.0, 0.0, 0.0};
  const ProjectionResult r = cone->project(apex.data(), "auto", {}).value();
  CHECK(r.distance <= 1e-15);
  CHECK(r.summary.location == Location::singular_point);
  CHECK_FALSE(r.has_normal());
}

TEST_CASE("implicit surface: a product splits into its factor surfaces with cells in the box") {
  // The unit sphere times the plane z = 0: two pieces; from (0, 0, 0.3) the plane is nearest
  // (0.3 < 0.7), from (0, 0, 0.9) the sphere (0.1).
  const auto both = implicit_surface_geometry_test::in_cube("(x^2+y^2+z^2-1)*z");
  const auto& s = implicit_surface_geometry_test::as_surface(both);
  CHECK(s.pieces().size() == 2);
  for (const auto& [z, d] : {std::pair{0.3, 0.3}, std::pair{0.9, 0.1}}) {
    const std::array<double, 3> p{0.0, 0.0, z};
    const ProjectionResult r = both->project(p.data(), "auto", {}).value();
    CHECK(r.distance == doctest::Approx(d).epsilon(1e-12));
  }
  // The plane x = 10 has no point in [-2, 2]^3: one piece, the sphere.
  const auto far = implicit_surface_geometry_test::in_cube("(x^2+y^2+z^2-1)*(x-10)");
  const auto& one = implicit_surface_geometry_test::as_surface(far);
  REQUIRE(one.pieces().size() == 1);
  const std::array<double, 3> q{0.0, 0.0, 2.0};
  double value = 0.0;
  one.pieces()[0].equation.program().values(q.data(), &value);
  CHECK(value == doctest::Approx(3.0).epsilon(1e-12));  // x^2 + y^2 + z^2 - 1
  // The compiled size holds every piece's cells.
  std::size_t cells = 0;
  for (const auto& piece : s.pieces()) cells += piece.cells.memory_bytes();
  CHECK(both->memory_bytes() >= sizeof(ImplicitSurface) + s.equation().program().memory_bytes() + cells);
}

TEST_CASE("implicit surface: the method table, dispatch by name, certify on the local methods") {
  const auto g = implicit_surface_geometry_test::in_cube("x^2+y^2+z^2-4", 3.0);
  test::check_method_table(
      *g, GeometryType::implicit_surface, "newton",
      "unknown method 'newton' for a implicit_surface (auto, lagrange_newton, first_order, hu_wallner)");
  // The sphere of radius 2: foot 2 p / |p|, distance |p| - 2.
  const std::array<double, 3> p{1.0, 2.0, 2.0};
  for (const MethodInfo& info : g->methods()) {
    CAPTURE(info.name);
    const ProjectionResult r = g->project(p.data(), info.name, {}).value();
    CHECK(r.summary.method == info.name);
    REQUIRE(r.summary.status == Status::converged);
    CHECK(r.distance == doctest::Approx(1.0).epsilon(1e-12));
    test::check_vec_close({r.foot[0], r.foot[1], r.foot[2]}, {2.0 / 3, 4.0 / 3, 4.0 / 3});
  }
  test::check_certify_option(*g, p.data(), {});
}

TEST_CASE("implicit surface: the definitions it refuses, with the field at fault") {
  using test::compile_error_code;
  std::string field;
  GeometryDefinition def{GeometryType::implicit_surface,
                         {{"f", "x^2+y^2+z^2-1"}},
                         {{"x", {-2.0, 2.0}}, {"y", {-2.0, 2.0}}, {"z", {-2.0, 2.0}}},
                         {},
                         {}};
  CHECK(compile_error_code(def, &field) == "wrong_shape");
  CHECK(field == "equation");
  def.formulas = {{"equation", "x^2+y^2+z^2-1"}, {"equation", "z"}};
  CHECK(compile_error_code(def) == "wrong_shape");
  def.formulas = {{"equation", "x^2+y^2+z^2-1"}};
  def.periodic = {"u"};
  CHECK(compile_error_code(def, &field) == "unknown_parameter");
  CHECK(field == "periodic");
  def.periodic = {};
  def.domain.pop_back();
  CHECK(compile_error_code(def, &field) == "bad_domain");
  CHECK(field == "domain.z");
  def.domain.push_back({"z", {-2.0, 2.0}});
  def.formulas = {{"equation", "x^2+y^2+z^2-1+t"}};
  CHECK(compile_error_code(def, &field) == "unknown_variable");
  // No point in the box: a definition error.
  def.formulas = {{"equation", "x^2+y^2+z^2+1"}};
  CHECK(compile_error_code(def, &field) == "empty_surface");
  CHECK(field == "domain");
  def.formulas = {{"equation", "(x-5)^2+y^2+z^2-1"}};
  CHECK(compile_error_code(def) == "empty_surface");
  // The unit sphere in a box of 1e300: the leaves that may hold it are too large for Newton from
  // their centres to land on it; no point found is an error naming the box, not an empty answer.
  def.formulas = {{"equation", "x^2+y^2+z^2-1"}};
  def.domain = {{"x", {-1e300, 1e300}}, {"y", {-1e300, 1e300}}, {"z", {-1e300, 1e300}}};
  CHECK(compile_error_code(def, &field) == "geometry_too_complex");
  CHECK(field == "domain");
  def.domain = {{"x", {-2.0, 2.0}}, {"y", {-2.0, 2.0}}, {"z", {-2.0, 2.0}}};
  CHECK(compile_error_code(def).empty());
  test::check_limits_refuse(def);
}
