// What the closure checks of surfaces (surface_closure.hpp) and curves (curve_closure.hpp) share:
// where an edge is sampled, the rounding-level tolerance and the limit a declared periodic
// direction is held to (their headers say why these numbers).
#pragma once
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "geometry/vec.hpp"

namespace footpoint::closure_sampling {

// Samples inside an edge, and in all with its two ends.
inline constexpr int kInside = 32;
inline constexpr int kSamples = kInside + 2;
// The rounding-level tolerance in units of ε = 2^-52 of the quantities the rounding scales with.
inline constexpr double kRoundingUlps = 256.0;
// A declared periodic direction's edges may be this fraction of the geometry's size apart.
inline constexpr double kDeclaredGap = 1e-6;

// kSamples parameters of [lo, hi], increasing: lo, lo + (k + α)/kInside (hi - lo) for
// k = 0 .. kInside - 1 with α = (3 - √5)/2, hi.
std::vector<double> samples(double lo, double hi);

// 256 ε scale.
inline double rounding_tolerance(double scale) {
  return kRoundingUlps * std::numeric_limits<double>::epsilon() * scale;
}
// max(tolerance, 1e-6 size).
inline double declared_limit(double tolerance, double size) {
  return std::max(tolerance, kDeclaredGap * size);
}

// The bounding box and the largest coordinate magnitude of the points added.
struct Extent {
  Vec3 lo{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
          std::numeric_limits<double>::infinity()};
  Vec3 hi{-lo.x, -lo.y, -lo.z};
  double magnitude = 0.0;
  void add(Vec3 p) {
    for (int c = 0; c < 3; ++c) {
      lo[c] = std::min(lo[c], p[c]);
      hi[c] = std::max(hi[c], p[c]);
      magnitude = std::max(magnitude, std::abs(p[c]));
    }
  }
  // The diagonal of the box (0 when nothing was added).
  double size() const { return lo.x <= hi.x ? norm(hi - lo) : 0.0; }
};

// A rigorous upper bound of sqrt(a^2 + b^2 + c^2) for a, b, c >= 0 (scaled by the largest, so that
// no square underflows or overflows; 16 ulps up cover the roundings); exactly 0 for zeros.
inline double norm_bound(double a, double b, double c) {
  const double m = std::max({a, b, c});
  if (!(m > 0.0)) return m;  // 0, or NaN
  if (!std::isfinite(m)) return m;
  const double x = a / m, y = b / m, z = c / m;
  double r = m * std::sqrt(x * x + y * y + z * z);
  for (int i = 0; i < 16; ++i) r = std::nextafter(r, std::numeric_limits<double>::infinity());
  return r;
}

// A rigorous upper bound of |a - b| (a difference that rounds to 0 is exact).
inline double difference_bound(double a, double b) {
  const double d = std::abs(a - b);
  return d > 0.0 ? std::nextafter(d, std::numeric_limits<double>::infinity()) : d;
}

// x with three significant digits, for error messages.
std::string format(double x);

}  // namespace footpoint::closure_sampling
