// Balls (midpoint-radius intervals) and first-order ball jets: rigorous enclosures of a formula's
// value and gradient at one point, at a few times the cost of the point jet (Program::ball_jets1).
// Where interval arithmetic (interval.hpp) encloses a function over a box, a ball jet encloses
// the exact values at a point whose evaluation in floating point rounds: the certificate of an
// answer (projection/certificate.hpp) needs f(q) and ∇f(q) at the foot point q to the last few ulps,
// with a proof, for every point projected.
//
// The rounding model is that of interval.hpp (IEEE 754 binary64, round to nearest, no extended
// precision). A ball {m, r} stands for every real x with |x - m| <= r. For a correctly rounded
// operation with computed result c, the exact result lies within u |c| + η of c, u = 2^-53 the
// unit roundoff and η = 2^-1022 the smallest normal number, which bounds the underflow of products
// and quotients (at most half the smallest subnormal, 2^-1075). The smallest subnormal would do as
// well, but it would make the radius of every exact value a subnormal number (a zero derivative:
// rounding(0) = η), and an x86 core takes a microcode assist, some hundred cycles, for each
// operation with a subnormal operand;
// the propagated part is the classical midpoint-radius bound (S. M. Rump, "Fast and parallel
// interval arithmetic", BIT 39 (1999) 534-554, Sections 2-3):
//   {a} ± {b}:  m = fl(ma ± mb),   r = ra + rb + u|m| + η
//   {a} × {b}:  m = fl(ma mb),     r = |ma| rb + ra |mb| + ra rb + u|m| + η
//   {a} / {b}:  m = fl(ma / mb),   r = (ra + (|m| + u|m| + η) rb) / (|mb| - rb) + u|m| + η, |mb| > rb
// Radii are themselves computed in round to nearest. A radius expression is a sum of products of
// non-negative numbers with at most 8 roundings, so its exact value is at most the computed one
// times (1 - u)^-8; `inflate` multiplies by 1 + 16u and adds 4η, which covers that (and the
// rounding of the multiplication itself, and up to four underflows) with room to spare.
// Elementary functions: the value φ(m) from the C library with the margin of interval_arith.hpp
// (8 ulps: 2^-48 |φ(m)| + 8η), and the propagated part sup |φ'| r over the ball [m - r, m + r];
// the derivative φ'(m) likewise with sup |φ''| r. Where a function is not differentiable inside
// the ball (abs, min, max at a switch), the value ball holds and the gradient ball holds Clarke's
// generalized gradient (as interval_jet.hpp); where it jumps or is undefined, nothing is enclosed.
#pragma once
#include <array>
#include <cmath>
#include <limits>

namespace footpoint::formula {

struct Ball {
  double mid = 0.0;
  double rad = 0.0;                        // >= 0; +inf encloses every value
  double lo() const { return mid - rad; }  // rounded: not an enclosure end by itself
  double hi() const { return mid + rad; }
};

template <int N>
struct BallJet1 {
  Ball v;
  std::array<Ball, N> g{};
  // false: the formula is undefined at (or too near, within the balls) the point, or jumps there:
  // nothing below holds.
  bool defined = true;
  // false: the formula is not differentiable within the balls (a kink of abs, min or max); `g`
  // then encloses Clarke's generalized gradient, as interval_jet.hpp's lipschitz-only case.
  bool differentiable = true;
};

namespace ball {

inline constexpr double kU = 0x1p-53;      // unit roundoff
inline constexpr double kEta = 0x1p-1022;  // the smallest normal number (see above)

// An upper bound of a radius expression computed in round to nearest (see above).
inline double inflate(double r) { return r * (1.0 + 16.0 * kU) + 4.0 * kEta; }
// The error bound of one correctly rounded operation whose result is c.
inline double rounding(double c) { return kU * std::abs(c) + kEta; }

inline Ball exact(double x) { return {x, 0.0}; }
inline Ball add(const Ball& a, const Ball& b) {
  const double m = a.mid + b.mid;
  return {m, inflate(a.rad + b.rad + rounding(m))};
}
inline Ball sub(const Ball& a, const Ball& b) {
  const double m = a.mid - b.mid;
  return {m, inflate(a.rad + b.rad + rounding(m))};
}
inline Ball neg(const Ball& a) { return {-a.mid, a.rad}; }
inline Ball mul(const Ball& a, const Ball& b) {
  const double m = a.mid * b.mid;
  return {m, inflate(std::abs(a.mid) * b.rad + a.rad * std::abs(b.mid) + a.rad * b.rad + rounding(m))};
}
// a times an exact double k.
inline Ball scale(const Ball& a, double k) {
  const double m = a.mid * k;
  return {m, inflate(a.rad * std::abs(k) + rounding(m))};
}
inline Ball div(const Ball& a, const Ball& b) {
  const double m = a.mid / b.mid;
  // |mb| - rb rounded down: one rounding of a difference, relative u
  const double denominator = (std::abs(b.mid) - b.rad) * (1.0 - 4.0 * kU);
  if (!(denominator > 0.0)) return {m, std::numeric_limits<double>::infinity()};
  const double q = std::abs(m) + rounding(m);
  return {m, inflate((a.rad + q * b.rad) / denominator + rounding(m))};
}
// The hull of two balls (Clarke's gradient of a switch, a select that may go either way).
inline Ball hull(const Ball& a, const Ball& b) {
  const double lo = std::fmin(a.mid - a.rad, b.mid - b.rad), hi = std::fmax(a.mid + a.rad, b.mid + b.rad);
  const double m = 0.5 * lo + 0.5 * hi;
  return {m, inflate(std::fmax(m - lo, hi - m) + rounding(lo) + rounding(hi))};
}
// Every value in the ball is > 0, < 0.
inline bool positive(const Ball& a) { return a.mid > a.rad * (1.0 + 4.0 * kU) + kEta; }
inline bool negative(const Ball& a) { return -a.mid > a.rad * (1.0 + 4.0 * kU) + kEta; }

}  // namespace ball

}  // namespace footpoint::formula
