// Compiling a geometry stops at the request's deadline with a clear error instead of holding a
// thread (found by the reliability work: a wild parametric curve took 7.5 s to sample).
#include <doctest/doctest.h>

#include <chrono>

#include "compiled/compiled_geometry.hpp"

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
