// sin x and cos x together, in one reduction of x, within 1 ulp of the exact values
// (tests/core/formula/sin_cos_test.cpp measures the error against long double); the values and jets of
// every sin and cos node use it. Internal to core/formula.
//
// x = k π/2 + r, |r| <= π/4 (about): Cody and Waite's reduction with π/2 = P1 + P2 + P3, where P1
// and P2 have 33 significant bits, so that k P1 and k P2 are exact for |k| < 2^20 and
// x - k P1 is exact (x and k P1 agree in their leading bits); the rounding of r is then that of
// the last two subtractions, relative to r itself. Then Taylor series on |r| <= π/4:
//   sin r = r + r^3 Σ_{j>=0} (-1)^(j+1) r^(2j) / (2j+3)!   (through r^17: the next term is < 1e-19 r)
//   cos r = 1 - r^2/2 + r^4 Σ_{j>=0} (-1)^j r^(2j) / (2j+4)!  (through r^18)
// and the quadrant k mod 4 picks the signs. |x| >= 2^20 and non-finite x go to glibc.
#pragma once
#include <bit>
#include <cmath>
#include <cstdint>

namespace footpoint::formula {

// The rounding error of d = a - b, exactly (Knuth's two-sum).
inline double two_diff_error(double a, double b, double d) {
  const double b_virtual = a - d;
  return (a - (d + b_virtual)) + (b_virtual - b);
}

// The rounding error of p = a b, exactly, without a fused multiply-add (Dekker's product: a and b
// split into halves of 26 bits, whose products are exact).
inline double product_error(double a, double b, double p) {
  constexpr double kSplit = 0x1p27 + 1.0;
  const double ta = kSplit * a, a_hi = ta - (ta - a), a_lo = a - a_hi;
  const double tb = kSplit * b, b_hi = tb - (tb - b), b_lo = b - b_hi;
  return ((a_hi * b_hi - p) + a_hi * b_lo + a_lo * b_hi) + a_lo * b_lo;
}

inline void sin_cos(double x, double* sin_x, double* cos_x) {
  const double ax = std::fabs(x);
  if (ax < 0x1p-27) {  // x^2 / 6 < 2^-56: sin x rounds to x (-0 kept), cos x to 1
    *sin_x = x, *cos_x = 1.0;
    return;
  }
  if (!(ax < 0x1p20)) {
    ::sincos(x, sin_x, cos_x);
    return;
  }
  constexpr double kTwoOverPi = 0x1.45f306dc9c883p-1;
  constexpr double kP1 = 0x1.921fb544p+0, kP2 = 0x1.0b4611a6p-34, kP3 = 0x1.3198a2e037073p-69;
  // k = x 2/π rounded to an integer: adding 1.5 2^52 leaves k in the low bits of the sum
  constexpr double kShift = 0x1.8p52;
  const double shifted = x * kTwoOverPi + kShift;
  const double k = shifted - kShift;
  const auto quadrant = static_cast<unsigned>(std::bit_cast<std::uint64_t>(shifted)) & 3u;
  // r = r_hi + r_lo: the two roundings of the reduction kept (Knuth's two-sum), so that the
  // result's error is that of the series' evaluation alone
  const double a = x - k * kP1, b = k * kP2, c3 = k * kP3;
  const double r1 = a - b;
  const double r1_lo = two_diff_error(a, b, r1);
  const double r = r1 - c3;
  const double r_lo = two_diff_error(r1, c3, r) + r1_lo;
  // z = r^2 exactly as z + z_lo (Dekker's product)
  const double z = r * r;
  const double z_lo = product_error(r, r, z);
  const double sin_tail =
      r * z *
      (-1.0 / 6 +
       z * (1.0 / 120 +
            z * (-1.0 / 5040 +
                 z * (1.0 / 362880 +
                      z * (-1.0 / 39916800 + z * (1.0 / 6227020800 + z * (-1.0 / 1307674368000 +
                                                                          z * (1.0 / 355687428096000))))))));
  const double cos_tail =
      z * z *
      (1.0 / 24 +
       z * (-1.0 / 720 +
            z * (1.0 / 40320 +
                 z * (-1.0 / 3628800 + z * (1.0 / 479001600 + z * (-1.0 / 87178291200 +
                                                                   z * (1.0 / 20922789888000 +
                                                                        z * (-1.0 / 6402373705728000))))))));
  // sin(r + r_lo) = sin r + r_lo cos r: r_lo (1 - z/2) to first order is r_lo within 2^-54
  const double s = r + (r_lo + sin_tail);
  // cos(r + r_lo) = cos r - r_lo sin r; 1 - z/2 as w plus its rounding error
  const double hz = 0.5 * z, w = 1.0 - hz;
  const double c = w + ((((1.0 - w) - hz) - 0.5 * z_lo) + (cos_tail - r * r_lo));
  switch (quadrant) {
    case 0:
      *sin_x = s, *cos_x = c;
      break;
    case 1:
      *sin_x = c, *cos_x = -s;
      break;
    case 2:
      *sin_x = -s, *cos_x = -c;
      break;
    default:
      *sin_x = -c, *cos_x = s;
      break;
  }
}

}  // namespace footpoint::formula
