// Nearest points of surfaces known in closed form, independently of the code, shared by the tests
// of parametric and implicit surfaces alike:
//  - the ellipsoid x^2/a^2 + y^2/b^2 + z^2/c^2 = 1: the foot of p (no coordinate 0) is
//    x_i = e_i^2 p_i / (t + e_i^2), t the unique root in (-min e_i^2, inf) of the secular equation
//    F(t) = sum (e_i p_i / (t + e_i^2))^2 - 1, which decreases from +inf to -1 there (D. Eberly,
//    "Distance from a Point to an Ellipse, an Ellipsoid, or a Hyperellipsoid", Geometric Tools
//    2013, Sec. 3); found here by bisection;
//  - the torus (hypot(x, y) - R)^2 + z^2 = r^2 (core radius R, tube radius r, about the z axis):
//    the foot of p off the core circle and the axis is the point of the tube circle of p's
//    meridian nearest to p, c + r (p - c) / |p - c| with c = R (cos phi, sin phi, 0).
#pragma once
#include <algorithm>
#include <cmath>

#include "geometry/vec.hpp"

namespace footpoint::test {

// The foot of p on the ellipsoid with semi-axes e (every p_i != 0), by bisection on the secular
// equation to the last bit of t.
inline Vec3 ellipsoid_foot(Vec3 e, Vec3 p) {
  const double least = std::min({e.x * e.x, e.y * e.y, e.z * e.z});
  auto secular = [&](double t) {
    double s = -1.0;
    for (int i = 0; i < 3; ++i) {
      const double q = e[i] * p[i] / (t + e[i] * e[i]);
      s += q * q;
    }
    return s;
  };
  double lo = -least, hi = 1.0;
  while (secular(hi) > 0.0) hi *= 2.0;
  for (int n = 0; n < 2000; ++n) {
    const double mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi) break;
    (secular(mid) > 0.0 ? lo : hi) = mid;
  }
  const double t = 0.5 * (lo + hi);
  Vec3 x;
  for (int i = 0; i < 3; ++i) x[i] = e[i] * e[i] * p[i] / (t + e[i] * e[i]);
  return x;
}

// The foot of p on the torus of radii R (core) and r (tube) about the z axis.
inline Vec3 torus_foot(double R, double r, Vec3 p) {
  const double rho = std::hypot(p.x, p.y);
  const double dr = rho - R, d = std::hypot(dr, p.z);
  const double radial = R + r * dr / d;
  return {radial * p.x / rho, radial * p.y / rho, r * p.z / d};
}

// The distance from p to that torus, negative inside the tube, and its absolute value.
inline double torus_signed_distance(double R, double r, Vec3 p) {
  return std::hypot(std::hypot(p.x, p.y) - R, p.z) - r;
}
inline double torus_distance(double R, double r, Vec3 p) { return std::fabs(torus_signed_distance(R, r, p)); }

}  // namespace footpoint::test
