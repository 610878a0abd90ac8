// Values and derivatives of the tape's operations. Internal to core/formula.
//
// Conventions where a derivative does not exist (documented one-sided values, never NaN):
//   abs'(0) = +1 (right derivative); sign' = 0 everywhere (sign(0) = 0);
//   min(a,b) takes a's derivatives when a <= b, max(a,b) takes a's when a >= b;
//   comparisons, && and || have zero derivatives; c ? a : b takes the derivatives of the branch taken.
// Where the function itself is singular (sqrt'(0), ln(0), 1/0) the result is non-finite and the
// solvers report status non_finite.
#pragma once
#include <cmath>
#include <numbers>

#include "formula/sin_cos.hpp"
#include "formula/tape.hpp"

namespace footpoint::formula {

inline double sign_of(double x) { return x > 0.0 ? 1.0 : (x < 0.0 ? -1.0 : 0.0); }

// Integer power by the ordinary power rule (exact for negative bases, e.g. u^6 at u = -1.5).
inline double pow_int(double x, int k) {
  if (k < 0) return 1.0 / pow_int(x, -k);
  double r = 1.0, b = x;
  while (k > 0) {
    if (k & 1) r *= b;
    b *= b;
    k >>= 1;
  }
  return r;
}

// Value of a unary op at x (k: the exponent for pow_int / pow_real).
inline double unary_value(Op op, double x, double k) {
  switch (op) {
    case Op::neg:
      return -x;
    case Op::add_k:
      return x + k;
    case Op::mul_k:
      return x * k;
    case Op::div_k:
      return x / k;
    case Op::rsub_k:
      return k - x;
    case Op::rdiv_k:
      return k / x;
    case Op::pow_int:
      return pow_int(x, static_cast<int>(k));
    case Op::pow_real:
      return std::pow(x, k);
    case Op::sqrt:
      return std::sqrt(x);
    case Op::exp:
      return std::exp(x);
    case Op::ln:
      return std::log(x);
    case Op::log2:
      return std::log2(x);
    case Op::log10:
      return std::log10(x);
    // the jets' sin_cos, so that a point and a jet at the same parameters agree to the last bit
    case Op::sin: {
      double s, c;
      sin_cos(x, &s, &c);
      return s;
    }
    case Op::cos: {
      double s, c;
      sin_cos(x, &s, &c);
      return c;
    }
    case Op::tan:
      return std::tan(x);
    case Op::asin:
      return std::asin(x);
    case Op::acos:
      return std::acos(x);
    case Op::atan:
      return std::atan(x);
    case Op::sinh:
      return std::sinh(x);
    case Op::cosh:
      return std::cosh(x);
    case Op::tanh:
      return std::tanh(x);
    case Op::asinh:
      return std::asinh(x);
    case Op::acosh:
      return std::acosh(x);
    case Op::atanh:
      return std::atanh(x);
    case Op::abs:
      return std::fabs(x);
    case Op::sign:
      return sign_of(x);
    default:
      return std::nan("");
  }
}

// d[0..order] = f(x), f'(x), f''(x), f'''(x) for a unary op (order <= 3).
[[gnu::always_inline]] inline void unary_derivatives(Op op, double x, double k, int order, double d[4]) {
  d[1] = d[2] = d[3] = 0.0;
  switch (op) {
    case Op::neg:
      d[0] = -x;
      d[1] = -1.0;
      return;
    case Op::add_k:
      d[0] = x + k;
      d[1] = 1.0;
      return;
    case Op::mul_k:
      d[0] = x * k;
      d[1] = k;
      return;
    case Op::div_k:
      d[0] = x / k;
      d[1] = 1.0 / k;
      return;
    case Op::rsub_k:
      d[0] = k - x;
      d[1] = -1.0;
      return;
    case Op::rdiv_k: {  // k/x: derivatives -k/x^2, 2k/x^3, -6k/x^4
      const double r = 1.0 / x;
      d[0] = k / x;
      d[1] = -k * r * r;
      d[2] = 2.0 * k * r * r * r;
      d[3] = -6.0 * k * r * r * r * r;
      return;
    }
    case Op::pow_int:
      if (k >= order) {
        // x^(k-n) for n = order..0 by successive products from one power: d[n] = k!/(k-n)! x^(k-n).
        double pw[4];
        pw[order] = pow_int(x, static_cast<int>(k) - order);
        for (int n = order - 1; n >= 0; --n) pw[n] = pw[n + 1] * x;
        d[0] = pw[0];
        double coeff = 1.0;
        for (int n = 1; n <= order; ++n) {
          coeff *= (k - (n - 1));
          d[n] = coeff * pw[n];
        }
        return;
      }
      [[fallthrough]];
    case Op::pow_real: {
      // (x^k)^(n) = k (k-1) ... (k-n+1) x^(k-n); a zero coefficient gives an exact zero
      // (so x^2 has second derivative 2 and third derivative 0 also at x = 0).
      const bool integer = op == Op::pow_int;
      auto power = [&](double e) { return integer ? pow_int(x, static_cast<int>(e)) : std::pow(x, e); };
      d[0] = power(k);
      double coeff = 1.0;
      for (int n = 1; n <= order; ++n) {
        coeff *= (k - (n - 1));
        d[n] = coeff == 0.0 ? 0.0 : coeff * power(k - n);
      }
      return;
    }
    case Op::sqrt: {
      const double s = std::sqrt(x);
      d[0] = s;
      d[1] = 0.5 / s;
      d[2] = -0.25 / (s * x);
      d[3] = 0.375 / (s * x * x);
      return;
    }
    case Op::exp:
      d[0] = d[1] = d[2] = d[3] = std::exp(x);
      return;
    case Op::ln:
    case Op::log2:
    case Op::log10: {
      const double scale =
          op == Op::ln ? 1.0 : (op == Op::log2 ? 1.0 / std::numbers::ln2 : 1.0 / std::numbers::ln10);
      d[0] = unary_value(op, x, k);
      const double r = 1.0 / x;
      d[1] = scale * r;
      d[2] = -scale * r * r;
      d[3] = 2.0 * scale * r * r * r;
      return;
    }
    case Op::sin: {
      double s, c;
      sin_cos(x, &s, &c);
      d[0] = s;
      d[1] = c;
      d[2] = -s;
      d[3] = -c;
      return;
    }
    case Op::cos: {
      double s, c;
      sin_cos(x, &s, &c);
      d[0] = c;
      d[1] = -s;
      d[2] = -c;
      d[3] = s;
      return;
    }
    case Op::tan: {
      const double t = std::tan(x), q = 1.0 + t * t;  // tan' = 1 + tan^2
      d[0] = t;
      d[1] = q;
      d[2] = 2.0 * t * q;
      d[3] = 2.0 * q * (1.0 + 3.0 * t * t);
      return;
    }
    case Op::asin:
    case Op::acos: {
      const double r = 1.0 / std::sqrt(1.0 - x * x), r3 = r * r * r, sg = op == Op::asin ? 1.0 : -1.0;
      d[0] = unary_value(op, x, k);
      d[1] = sg * r;
      d[2] = sg * x * r3;
      d[3] = sg * (1.0 + 2.0 * x * x) * r3 * r * r;
      return;
    }
    case Op::atan: {
      const double q = 1.0 / (1.0 + x * x);
      d[0] = std::atan(x);
      d[1] = q;
      d[2] = -2.0 * x * q * q;
      d[3] = (6.0 * x * x - 2.0) * q * q * q;
      return;
    }
    case Op::sinh: {
      const double s = std::sinh(x), c = std::cosh(x);
      d[0] = s;
      d[1] = c;
      d[2] = s;
      d[3] = c;
      return;
    }
    case Op::cosh: {
      const double s = std::sinh(x), c = std::cosh(x);
      d[0] = c;
      d[1] = s;
      d[2] = c;
      d[3] = s;
      return;
    }
    case Op::tanh: {
      const double t = std::tanh(x), q = 1.0 - t * t;  // tanh' = 1 - tanh^2
      d[0] = t;
      d[1] = q;
      d[2] = -2.0 * t * q;
      d[3] = (6.0 * t * t - 2.0) * q;
      return;
    }
    case Op::asinh: {
      const double r = 1.0 / std::sqrt(1.0 + x * x), r3 = r * r * r;
      d[0] = std::asinh(x);
      d[1] = r;
      d[2] = -x * r3;
      d[3] = (2.0 * x * x - 1.0) * r3 * r * r;
      return;
    }
    case Op::acosh: {
      const double r = 1.0 / std::sqrt(x * x - 1.0), r3 = r * r * r;
      d[0] = std::acosh(x);
      d[1] = r;
      d[2] = -x * r3;
      d[3] = (2.0 * x * x + 1.0) * r3 * r * r;
      return;
    }
    case Op::atanh: {
      const double q = 1.0 / (1.0 - x * x);
      d[0] = std::atanh(x);
      d[1] = q;
      d[2] = 2.0 * x * q * q;
      d[3] = (2.0 + 6.0 * x * x) * q * q * q;
      return;
    }
    case Op::abs:
      d[0] = std::fabs(x);
      d[1] = x >= 0.0 ? 1.0 : -1.0;
      return;
    case Op::sign:
      d[0] = sign_of(x);
      return;
    default:
      d[0] = std::nan("");
      return;
  }
}

// Value of a binary op (arithmetic, min/max, comparisons, logic).
inline double binary_value(Op op, double a, double b) {
  switch (op) {
    case Op::add:
      return a + b;
    case Op::sub:
      return a - b;
    case Op::mul:
      return a * b;
    case Op::div:
      return a / b;
    case Op::min:
      return a <= b ? a : b;
    case Op::max:
      return a >= b ? a : b;
    case Op::lt:
      return a < b;
    case Op::le:
      return a <= b;
    case Op::gt:
      return a > b;
    case Op::ge:
      return a >= b;
    case Op::eq:
      return a == b;
    case Op::ne:
      return a != b;
    case Op::logical_and:
      return (a != 0.0) && (b != 0.0);
    case Op::logical_or:
      return (a != 0.0) || (b != 0.0);
    default:
      return std::nan("");
  }
}

inline bool is_comparison(Op op) { return op >= Op::lt && op <= Op::logical_or; }

}  // namespace footpoint::formula
