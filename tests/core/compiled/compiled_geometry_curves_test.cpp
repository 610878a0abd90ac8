// Compiling curve definitions: shapes, domains, formula errors, the method lists; and `auto`
// shared by several threads at once.
#include <doctest/doctest.h>

#include <cmath>
#include <thread>
#include <vector>

#include "compiled/implicit_curve_geometry.hpp"
#include "compiled/parametric_curve_geometry.hpp"

using namespace footpoint;

namespace {

std::string code_of(void (*f)()) {
  try {
    f();
  } catch (const GeometryError& e) {
    return e.code;
  }
  return "";
}

std::vector<std::string> names(const CompiledGeometry& g) {
  std::vector<std::string> n;
  for (const auto& m : g.methods()) n.emplace_back(m.name);
  return n;
}

}  // namespace

TEST_CASE("implicit curves: spatial (two equations) and planar (one)") {
  GeometryDefinition def;
  def.type = GeometryType::implicit_curve;
  def.formulas = {{"equations[0]", "x^2+y^2+z^2-4"}, {"equations[1]", "(x-1)^2+y^2-1"}};
  def.domain = {{"x", {-3.0, 3.0}}, {"y", {-3.0, 3.0}}, {"z", {-3.0, 3.0}}};
  const auto spatial = compile_implicit_curve(def, {});
  CHECK(spatial->point_dim() == 3);
  CHECK(spatial->num_params() == 0);
  CHECK(names(*spatial) == std::vector<std::string>{"auto", "steepest_descent", "foot_point_march",
                                                    "accelerated", "complete", "simplified"});
  CHECK(spatial->memory_bytes() > 0);

  def.formulas = {{"equations[0]", "x^2/9+y^2/4-1"}};
  def.domain = {{"x", {-4.0, 4.0}}, {"y", {-4.0, 4.0}}};
  const auto planar = compile_implicit_curve(def, {});
  CHECK(planar->point_dim() == 2);
  CHECK(names(*planar) == std::vector<std::string>{"auto", "tangent_foot"});
  // A spatial method on a planar curve: an error value naming the planar curve's methods.
  const auto unknown = planar->project(std::array<double, 2>{1.0, 1.0}.data(), "simplified", {});
  REQUIRE(!unknown.has_value());
  CHECK(unknown.error().message == "unknown method 'simplified' for a implicit_curve (auto, tangent_foot)");
  CHECK_THROWS_AS(unknown.value(), std::logic_error);
}

TEST_CASE("parametric curves: planar and spatial") {
  GeometryDefinition def;
  def.type = GeometryType::parametric_curve;
  def.formulas = {{"x", "cos(t)"}, {"y", "sin(t)"}};
  def.domain = {{"t", {0.0, 3.0}}};
  const auto planar = compile_parametric_curve(def, {});
  CHECK(planar->point_dim() == 2);
  CHECK(planar->num_params() == 1);
  CHECK(names(*planar) == std::vector<std::string>{"auto", "newton", "curvature_circle"});
  def.formulas.push_back({"z", "t"});
  CHECK(compile_parametric_curve(def, {})->point_dim() == 3);
}

TEST_CASE("curve definitions that do not compile") {
  CHECK(code_of([] {
          GeometryDefinition def;
          def.type = GeometryType::implicit_curve;
          def.formulas = {{"equations[0]", "x"}, {"equations[1]", "y"}, {"equations[2]", "z"}};
          def.domain = {{"x", {-1.0, 1.0}}, {"y", {-1.0, 1.0}}, {"z", {-1.0, 1.0}}};
          compile_implicit_curve(def, {});
        }) == "wrong_shape");
  CHECK(code_of([] {
          GeometryDefinition def;
          def.type = GeometryType::implicit_curve;
          def.formulas = {{"equations[0]", "x^2+y^2-1"}};
          def.domain = {{"x", {-1.0, 1.0}}, {"y", {1.0, -1.0}}};
          compile_implicit_curve(def, {});
        }) == "bad_domain");
  CHECK(code_of([] {
          GeometryDefinition def;
          def.type = GeometryType::implicit_curve;
          def.formulas = {{"equations[0]", "x^2+y^2+z-1"}};  // z is not a variable of a planar curve
          def.domain = {{"x", {-1.0, 1.0}}, {"y", {-1.0, 1.0}}};
          compile_implicit_curve(def, {});
        }) != "");
  CHECK(code_of([] {
          GeometryDefinition def;
          def.type = GeometryType::parametric_curve;
          def.formulas = {{"x", "t"}};
          def.domain = {{"t", {0.0, 1.0}}};
          compile_parametric_curve(def, {});
        }) == "wrong_shape");
  CHECK(code_of([] {
          GeometryDefinition def;
          def.type = GeometryType::parametric_curve;
          def.formulas = {{"x", "t"}, {"y", "sin(t"}};
          def.domain = {{"t", {0.0, 1.0}}};
          compile_parametric_curve(def, {});
        }) != "");
}

TEST_CASE("auto is safe to call from several threads on one compiled curve") {
  GeometryDefinition def;
  def.type = GeometryType::implicit_curve;
  def.formulas = {{"equations[0]", "x^2/9+y^2/16+z^2/9+4*x*y-1"}, {"equations[1]", "x^2+y^2+x-4*z"}};
  def.domain = {{"x", {-300.0, 300.0}}, {"y", {-300.0, 300.0}}, {"z", {-300.0, 300.0}}};
  const auto g = compile_implicit_curve(def, {});
  constexpr int kPoints = 400;
  std::vector<double> points(std::size_t{3} * kPoints);
  for (int i = 0; i < 3 * kPoints; ++i) points[static_cast<std::size_t>(i)] = 300.0 * std::sin(1.7 * i + 0.3);
  std::vector<double> serial(kPoints);
  for (int i = 0; i < kPoints; ++i)
    serial[static_cast<std::size_t>(i)] =
        g->project(&points[3 * static_cast<std::size_t>(i)], "auto", {}).value().distance;
  std::vector<double> parallel(kPoints);
  std::vector<std::thread> threads;
  threads.reserve(4);
  for (int t = 0; t < 4; ++t)
    threads.emplace_back([&, t] {
      for (int i = t; i < kPoints; i += 4)
        parallel[static_cast<std::size_t>(i)] =
            g->project(&points[3 * static_cast<std::size_t>(i)], "auto", {}).value().distance;
    });
  for (auto& th : threads) th.join();
  CHECK(parallel == serial);
}
