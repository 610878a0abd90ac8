// Compiling a geometry stops at the request's deadline with a clear error instead of holding a
// thread (found by the reliability work: a wild parametric curve took 7.5 s to sample).
#include <doctest/doctest.h>

#include <array>
#include <chrono>
#include <string>
#include <utility>
#include <vector>

#include "compiled/compiled_geometry.hpp"
#include "geometry/geometry_error.hpp"

using namespace footpoint;

TEST_CASE("a geometry whose search structure cannot be built in time fails with compile_timeout") {
  std::string x;
  for (int k = 1; k <= 119 && x.size() < 3900; ++k) {
    if (k > 1) x.push_back('+');
    x.append("sin(").append(std::to_string(k)).append("*t+").append(std::to_string(k % 5)).append("*t)");
  }
  GeometryDefinition def;
  def.type = GeometryType::parametric_curve;
  def.formulas = {{"x", x}, {"y", "t"}};
  def.domain = {{"t", {-1000.0, 1000.0}}};
  formula::CompileLimits limits;
  const auto start = std::chrono::steady_clock::now();
  limits.deadline = start + std::chrono::milliseconds(200);
  std::string code;
  try {
    compile_geometry(def, limits);
  } catch (const GeometryError& e) {
    code = e.code;
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  CHECK(code == "compile_timeout");
  CHECK(seconds < 2.0);  // generous: the budget is checked every few dozen loop steps

  // The same definition compiles without a deadline on a small domain.
  def.domain = {{"t", {-1.0, 1.0}}};
  limits.deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  CHECK(compile_geometry(def, limits)->point_dim() == 2);
}

TEST_CASE("a search structure growing past max_geometry_bytes is stopped while it is built") {
  // exp(500 t) on [0, 1]: the sampling runs to its million samples (143 MB compiled, issue 38).
  const GeometryDefinition wild = GeometryDefinition{
      GeometryType::parametric_curve, {{"x", "exp(t*500)"}, {"y", "t"}}, {{"t", {0.0, 1.0}}}, {}, {}};
  formula::CompileLimits limits;
  limits.max_geometry_bytes = std::size_t{8} << 20;
  std::string message;
  try {
    compile_geometry(wild, limits);
    FAIL("compiled past the bound");
  } catch (const GeometryError& e) {
    CHECK(e.code == "geometry_too_large");
    message = e.what();
  }
  // Stopped at the first sample past the bound: the message names the bytes reached, above the
  // bound by less than one sample's share.
  const auto at = message.find("reached ");
  REQUIRE(at != std::string::npos);
  const std::size_t reached = std::stoull(message.substr(at + 8));
  CHECK(reached > limits.max_geometry_bytes);
  CHECK(reached < limits.max_geometry_bytes + 4096);
  CHECK(message.find("over the limit of 8388608") != std::string::npos);
}

TEST_CASE("each compile has a budget of its own: two compiles near the bound both pass") {
  // The sampled curve below grows to two thirds of the bound; were the counts of two compiles
  // added (a budget shared between them), the second would be stopped.
  const GeometryDefinition curve = GeometryDefinition{
      GeometryType::parametric_curve, {{"x", "exp(t*50)"}, {"y", "t"}}, {{"t", {0.0, 1.0}}}, {}, {}};
  formula::CompileLimits limits;
  limits.max_geometry_bytes = compile_geometry(curve)->memory_bytes() * 3 / 2;
  CHECK(compile_geometry(curve, limits)->memory_bytes() <= limits.max_geometry_bytes);
  CHECK(compile_geometry(curve, limits)->memory_bytes() <= limits.max_geometry_bytes);
}

TEST_CASE(
    "what the compile counts is a lower bound of memory_bytes: a geometry at its size is never stopped") {
  const std::vector<GeometryDefinition> cases = {
      GeometryDefinition{GeometryType::parametric_curve,
                         {{"x", "cos(t)"}, {"y", "sin(3*t)"}, {"z", "t"}},
                         {{"t", {0.0, 20.0}}},
                         {},
                         {}},
      GeometryDefinition{
          GeometryType::parametric_curve, {{"x", "exp(t*50)"}, {"y", "t"}}, {{"t", {0.0, 1.0}}}, {}, {}},
      GeometryDefinition{GeometryType::parametric_surface,
                         {{"x", "u+v"}, {"y", "sin(u)+2*cos(v)"}, {"z", "sin(u+v)"}},
                         {{"u", {-5.0, 5.0}}, {"v", {-5.0, 5.0}}},
                         {},
                         {}},
      GeometryDefinition{GeometryType::implicit_curve,
                         {{"equations[0]", "x^4+y^4-1"}},
                         {{"x", {-2.0, 2.0}}, {"y", {-2.0, 2.0}}},
                         {},
                         {}},
      GeometryDefinition{GeometryType::implicit_surface,
                         {{"equation", "x^2+y^2+z^2-1"}},
                         {{"x", {-2.0, 2.0}}, {"y", {-2.0, 2.0}}, {"z", {-2.0, 2.0}}},
                         {},
                         {}},
  };
  for (const auto& def : cases) {
    CAPTURE(def.canonical());
    const std::size_t bytes = compile_geometry(def)->memory_bytes();
    formula::CompileLimits limits;
    limits.max_geometry_bytes = bytes;
    CHECK(compile_geometry(def, limits)->memory_bytes() == bytes);
  }
}
