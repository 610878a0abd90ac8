// Midpoint-radius dot products over intervals ([Rump99]; formula/ball.hpp): each interval
// [lo, hi] is taken as the ball about c = fl(lo/2 + hi/2) with a radius that bounds c - lo and
// hi - c; a dot product of balls is a centre computed in floating point plus one radius that
// covers the propagated radii and the rounding of the centre. A few times cheaper than interval
// products rounded outwards one by one (formula/interval.hpp), and as tight where the intervals
// are narrow against their midpoints. Used by Krawczyk's test (geometry/krawczyk.hpp) and the
// curve certificates' gradients of F (implicit/solvers/implicit_curve_certificate).
//
// The allowance: a dot product of at most 15 terms (and roundings) computed in round to nearest
// is within γ_15 / (1 - γ_15) < 15.1 u of the exact one, relative to the computed sum S of its
// terms' magnitudes, plus 15 η for underflows; a computed radius sum R likewise understates its
// exact value by at most 15.1 u R + 15 η (N. J. Higham, Accuracy and Stability of Numerical
// Algorithms, 2nd ed., SIAM 2002, Section 3.1). So
//   radius = fl(fl(R + fl(16 u S)) (1 + 32 u) + 2^-900)
// bounds the exact radius plus the centre's error: its own four roundings lose less than the
// margins (16 against 15.1, 32 against 15.1, 2^-900 against 30 η). The floor is a normal number,
// so products with it stay out of the subnormal range (slow on some processors). Where every term
// has an exact zero factor the sum is exactly 0 and needs no floor: an exact coordinate (the plane
// z = 0 of a planar curve) stays exact.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>

#include "formula/interval.hpp"

namespace footpoint::midrad {

inline constexpr double kU = 0x1p-53;

struct Ball {
  double c = 0.0, r = 0.0;
  bool nonzero() const { return c != 0.0 || r != 0.0; }
};

// The ball of an interval: the two differences are one rounding each (exact where subnormal); a
// NaN difference comes with a centre that is not finite, which decides nothing.
inline Ball of(const formula::Interval& a) {
  const double c = formula::interval::mid(a);
  return {c, std::max(c - a.lo, a.hi - c) * (1.0 + 4.0 * kU)};
}

// The radius of a dot product of at most 15 terms with propagated radius sum r and magnitude sum
// s, computed in round to nearest (above); 0 where every term has an exact zero factor.
inline double radius(double r, double s, bool terms) {
  return terms ? (r + s * (16.0 * kU)) * (1.0 + 32.0 * kU) + 0x1p-900 : 0.0;
}

// An enclosure of Σ_i a_i b_i - t for every a_i, b_i, t in the intervals (N <= 7: at most 15
// roundings), its ends one rounding outwards from the ball's; exactly 0 where every term has an
// exact zero factor and t = 0; the whole line where anything is not finite.
template <std::size_t N>
formula::Interval dot_minus(const std::array<formula::Interval, N>& a,
                            const std::array<formula::Interval, N>& b, const formula::Interval& t) {
  static_assert(N <= 7, "the rounding allowance counts at most 15 terms");
  const Ball tb = of(t);
  double c = -tb.c, s = std::abs(tb.c), r = tb.r;
  bool terms = tb.nonzero();
  for (std::size_t i = 0; i < N; ++i) {
    const Ball x = of(a[i]), y = of(b[i]);
    c += x.c * y.c;
    s += std::abs(x.c * y.c);
    r += std::abs(x.c) * y.r + x.r * (std::abs(y.c) + y.r);
    terms = terms || (x.nonzero() && y.nonzero());
  }
  if (!terms) return {0.0, 0.0};
  const double rad = radius(r, s, true);
  if (!(std::isfinite(c) && std::isfinite(rad)))
    return {-std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  return {formula::next_down(c - rad), formula::next_up(c + rad)};
}

}  // namespace footpoint::midrad
