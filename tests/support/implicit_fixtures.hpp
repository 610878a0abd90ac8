// Shared by the unit tests of the implicit-curve kernels and solvers: equations compiled from
// formulas, curves compiled as posted definitions, and a circle whose foot points and
// differential geometry are known in closed form.
#pragma once
#include <array>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "compiled/compiled_geometry.hpp"
#include "formula/program.hpp"
#include "implicit/geometry/implicit_curve.hpp"

namespace footpoint::test {

// f1 = 0 and f2 = 0 in x, y, z.
inline ImplicitEquations spatial_equations(const std::string& f1, const std::string& f2) {
  return ImplicitEquations(
      formula::Program::compile({{"equations[0]", f1}, {"equations[1]", f2}}, {"x", "y", "z"}, {}), false);
}

// f = 0 in x, y (embedded as f1 = f, f2 = z).
inline ImplicitEquations planar_equations(const std::string& f) {
  return ImplicitEquations(formula::Program::compile({{"equations[0]", f}}, {"x", "y"}, {}), true);
}

// The implicit curve {equations = 0} (one in x, y or two in x, y, z) inside `box` (the ranges of
// x, y[, z]), compiled as a posted definition.
inline std::shared_ptr<const CompiledGeometry> implicit_curve(const std::vector<std::string>& equations,
                                                              const std::vector<std::array<double, 2>>& box) {
  GeometryDefinition def;
  def.type = GeometryType::implicit_curve;
  for (std::size_t i = 0; i < equations.size(); ++i)
    def.formulas.push_back({"equations[" + std::to_string(i) + "]", equations[i]});
  const char* names[] = {"x", "y", "z"};
  for (std::size_t k = 0; k < box.size(); ++k) def.domain.push_back({names[k], box[k]});
  return compile_geometry(def);
}

// The circle {x^2 + y^2 + z^2 = 4} ∩ {z = 1}: centre (0, 0, 1), radius sqrt(3), in the plane z = 1.
// With grad f1 = 2 X and grad f2 = e_z, its tangent is T = (2y, -2x, 0).
inline ImplicitEquations circle() { return spatial_equations("x^2+y^2+z^2-4", "z-1"); }
inline constexpr double kCircleRadius = 1.7320508075688772;  // sqrt(3)

// The foot point of p on that circle (p not on its axis).
inline Vec3 circle_foot(Vec3 p) {
  const double r = std::hypot(p.x, p.y);
  return {kCircleRadius * p.x / r, kCircleRadius * p.y / r, 1.0};
}

// The circle's point at angle a.
inline Vec3 circle_point(double a) { return {kCircleRadius * std::cos(a), kCircleRadius * std::sin(a), 1.0}; }

}  // namespace footpoint::test
