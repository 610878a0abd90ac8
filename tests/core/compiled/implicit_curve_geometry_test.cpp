// The compiled implicit curve (core/compiled/implicit_curve_geometry.hpp): its equations at a point
// (evaluate_equations: values, gradients and Hessians against the closed forms of an ellipse and
// of two quadrics, the unit normal of the square-free equation where the written gradient
// vanishes), its foot normals and signed distances, the factor curves it splits into (a product's
// factors with points in the box, the others dropped), its method table and the dispatch through
// it (each method's answer a circle's closed form, certify honoured), its size accounting, and the
// definitions it refuses with which error.
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <string>

#include "compile_definition.hpp"
#include "compiled/implicit_curve_geometry.hpp"
#include "geometry_checks.hpp"

using namespace footpoint;

namespace implicit_curve_geometry_test {

const ImplicitCurve& as_curve(const std::shared_ptr<const CompiledGeometry>& g) {
  return dynamic_cast<const ImplicitCurve&>(*g);
}

std::shared_ptr<const CompiledGeometry> planar(const std::string& f, double half = 2.0) {
  return test::compile_definition(GeometryType::implicit_curve, {{"equations[0]", f}},
                                  {{"x", {-half, half}}, {"y", {-half, half}}});
}

}  // namespace implicit_curve_geometry_test

TEST_CASE("implicit curve: evaluate_equations gives the written equations' values, gradients and Hessians") {
  // Planar: f = x^2/9 + y^2/4 - 1, grad f = (2x/9, y/2), Hessian diag(2/9, 1/2); no z.
  const auto ellipse = implicit_curve_geometry_test::planar("x^2/9+y^2/4-1", 4.0);
  for (const std::array<double, 2> x : {std::array<double, 2>{3.0, 0.0}, {1.0, -1.5}, {-5.0, 0.25}}) {
    CAPTURE(x[0]);
    EquationEvaluation e;
    REQUIRE(ellipse->evaluate_equations(x.data(), e));
    CHECK(e.equations == 1);
    CHECK(e.value[0] == doctest::Approx(x[0] * x[0] / 9 + x[1] * x[1] / 4 - 1).epsilon(1e-12));
    test::check_vec_close(e.gradient[0], {2 * x[0] / 9, x[1] / 2, 0.0});
    test::check_vec_close(e.hessian[0][0], {2.0 / 9, 0.0, 0.0});
    test::check_vec_close(e.hessian[0][1], {0.0, 0.5, 0.0});
    test::check_vec_close(e.hessian[0][2], {0.0, 0.0, 0.0});
    REQUIRE(e.normal_defined);
    const double length = std::hypot(2 * x[0] / 9, x[1] / 2);
    test::check_vec_close(e.normal, {2 * x[0] / 9 / length, x[1] / 2 / length, 0.0});
    CHECK(e.inside_box == (std::abs(x[0]) <= 4.0));
  }
  // Spatial: the sphere f1 = x^2 + y^2 + z^2 - 4 and the cylinder f2 = (x - 1)^2 + y^2 - 1
  // (Viviani's curve): gradients (2x, 2y, 2z) and (2(x - 1), 2y, 0), Hessians 2 I and
  // diag(2, 2, 0); a space curve has a plane of normals, none defined.
  const auto viviani = test::compile_definition(
      GeometryType::implicit_curve, {{"equations[0]", "x^2+y^2+z^2-4"}, {"equations[1]", "(x-1)^2+y^2-1"}},
      {{"x", {-3.0, 3.0}}, {"y", {-3.0, 3.0}}, {"z", {-3.0, 3.0}}});
  const std::array<double, 3> x{0.5, -1.25, 4.0};
  EquationEvaluation e;
  REQUIRE(viviani->evaluate_equations(x.data(), e));
  CHECK(e.equations == 2);
  CHECK(e.value[0] == doctest::Approx(0.25 + 1.5625 + 16 - 4).epsilon(1e-12));
  CHECK(e.value[1] == doctest::Approx(0.25 + 1.5625 - 1).epsilon(1e-12));
  test::check_vec_close(e.gradient[0], {1.0, -2.5, 8.0});
  test::check_vec_close(e.gradient[1], {-1.0, -2.5, 0.0});
  for (int r = 0; r < 3; ++r) {
    const auto k = static_cast<std::size_t>(r);
    test::check_vec_close(e.hessian[0][k], {r == 0 ? 2.0 : 0.0, r == 1 ? 2.0 : 0.0, r == 2 ? 2.0 : 0.0});
    test::check_vec_close(e.hessian[1][k], {r == 0 ? 2.0 : 0.0, r == 1 ? 2.0 : 0.0, 0.0});
  }
  CHECK_FALSE(e.normal_defined);
  CHECK_FALSE(e.inside_box);  // z = 4 is outside [-3, 3]
}

TEST_CASE("implicit curve: a repeated factor is written as given, its normal the square-free one's") {
  // (x^2 + y^2 - 1)^2 = 0 is the unit circle; its written gradient vanishes on it, the square-free
  // x^2 + y^2 - 1 has the normal (x, y).
  const auto g = implicit_curve_geometry_test::planar("(x^2+y^2-1)^2");
  const auto& curve = implicit_curve_geometry_test::as_curve(g);
  CHECK_FALSE(curve.written_equations().program().same_tape(curve.equations().program()));
  const std::array<double, 2> on{0.6, 0.8};
  EquationEvaluation e;
  REQUIRE(g->evaluate_equations(on.data(), e));
  CHECK(std::abs(e.value[0]) <= 1e-15);
  CHECK(norm(e.gradient[0]) <= 1e-14);
  REQUIRE(e.normal_defined);
  test::check_vec_close(e.normal, {0.6, 0.8, 0.0});
  const std::array<double, 2> off{2.0, 0.0};
  REQUIRE(g->evaluate_equations(off.data(), e));
  CHECK(e.value[0] == doctest::Approx(9.0).epsilon(1e-12));  // (4 - 1)^2, as written
  test::check_vec_close(e.gradient[0], {24.0, 0.0, 0.0});    // 2 (r^2 - 1) 2x
  // Projected: foot p / |p|, the outward normal, the distance signed + outside, - inside.
  for (const auto& [p, signed_distance] :
       {std::pair{std::array<double, 2>{1.2, 1.6}, 1.0}, std::pair{std::array<double, 2>{0.3, -0.4}, -0.5}}) {
    const ProjectionResult r = g->project(p.data(), "auto", {}).value();
    REQUIRE(r.summary.status == Status::converged);
    const double len = std::hypot(p[0], p[1]);
    CHECK(r.foot[0] == doctest::Approx(p[0] / len).epsilon(1e-12));
    CHECK(r.foot[1] == doctest::Approx(p[1] / len).epsilon(1e-12));
    REQUIRE(r.has_normal());
    CHECK(r.normal[0] == doctest::Approx(p[0] / len).epsilon(1e-12));
    CHECK(r.signed_distance == doctest::Approx(signed_distance).epsilon(1e-12));
  }
}

TEST_CASE("implicit curve: a product splits into its factor curves with points in the box") {
  // x y = 0: the two axes, meeting in a node.
  const auto cross = implicit_curve_geometry_test::planar("x*y", 1.0);
  CHECK(implicit_curve_geometry_test::as_curve(cross).factors().size() == 2);
  // From (0.5, 0.5) both axes are at 0.5: a tie of two feet.
  const std::array<double, 2> p{0.5, 0.5};
  const ProjectionResult r = cross->project(p.data(), "auto", {}).value();
  CHECK(r.distance == doctest::Approx(0.5).epsilon(1e-12));
  CHECK(r.summary.multiplicity.kind == Multiplicity::tied);
  CHECK(r.summary.multiplicity.count == 2);
  // At the node itself: a singular point, which has no normal.
  const std::array<double, 2> node{0.0, 0.0};
  const ProjectionResult at_node = cross->project(node.data(), "auto", {}).value();
  CHECK(at_node.distance <= 1e-15);
  CHECK(at_node.summary.location == Location::singular_point);
  CHECK_FALSE(at_node.has_normal());
  // Two circles, the one of radius 10 outside the box [-2, 2]^2: one factor curve, the unit circle.
  const auto far = implicit_curve_geometry_test::planar("(x^2+y^2-1)*(x^2+y^2-100)");
  const auto& curve = implicit_curve_geometry_test::as_curve(far);
  REQUIRE(curve.factors().size() == 1);
  const std::array<double, 2> q{1.5, 0.0};
  double value = 0.0;
  curve.factors()[0]->equations.program().values(q.data(), &value);
  CHECK(value == doctest::Approx(1.25).epsilon(1e-12));  // x^2 + y^2 - 1, the circle in the box
  // The compiled size holds the whole curve's discovery and every factor curve.
  std::size_t factors = 0;
  for (const DiscoveredCurve* f : implicit_curve_geometry_test::as_curve(cross).factors())
    factors += f->memory_bytes();
  CHECK(cross->memory_bytes() >=
        sizeof(ImplicitCurve) + implicit_curve_geometry_test::as_curve(cross).discovery().memory_bytes() +
            factors);
}

TEST_CASE(
    "implicit curve: the method tables by dimension, dispatch by name, certify on the papers' methods") {
  // Every row of the table, planar rows and spatial rows each a part of it in its order.
  const std::vector<MethodInfo>& every = methods_of(GeometryType::implicit_curve);
  CHECK(every.size() == 7);
  // The circle x^2 + y^2 = 4 in the plane z = 1: foot (2 q / |q|, 1), q = (p_x, p_y).
  const auto circle = test::compile_definition(GeometryType::implicit_curve,
                                               {{"equations[0]", "x^2+y^2-4"}, {"equations[1]", "z-1"}},
                                               {{"x", {-3.0, 3.0}}, {"y", {-3.0, 3.0}}, {"z", {-3.0, 3.0}}});
  const std::array<double, 3> p{1.0, 2.0, 1.5};
  const double q = std::hypot(1.0, 2.0);
  CHECK(circle->methods().size() + implicit_curve_geometry_test::planar("x^2+y^2-4")->methods().size() ==
        every.size() + 1);  // `auto` in both
  for (const MethodInfo& info : circle->methods()) {
    CAPTURE(info.name);
    Options options;
    options.certify = true;
    const ProjectionResult r = circle->project(p.data(), info.name, options).value();
    CHECK(r.summary.method == info.name);
    if (info.name == "steepest_descent") {
      // [Curve]'s Algorithm 1 alone lands on the curve, not at the foot: a point of the circle,
      // farther than the foot, reported not_orthogonal.
      CHECK(r.summary.status == Status::not_orthogonal);
      CHECK(std::hypot(r.foot[0], r.foot[1]) == doctest::Approx(2.0).epsilon(1e-12));
      CHECK(r.foot[2] == doctest::Approx(1.0).epsilon(1e-12));
      CHECK(r.distance > std::hypot(q - 2.0, 0.5));
      // Asked to certify, its answer is refuted, not improved: the foot is nearer.
      CHECK(r.summary.certificate.computed);
      CHECK_FALSE(r.summary.certificate.certified);
      continue;
    }
    REQUIRE(r.summary.status == Status::converged);
    CHECK(r.distance == doctest::Approx(std::hypot(q - 2.0, 0.5)).epsilon(1e-12));
    test::check_vec_close({r.foot[0], r.foot[1], r.foot[2]}, {2.0 / q, 4.0 / q, 1.0});
    CHECK(r.summary.certificate.computed);
    CHECK(r.summary.certificate.certified);
    CHECK_FALSE(r.has_normal());
  }
  const auto unknown = circle->method("tangent_foot");
  REQUIRE_FALSE(unknown);
  CHECK(unknown.error().message ==
        "unknown method 'tangent_foot' for a implicit_curve (auto, steepest_descent, foot_point_march, "
        "accelerated, complete, simplified)");
}

TEST_CASE("implicit curve: the definitions it refuses, with the field at fault") {
  using test::compile_error_code;
  std::string field;
  GeometryDefinition def{GeometryType::implicit_curve,
                         {{"equations[1]", "x^2+y^2-1"}},
                         {{"x", {-2.0, 2.0}}, {"y", {-2.0, 2.0}}},
                         {},
                         {}};
  CHECK(compile_error_code(def, &field) == "wrong_shape");
  CHECK(field == "equations[1]");
  def.formulas = {{"equations[0]", "x^2+y^2-1"}};
  def.periodic = {"t"};
  CHECK(compile_error_code(def, &field) == "unknown_parameter");
  CHECK(field == "periodic");
  def.periodic = {};
  def.domain.push_back({"z", {-1.0, 1.0}});  // a planar curve has no z
  CHECK(compile_error_code(def, &field) == "bad_domain");
  def.domain.pop_back();
  // No point in the box: a definition error, not a point's failure.
  def.formulas = {{"equations[0]", "x^2+y^2+1"}};
  CHECK(compile_error_code(def, &field) == "empty_curve");
  CHECK(field == "domain");
  def.formulas = {{"equations[0]", "(x-5)^2+y^2-1"}};
  CHECK(compile_error_code(def, &field) == "empty_curve");
  def.formulas = {{"equations[0]", "(x-1.5)^2+y^2-1"}};
  CHECK(compile_error_code(def).empty());
  test::check_limits_refuse(def);
}
