// Closed intervals [lo, hi] with outward rounding, for rigorous range bounds of a formula over a
// box (exclusion tests: a box where 0 is outside the range of f cannot contain a point of f = 0;
// a box whose image is farther than a known distance cannot hold the nearest point).
//
// The rounding model every enclosure here relies on: IEEE 754 binary64 arithmetic in round to
// nearest (the default; nothing in the process changes it), without extended precision (x86-64
// SSE2). Then +, -, x, / and sqrt are correctly rounded: the exact result lies within half an ulp
// of the computed one, and one step to the neighbouring double outwards (next_down / next_up)
// encloses it - also in the subnormal range, where the rounding error is at most half the
// smallest subnormal. A fused multiply-add would only shorten those errors. Elementary functions
// from the C library are not correctly rounded; their margin is explained where they are used
// (formula/program.cpp).
#pragma once
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

namespace footpoint::formula {

struct Interval {
  double lo = 0.0;
  double hi = 0.0;
  // Some points of the box lie outside the expression's domain (its value is NaN there, e.g. sqrt
  // of a negative number). [lo, hi] encloses the values at the other points. Operations that turn a
  // NaN into a number (comparisons, min/max, sign, ?:) widen their result to cover that case.
  bool partial = false;
  // True when the interval certainly does not contain zero (NaN bounds never exclude).
  bool excludes_zero() const { return lo > 0.0 || hi < 0.0; }
};

// The next double above x (the successor), exactly: next_up(+inf) = +inf, next_up(-inf) is the
// most negative double (a value rounded to -inf by overflow is above -inf), NaN stays NaN.
// Below +inf the bit pattern of x, read as a signed integer b, is one step from its successor's:
// b + 1 for x >= +0, b - 1 for x < 0 (the magnitude shrinks), i.e. b + 1 + 2 (b >> 63); x + 0
// turns -0 into +0, whose successor is the least subnormal. No branch on the sign: products of
// intervals round bounds of either sign, which a predictor cannot guess.
inline double next_up(double x) {
  if (!(x < std::numeric_limits<double>::infinity())) return x;  // +inf, NaN
  const auto bits = std::bit_cast<std::int64_t>(x + 0.0);
  return std::bit_cast<double>(bits + 1 + 2 * (bits >> 63));
}
// The next double below x (the predecessor), exactly.
inline double next_down(double x) { return -next_up(-x); }
// n steps up or down: n ulps of x (of the doubles passed), at least n u |x| where u = 2^-53.
inline double up(double x, int n) {
  for (int i = 0; i < n; ++i) x = next_up(x);
  return x;
}
inline double down(double x, int n) {
  for (int i = 0; i < n; ++i) x = next_down(x);
  return x;
}

namespace interval {

constexpr double kInf = std::numeric_limits<double>::infinity();

inline Interval point(double x) { return {x, x}; }
inline Interval entire() { return {-kInf, kInf}; }
// [lo, hi] computed by one correctly rounded operation each: one step outwards.
inline Interval outward(double lo, double hi) { return {next_down(lo), next_up(hi)}; }
inline bool is_empty(const Interval& a) { return std::isnan(a.lo) || std::isnan(a.hi); }

inline bool is_zero(const Interval& a) { return a.lo == 0.0 && a.hi == 0.0; }
// Sums and products with an exact zero are exact (the derivatives of linear parts are zeros).
inline Interval add(const Interval& a, const Interval& b) {
  if (is_zero(b)) return {a.lo, a.hi};
  if (is_zero(a)) return {b.lo, b.hi};
  return outward(a.lo + b.lo, a.hi + b.hi);
}
inline Interval neg(const Interval& a) { return {-a.hi, -a.lo}; }
inline Interval sub(const Interval& a, const Interval& b) {
  if (is_zero(b)) return {a.lo, a.hi};
  if (is_zero(a)) return neg(b);
  return outward(a.lo - b.hi, a.hi - b.lo);
}
inline Interval hull(const Interval& a, const Interval& b) {
  return {std::min(a.lo, b.lo), std::max(a.hi, b.hi)};
}
// The product; 0 x inf counts as 0 (the bound of a product with an exact zero factor: the
// convention of IEEE 1788-2015 for interval bounds).
inline Interval mul(const Interval& a, const Interval& b) {
  if (is_zero(a) || is_zero(b)) return {0.0, 0.0};
  auto prod = [](double x, double y) {
    const double p = x * y;
    return std::isnan(p) ? 0.0 : p;
  };
  const double p0 = prod(a.lo, b.lo), p1 = prod(a.lo, b.hi), p2 = prod(a.hi, b.lo), p3 = prod(a.hi, b.hi);
  return outward(std::min(std::min(p0, p1), std::min(p2, p3)), std::max(std::max(p0, p1), std::max(p2, p3)));
}
// The product with a point a: the bounds of mul(point(a), b), from two products instead of four.
inline Interval mul(double a, const Interval& b) {
  if (a == 0.0 || is_zero(b)) return {0.0, 0.0};
  auto prod = [a](double y) {
    const double p = a * y;
    return std::isnan(p) ? 0.0 : p;
  };
  const double p0 = prod(b.lo), p1 = prod(b.hi);
  return a > 0.0 ? outward(p0, p1) : outward(p1, p0);
}
// a times a (tighter than mul(a, a): never negative).
inline Interval sqr(const Interval& a) {
  const double l = std::abs(a.lo), h = std::abs(a.hi);
  if (a.lo <= 0.0 && a.hi >= 0.0) return {0.0, next_up(std::max(l, h) * std::max(l, h))};
  const double m = std::min(l, h), M = std::max(l, h);
  return {std::max(0.0, next_down(m * m)), next_up(M * M)};
}
// 1/a; the whole line when a contains 0.
inline Interval recip(const Interval& a) {
  if (a.lo <= 0.0 && a.hi >= 0.0) return entire();
  return outward(1.0 / a.hi, 1.0 / a.lo);
}
inline Interval div(const Interval& a, const Interval& b) {
  if (b.lo <= 0.0 && b.hi >= 0.0) return entire();
  const double p0 = a.lo / b.lo, p1 = a.lo / b.hi, p2 = a.hi / b.lo, p3 = a.hi / b.hi;
  auto fix = [](double x) { return std::isnan(x) ? 0.0 : x; };  // inf / inf: a bound at infinity
  return outward(std::min(std::min(fix(p0), fix(p1)), std::min(fix(p2), fix(p3))),
                 std::max(std::max(fix(p0), fix(p1)), std::max(fix(p2), fix(p3))));
}
// Largest and smallest absolute value, midpoint and radius (the radius rounded up, so that
// [mid - rad, mid + rad] holds the interval).
inline double mag(const Interval& a) { return std::max(std::abs(a.lo), std::abs(a.hi)); }
inline double mig(const Interval& a) {
  if (a.lo <= 0.0 && a.hi >= 0.0) return 0.0;
  return std::min(std::abs(a.lo), std::abs(a.hi));
}
inline double mid(const Interval& a) {
  const double m = 0.5 * a.lo + 0.5 * a.hi;  // no overflow; exact halving unless subnormal
  return std::isfinite(m) ? m : (a.lo == -a.hi ? 0.0 : m);
}
inline double rad(const Interval& a) {
  const double m = mid(a);
  return next_up(std::max(m - a.lo, a.hi - m));
}
inline Interval intersect(const Interval& a, const Interval& b) {
  return {std::max(a.lo, b.lo), std::min(a.hi, b.hi)};
}

}  // namespace interval

}  // namespace footpoint::formula
