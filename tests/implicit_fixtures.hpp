// Shared by the unit tests of the implicit-curve kernels and solvers: equations compiled from
// formulas, and a circle whose foot points and differential geometry are known in closed form.
#pragma once
#include <cmath>
#include <string>

#include "formula/program.hpp"
#include "geometry/implicit_curve.hpp"

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
