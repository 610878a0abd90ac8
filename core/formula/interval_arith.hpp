// Interval enclosures of the tape's operations over a box, outward rounded. Internal to
// core/formula: the tape's interval evaluation (Program::intervals) and its interval jets
// (Program::interval_jets2) both take every value enclosure from here.
//
// What each enclosure relies on (formula/interval.hpp states the rounding model):
//  - +, -, x, /, sqrt: correctly rounded, one step outwards (interval.hpp).
//  - x^k for an integer k by binary powering (formula::pow_int, the same product as the point
//    evaluation): every rounding factor (1 + δ), |δ| <= u = 2^-53, of a squaring is raised to the
//    power of the uses of its result, and the factors of x^k total k - 1, so the computed r
//    satisfies |r - x^k| <= γ_{k-1} |x^k|, γ_n = n u / (1 - n u) (N. J. Higham, Accuracy and
//    Stability of Numerical Algorithms, 2nd ed., SIAM 2002, Lemma 3.1), plus at most (k - 1) times
//    half the smallest subnormal where the products underflow: widened by (k + 1) u |r| and k
//    subnormals.
//  - exp, log, log2, log10, sin, cos, tan, asin, acos, atan, sinh, cosh, tanh, asinh, acosh,
//    atanh, pow (glibc's libm): not correctly rounded. The GNU C Library manual (section "Known
//    Maximum Errors in Math Functions") and its x86_64 test data (sysdeps/x86_64/fpu/
//    libm-test-ulps) list at most 2 ulps for each of these in round to nearest (exp, log, sin,
//    cos, asin, acos, atan, pow: 1; log2, log10, sinh, cosh, tanh, asinh, acosh, atanh: 2; tan: 0).
//    Those are the largest errors glibc's tests found, not proven bounds; we widen every libm
//    result by kLibmUlps = 8 ulps, four times the largest listed error, and use each function's
//    exact monotonicity (the enclosure of an increasing f over [lo, hi] is [f(lo), f(hi)]).
//  - sin, cos: besides the end values, +1 or -1 wherever a maximum or minimum phase + 2kπ may lie
//    in [lo, hi]. That test is made conservative against its own rounding (periodic() below):
//    for |x| <= 1e12 the computed phase + 2kπ is within 1e-15 (|lo| + |hi| + 20) of the true one
//    (the doubles for π/2, π and 2π are within 2.5e-16 of them, the products and sums add a few u
//    of |lo| + |hi|), and the test takes a slack ten times that; beyond 1e12 the range is [-1, 1].
//    The poles of tan likewise.
//  - The constants on the tape are doubles: numbers in the formulas as muparser reads them, and
//    constant subexpressions (sqrt(2), _pi / 2) folded once in double precision. The enclosures are
//    those of the functions the tape computes with these constants - the compiled formulas.
#pragma once
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "formula/elementary.hpp"
#include "formula/interval.hpp"
#include "formula/tape.hpp"

namespace footpoint::formula {

struct IntervalArith {
  using T = Interval;
  using Input = Interval;
  using Output = T;
  static constexpr double kInf = std::numeric_limits<double>::infinity();
  static constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  static constexpr int kLibmUlps = 8;

  static const T& output(const T& a) { return a; }
  static T empty() { return {nan, nan}; }  // no point of the box is in the function's domain
  static bool bad(const T& a) { return std::isnan(a.lo) || std::isnan(a.hi); }
  // ends computed by one correctly rounded operation each
  static T widen(double lo, double hi) {
    if (std::isnan(lo) || std::isnan(hi)) return empty();
    return interval::outward(lo, hi);
  }
  // ends computed by the C library (see above): kLibmUlps ulps of a result y are at most
  // 8 x 2^-52 |y| <= 2^-48 |c| for the computed c (and 8 subnormals below the normal range)
  static double libm_margin(double c) {
    return next_up(next_up(std::abs(c) * 0x1p-48) + kLibmUlps * std::numeric_limits<double>::denorm_min());
  }
  static T widen_libm(double lo, double hi) {
    if (std::isnan(lo) || std::isnan(hi)) return empty();
    return {next_down(lo - libm_margin(lo)), next_up(hi + libm_margin(hi))};
  }
  static T constant(double c) { return {c, c}; }
  static T variable(const Input* x, int i) { return x[i]; }
  static T hull(const T& a, const T& b) {
    if (bad(a) || bad(b)) return empty();
    return {std::min(a.lo, b.lo), std::max(a.hi, b.hi), a.partial || b.partial};
  }
  // f increasing on [dlo, dhi]: clip the argument to the domain, map the ends; a clipped argument
  // means f is undefined (NaN) at some points of the box.
  template <class F>
  static T increasing(const T& a, F f, double dlo = -kInf, double dhi = kInf) {
    const double lo = std::max(a.lo, dlo), hi = std::min(a.hi, dhi);
    if (lo > hi) return empty();
    T r = widen_libm(f(lo), f(hi));
    r.partial = a.lo < dlo || a.hi > dhi;
    return r;
  }
  template <class F>
  static T decreasing(const T& a, F f, double dlo = -kInf, double dhi = kInf) {
    const double lo = std::max(a.lo, dlo), hi = std::min(a.hi, dhi);
    if (lo > hi) return empty();
    T r = widen_libm(f(hi), f(lo));
    r.partial = a.lo < dlo || a.hi > dhi;
    return r;
  }
  // f even, increasing in |x| (cosh), its ends by the C library.
  template <class F>
  static T even(const T& a, F f) {
    if (a.lo >= 0.0) return widen_libm(f(a.lo), f(a.hi));
    if (a.hi <= 0.0) return widen_libm(f(-a.hi), f(-a.lo));
    return widen_libm(f(0.0), f(std::max(-a.lo, a.hi)));
  }
  // Some phase + 2kπ (k an integer) may lie in [lo, hi]: true whenever one does (see above).
  static bool may_contain_phase(double lo, double hi, double phase, double period) {
    const double slack = 1e-14 * (std::abs(lo) + std::abs(hi) + 20.0);
    const double k0 = std::floor((lo - phase) / period);
    for (double k = k0 - 1.0; k <= k0 + 2.0; k += 1.0) {
      const double x = phase + period * k;
      if (x >= lo - slack && x <= hi + slack) return true;
    }
    return false;
  }
  // sin or cos over [lo, hi]: the ends, plus +1 / -1 where a maximum (phase_max + 2kπ) or a
  // minimum (phase_max + π + 2kπ) may lie inside.
  template <class F>
  static T periodic(double lo, double hi, F f, double phase_max) {
    constexpr double two_pi_below = 6.283185307179586;  // the double below 2π
    if (!(hi - lo < two_pi_below) || !(std::abs(lo) <= 1e12) || !(std::abs(hi) <= 1e12)) return {-1.0, 1.0};
    const double flo = f(lo), fhi = f(hi);
    double rlo = std::min(flo, fhi), rhi = std::max(flo, fhi);
    const bool has_max = may_contain_phase(lo, hi, phase_max, 2.0 * std::numbers::pi);
    const bool has_min = may_contain_phase(lo, hi, phase_max + std::numbers::pi, 2.0 * std::numbers::pi);
    const T r = widen_libm(rlo, rhi);
    return {has_min ? -1.0 : std::max(r.lo, -1.0), has_max ? 1.0 : std::min(r.hi, 1.0)};
  }
  static T mul(const T& a, const T& b) {
    const double p[4] = {a.lo * b.lo, a.lo * b.hi, a.hi * b.lo, a.hi * b.hi};
    bool zero_times_inf = false;
    for (double x : p) zero_times_inf = zero_times_inf || std::isnan(x);
    T r = interval::mul(a, b);  // 0 x inf counts as 0 there
    r.partial = zero_times_inf;
    return r;
  }
  static T div(const T& a, const T& b) {
    if (b.lo <= 0.0 && b.hi >= 0.0) {  // a/0 is infinite, 0/0 undefined
      T r{-kInf, kInf};
      r.partial = a.lo <= 0.0 && a.hi >= 0.0;
      return r;
    }
    return mul(a, widen(1.0 / b.hi, 1.0 / b.lo));
  }
  // x^k by binary powering over [lo, hi] (k >= 1), with its rounding bound (see above).
  static T pow_int_positive(const T& a, int k) {
    if (k == 1) return a;
    if (k == 2) return interval::sqr(a);
    auto f = [k](double x) { return formula::pow_int(x, k); };
    double lo, hi;
    if (k % 2 != 0) {
      lo = f(a.lo), hi = f(a.hi);
    } else if (a.lo >= 0.0) {
      lo = f(a.lo), hi = f(a.hi);
    } else if (a.hi <= 0.0) {
      lo = f(-a.hi), hi = f(-a.lo);
    } else {
      lo = 0.0, hi = f(std::max(-a.lo, a.hi));
    }
    if (std::isnan(lo) || std::isnan(hi)) return empty();
    const double rel = (k + 1.0) * 0x1p-53;
    const double tiny = k * std::numeric_limits<double>::denorm_min();
    auto margin = [&](double x) { return next_up(next_up(std::abs(x) * rel) + tiny); };
    T r{next_down(lo - margin(lo)), next_up(hi + margin(hi))};
    if (k % 2 == 0) r.lo = std::max(r.lo, 0.0);
    return r;
  }
  static T pow_int(const T& a, int k) {
    if (k < 0) return div(constant(1.0), pow_int_positive(a, -k));
    if (k == 0) return constant(1.0);
    return pow_int_positive(a, k);
  }
  static T unary(Op op, const T& a, double k) {
    T r = unary_defined(op, a, k);
    r.partial = r.partial || a.partial;
    return r;
  }
  // The poles π/2 + kπ of tan may lie in [lo, hi].
  static bool tan_pole(double lo, double hi) {
    if (!(hi - lo < 3.141592653589793) || !(std::abs(lo) <= 1e12) || !(std::abs(hi) <= 1e12)) return true;
    return may_contain_phase(lo, hi, 0.5 * std::numbers::pi, std::numbers::pi);
  }
  static T unary_defined(Op op, const T& a, double k) {
    if (bad(a)) return empty();
    switch (op) {
      case Op::neg:
        return {-a.hi, -a.lo};
      case Op::add_k:
        return widen(a.lo + k, a.hi + k);
      case Op::mul_k:
        return mul(a, constant(k));
      case Op::div_k:
        return div(a, constant(k));
      case Op::rsub_k:
        return widen(k - a.hi, k - a.lo);
      case Op::rdiv_k:
        return div(constant(k), a);
      case Op::pow_int:
        return pow_int(a, static_cast<int>(k));
      case Op::pow_real:
        if (!std::isfinite(k)) return {-kInf, kInf, true};  // x^(+-inf): 0, 1, inf or NaN by |x|
        if (k == std::floor(k)) {  // integral exponents beyond pow_int's range: the power rule's parity
          if (k < 0) return div(constant(1.0), unary(Op::pow_real, a, -k));
          auto f = [k](double x) { return std::pow(x, k); };
          return std::fmod(k, 2.0) == 0.0 ? even(a, f) : increasing(a, f);
        }
        if (k > 0)
          return increasing(
              a, [k](double x) { return std::pow(x, k); }, 0.0);
        return decreasing(
            a, [k](double x) { return std::pow(x, k); }, 0.0);
      case Op::sqrt: {  // correctly rounded
        const double lo = std::max(a.lo, 0.0);
        if (lo > a.hi) return empty();
        T r{std::max(0.0, next_down(std::sqrt(lo))), next_up(std::sqrt(a.hi))};
        r.partial = a.lo < 0.0;
        return r;
      }
      case Op::exp: {
        T r = increasing(a, [](double x) { return std::exp(x); });
        r.lo = std::max(r.lo, 0.0);
        return r;
      }
      case Op::ln:
        return increasing(
            a, [](double x) { return std::log(x); }, 0.0);
      case Op::log2:
        return increasing(
            a, [](double x) { return std::log2(x); }, 0.0);
      case Op::log10:
        return increasing(
            a, [](double x) { return std::log10(x); }, 0.0);
      case Op::sin:
        return periodic(
            a.lo, a.hi, [](double x) { return std::sin(x); }, 0.5 * std::numbers::pi);
      case Op::cos:
        return periodic(
            a.lo, a.hi, [](double x) { return std::cos(x); }, 0.0);
      case Op::tan:
        if (tan_pole(a.lo, a.hi)) return {-kInf, kInf};
        return increasing(a, [](double x) { return std::tan(x); });
      case Op::asin:
        return increasing(
            a, [](double x) { return std::asin(x); }, -1.0, 1.0);
      case Op::acos: {
        T r = decreasing(
            a, [](double x) { return std::acos(x); }, -1.0, 1.0);
        r.lo = std::max(r.lo, 0.0);
        return r;
      }
      case Op::atan:
        return increasing(a, [](double x) { return std::atan(x); });
      case Op::sinh:
        return increasing(a, [](double x) { return std::sinh(x); });
      case Op::cosh: {
        T r = even(a, [](double x) { return std::cosh(x); });
        r.lo = std::max(r.lo, 1.0);
        return r;
      }
      case Op::tanh: {
        T r = increasing(a, [](double x) { return std::tanh(x); });
        return {std::max(r.lo, -1.0), std::min(r.hi, 1.0), r.partial};
      }
      case Op::asinh:
        return increasing(a, [](double x) { return std::asinh(x); });
      case Op::acosh:
        return increasing(
            a, [](double x) { return std::acosh(x); }, 1.0);
      case Op::atanh:
        return increasing(
            a, [](double x) { return std::atanh(x); }, -1.0, 1.0);
      case Op::abs:  // exact
        if (a.lo >= 0.0) return {a.lo, a.hi};
        if (a.hi <= 0.0) return {-a.hi, -a.lo};
        return {0.0, std::max(-a.lo, a.hi)};
      case Op::sign:  // sign(NaN) is 0
        return {a.partial ? std::min(0.0, sign_of(a.lo)) : sign_of(a.lo),
                a.partial ? std::max(0.0, sign_of(a.hi)) : sign_of(a.hi), a.partial};
      default:
        return empty();
    }
  }
  static bool surely_nonzero(const T& a) { return a.excludes_zero(); }
  static bool surely_zero(const T& a) { return a.lo == 0.0 && a.hi == 0.0; }
  static T truth(bool surely_true, bool surely_false) {
    return surely_true ? T{1.0, 1.0} : (surely_false ? T{0.0, 0.0} : T{0.0, 1.0});
  }
  // Where an operand is NaN, comparisons and logic give 0 or 1 (NaN compares false and is
  // "nonzero"), min/max give either operand: the result's range must cover those values too.
  static T binary(Op op, const T& a, const T& b) {
    if (bad(a) || bad(b)) return empty();
    T r = binary_defined(op, a, b);
    if (!(a.partial || b.partial)) return r;
    if (is_comparison(op)) return {0.0, 1.0, false};
    if (op == Op::min || op == Op::max) r = hull(r, hull(a, b));
    r.partial = true;
    return r;
  }
  static T binary_defined(Op op, const T& a, const T& b) {
    switch (op) {
      case Op::add:
        return widen(a.lo + b.lo, a.hi + b.hi);
      case Op::sub:
        return widen(a.lo - b.hi, a.hi - b.lo);
      case Op::mul:  // x * x (one node for both operands: the same value everywhere) is a square
        return &a == &b ? interval::sqr(a) : mul(a, b);
      case Op::div:
        return div(a, b);
      case Op::min:
        return {std::min(a.lo, b.lo), std::min(a.hi, b.hi)};
      case Op::max:
        return {std::max(a.lo, b.lo), std::max(a.hi, b.hi)};
      case Op::lt:
        return truth(a.hi < b.lo, a.lo >= b.hi);
      case Op::le:
        return truth(a.hi <= b.lo, a.lo > b.hi);
      case Op::gt:
        return truth(a.lo > b.hi, a.hi <= b.lo);
      case Op::ge:
        return truth(a.lo >= b.hi, a.hi < b.lo);
      case Op::eq:
        return truth(a.lo == a.hi && b.lo == b.hi && a.lo == b.lo, a.hi < b.lo || b.hi < a.lo);
      case Op::ne:
        return truth(a.hi < b.lo || b.hi < a.lo, a.lo == a.hi && b.lo == b.hi && a.lo == b.lo);
      case Op::logical_and:
        return truth(surely_nonzero(a) && surely_nonzero(b), surely_zero(a) || surely_zero(b));
      case Op::logical_or:
        return truth(surely_nonzero(a) || surely_nonzero(b), surely_zero(a) && surely_zero(b));
      default:
        return empty();
    }
  }
  // The condition c takes one branch over the whole box.
  static bool decided(const T& c) { return surely_nonzero(c) || (surely_zero(c) && !c.partial); }
  static T select(const T& c, const T& a, const T& b) {  // c ? a : b, and NaN ? a : b is a
    if (surely_nonzero(c)) return a;
    if (surely_zero(c) && !c.partial) return b;
    return hull(a, b);
  }
};

}  // namespace footpoint::formula
