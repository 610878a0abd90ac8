// A rigorous lower bound of the distance from a point p to the segment [a, b], in round to nearest.
//
// With w = p - a, v = b - a and z = p - b, the nearest point of the segment is
//  - a when ⟨w, v⟩ <= 0: the distance is |w|;
//  - b when ⟨z, v⟩ >= 0: the distance is |z|;
//  - else the foot of the perpendicular on the line: the distance is |w × v| / |v|, a lower bound
//    of the distance in every case (the segment lies on the line).
// Rounding. Each of w, v, z and of the sums of products below is computed in round to nearest, a
// few roundings per term; a computed sum of products is within 64 u (the sum of the magnitudes of
// its terms) of the exact one (N. J. Higham, Accuracy and Stability of Numerical Algorithms, 2nd
// ed., SIAM 2002, Section 3.1, γ_n with n <= 32; the same allowance as parametric/geometry/distance_bound).
// A case is taken only when its sign test holds beyond that allowance, each component of w × v is
// lowered in magnitude by its allowance, and the quotient, its square root and their own roundings
// are covered by a final factor 1 - 2^-44 and the square root rounded down.
#pragma once
#include <cmath>
#include <limits>

#include "formula/interval.hpp"
#include "geometry/vec.hpp"

namespace footpoint {

inline double segment_distance_lower_bound(Vec3 p, Vec3 a, Vec3 b) {
  constexpr double kAllowance = 64.0 * 0x1p-53;
  const Vec3 w = p - a, v = b - a, z = p - b;
  const auto lowered_sqrt = [](double square) {
    return square > 0x1p-960 && square <= std::numeric_limits<double>::max()
               ? formula::next_down(std::sqrt(square * (1.0 - 0x1p-44)))
               : 0.0;
  };
  const auto magnitude = [](Vec3 x, Vec3 y) {
    return std::fabs(x.x * y.x) + std::fabs(x.y * y.y) + std::fabs(x.z * y.z);
  };
  if (dot(w, v) + kAllowance * magnitude(w, v) <= 0.0) return lowered_sqrt(dot(w, w) * (1.0 - kAllowance));
  if (dot(z, v) - kAllowance * magnitude(z, v) >= 0.0) return lowered_sqrt(dot(z, z) * (1.0 - kAllowance));
  const auto component = [&](double wi, double vj, double wj, double vi) {
    const double c = std::fabs(wi * vj - wj * vi);
    const double allowance = kAllowance * (std::fabs(wi * vj) + std::fabs(wj * vi));
    return c > allowance ? c - allowance : 0.0;
  };
  const double c0 = component(w.y, v.z, w.z, v.y), c1 = component(w.z, v.x, w.x, v.z),
               c2 = component(w.x, v.y, w.y, v.x);
  const double vv = dot(v, v) * (1.0 + kAllowance);
  if (!(vv > 0.0)) return lowered_sqrt(dot(w, w) * (1.0 - kAllowance));  // a = b: a point
  return lowered_sqrt((c0 * c0 + c1 * c1 + c2 * c2) * (1.0 - kAllowance) / vv);
}

}  // namespace footpoint
