// Shared by the tests of the implicit-curve seeding and solvers: curves with a known
// parametrisation c(t) (so their points are known independently of the implicit equations), the
// brute-force nearest point of p on them (a dense sampling of t refined by Newton on
// g(t) = <c(t) - p, c'(t)>, the derivative of |c(t) - p|^2 / 2), and the certified subdivision of
// an implicit curve's box built as discovery builds it.
#pragma once
#include <cmath>
#include <functional>
#include <numbers>

#include "geometry/compile_budget.hpp"
#include "implicit/seeding/curve_cells.hpp"
#include "implicit/seeding/curve_enclosure.hpp"

namespace footpoint::test {

struct ParamCurve {
  std::function<Vec3(double)> c, dc, ddc;  // the point and its first two derivatives in t
  double t0 = 0.0, t1 = 0.0;               // one period (closed) or the whole range
};

// The ellipse x^2 / a^2 + y^2 / b^2 = 1, z = z0: (a cos t, b sin t, z0).
inline ParamCurve ellipse_curve(double a, double b, double z0 = 0.0) {
  return {[=](double t) {
            return Vec3{a * std::cos(t), b * std::sin(t), z0};
          },
          [=](double t) {
            return Vec3{-a * std::sin(t), b * std::cos(t), 0.0};
          },
          [=](double t) {
            return Vec3{-a * std::cos(t), -b * std::sin(t), 0.0};
          },
          0.0, 2.0 * std::numbers::pi};
}

// Viviani's curve {x^2 + y^2 + z^2 = 4} ∩ {(x - 1)^2 + y^2 = 1}: (1 + cos t, sin t, 2 sin(t/2)),
// t in [0, 4 pi) (x^2 + y^2 = 2 + 2 cos t, z^2 = 2 - 2 cos t). Its double point (2, 0, 0) is
// t = 0 and t = 2 pi, where the sphere and the cylinder touch.
inline ParamCurve viviani_curve() {
  return {[](double t) {
            return Vec3{1.0 + std::cos(t), std::sin(t), 2.0 * std::sin(0.5 * t)};
          },
          [](double t) {
            return Vec3{-std::sin(t), std::cos(t), std::cos(0.5 * t)};
          },
          [](double t) {
            return Vec3{-std::cos(t), -std::sin(t), -0.5 * std::sin(0.5 * t)};
          },
          0.0, 4.0 * std::numbers::pi};
}

struct CurveNearest {
  double t = 0.0;
  Vec3 x;
  double distance = 0.0;
};

// The nearest point of p on the curve: the least of n samples, refined by Newton on
// g(t) = <c - p, c'>, g' = |c'|^2 + <c - p, c''>, kept only where it lowers the distance.
inline CurveNearest nearest_on(const ParamCurve& curve, Vec3 p, int n = 20000) {
  CurveNearest best{curve.t0, curve.c(curve.t0), norm(p - curve.c(curve.t0))};
  for (int i = 1; i < n; ++i) {
    const double t = curve.t0 + (curve.t1 - curve.t0) * i / n;
    const double d = norm(p - curve.c(t));
    if (d < best.distance) best = {t, curve.c(t), d};
  }
  double t = best.t;
  for (int k = 0; k < 50; ++k) {
    const Vec3 r = curve.c(t) - p, d1 = curve.dc(t);
    const double g = dot(r, d1), dg = dot(d1, d1) + dot(r, curve.ddc(t));
    if (!(dg > 0.0)) break;
    const double next = t - g / dg;
    if (next == t) break;
    t = next;
  }
  if (norm(p - curve.c(t)) <= best.distance) best = {t, curve.c(t), norm(p - curve.c(t))};
  return best;
}

// The certified subdivision of the curve's box (implicit/seeding/curve_cells) over its enclosure, as
// discovery computes them.
inline CurveCells subdivided_cells(const ImplicitEquations& equations, const Box3& box,
                                   const SubdivisionSettings& settings = {}) {
  CompileBudget budget;
  const CurveEnclosure enclosure = enclose_curve(equations, box, budget);
  return subdivide_curve(equations, enclosure, budget, settings);
}

}  // namespace footpoint::test
