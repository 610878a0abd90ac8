// φ'(A) and φ''(A) enclosed over an argument range A for the tape's unary operations: the
// derivatives of the interval jets (interval_jets.cpp) and of the ball jets' functions without a
// fast path (ball_jets.cpp). Internal to core/formula.
#pragma once
#include <cmath>
#include <numbers>

#include "formula/interval_arith.hpp"
#include "formula/tape.hpp"

namespace footpoint::formula {

// φ'(A) and φ''(A) over the argument's range A (R = φ(A)), and whether φ is Lipschitz / twice
// continuously differentiable on a neighbourhood of A.
struct Derivatives {
  Interval d1, d2;
  bool lipschitz = true, smooth = true;
};

// Without `second`, d2 may be left unset where it costs more than a product (first-order jets).
inline Derivatives interval_derivatives(Op op, const Interval& A, const Interval& R, double k,
                                        bool second = true) {
  using namespace interval;
  auto libm = [](Op f, const Interval& a) { return IntervalArith::unary(f, a, 0.0); };
  // an interval holding a constant computed to the nearest double (within half an ulp)
  auto nearest = [](double c) { return outward(c, c); };
  Derivatives d;
  auto singular = [&] {
    d.lipschitz = d.smooth = false;
    return d;
  };
  auto inside_unit = [&] { return A.lo > -1.0 && A.hi < 1.0; };
  switch (op) {
    case Op::rdiv_k:  // k/x: -k/x^2 = -R/x, 2k/x^3 = -2 d1/x
      if (A.lo <= 0.0 && A.hi >= 0.0) return singular();
      d.d1 = neg(div(R, A));
      d.d2 = mul(-2.0, div(d.d1, A));
      return d;
    case Op::pow_int: {  // n x^(n-1), n (n-1) x^(n-2); n is neither 0 nor 1 on the tape
      const int n = static_cast<int>(k);
      if (n < 0 && A.lo <= 0.0 && A.hi >= 0.0) return singular();
      d.d1 = mul(n, IntervalArith::pow_int(A, n - 1));
      if (second) d.d2 = mul(mul(point(n), point(n - 1.0)), IntervalArith::pow_int(A, n - 2));
      return d;
    }
    case Op::pow_real:  // x^k for x > 0: k x^k / x, (k - 1) d1 / x
      if (!std::isfinite(k) || !(A.lo > 0.0)) return singular();
      d.d1 = mul(k, div(R, A));
      d.d2 = mul(sub(point(k), point(1.0)), div(d.d1, A));
      return d;
    case Op::sqrt:  // 0.5/sqrt(x), -d1 (0.5/x)
      if (!(A.lo > 0.0)) return singular();
      d.d1 = div(point(0.5), R);
      d.d2 = neg(mul(d.d1, div(point(0.5), A)));
      return d;
    case Op::exp:
      d.d1 = d.d2 = R;
      return d;
    case Op::ln:
    case Op::log2:
    case Op::log10: {  // c/x, -d1/x with c = 1, 1/ln 2, 1/ln 10
      if (!(A.lo > 0.0)) return singular();
      const Interval c = op == Op::ln     ? point(1.0)
                         : op == Op::log2 ? nearest(std::numbers::log2e)
                                          : nearest(std::numbers::log10e);
      d.d1 = mul(c, recip(A));
      d.d2 = neg(div(d.d1, A));
      return d;
    }
    case Op::sin:
      d.d1 = libm(Op::cos, A);
      d.d2 = neg(R);
      return d;
    case Op::cos:
      d.d1 = neg(libm(Op::sin, A));
      d.d2 = neg(R);
      return d;
    case Op::tan:  // 1 + tan^2, 2 tan (1 + tan^2)
      if (!std::isfinite(R.lo) || !std::isfinite(R.hi)) return singular();
      d.d1 = add(point(1.0), sqr(R));
      d.d2 = mul(2.0, mul(R, d.d1));
      return d;
    case Op::asin:
    case Op::acos: {  // ±1/sqrt(1 - x^2), ±x (1 - x^2)^(-3/2)
      if (!inside_unit()) return singular();
      const Interval q = recip(libm(Op::sqrt, sub(point(1.0), sqr(A))));
      d.d1 = q;
      d.d2 = mul(A, mul(q, sqr(q)));
      if (op == Op::acos) d.d1 = neg(d.d1), d.d2 = neg(d.d2);
      return d;
    }
    case Op::atan: {  // 1/(1 + x^2), -2x/(1 + x^2)^2
      const Interval q = recip(add(point(1.0), sqr(A)));
      d.d1 = q;
      d.d2 = mul(-2.0, mul(A, sqr(q)));
      return d;
    }
    case Op::sinh:
      d.d1 = libm(Op::cosh, A);
      d.d2 = R;
      return d;
    case Op::cosh:
      d.d1 = libm(Op::sinh, A);
      d.d2 = R;
      return d;
    case Op::tanh:  // 1 - tanh^2, -2 tanh (1 - tanh^2)
      d.d1 = sub(point(1.0), sqr(R));
      d.d2 = mul(-2.0, mul(R, d.d1));
      return d;
    case Op::asinh: {  // 1/sqrt(1 + x^2), -x (1 + x^2)^(-3/2)
      const Interval q = recip(libm(Op::sqrt, add(point(1.0), sqr(A))));
      d.d1 = q;
      d.d2 = neg(mul(A, mul(q, sqr(q))));
      return d;
    }
    case Op::acosh: {  // 1/sqrt(x^2 - 1), -x (x^2 - 1)^(-3/2)
      if (!(A.lo > 1.0)) return singular();
      const Interval q = recip(libm(Op::sqrt, sub(sqr(A), point(1.0))));
      d.d1 = q;
      d.d2 = neg(mul(A, mul(q, sqr(q))));
      return d;
    }
    case Op::atanh: {  // 1/(1 - x^2), 2x/(1 - x^2)^2
      if (!inside_unit()) return singular();
      const Interval q = recip(sub(point(1.0), sqr(A)));
      d.d1 = q;
      d.d2 = mul(2.0, mul(A, sqr(q)));
      return d;
    }
    default:
      return singular();
  }
}

}  // namespace footpoint::formula
