// Interval jets of the tape (formula/interval_jet.hpp): the chain and Leibniz rules of the point
// jets (program.cpp), every product and sum an outward-rounded interval operation, the value of
// each node the interval evaluation's (interval_arith.hpp), and each operation's derivatives
// enclosed over the range of its argument. The identities hold pointwise at every x of the box
// with the exact values lying in the enclosures, so the enclosures hold:
//   (φ∘a)_i = φ'(a) a_i,            (φ∘a)_ij = φ'(a) a_ij + φ''(a) a_i a_j,
//   (ab)_i = a_i b + a b_i,         (ab)_ij = a_ij b + a_i b_j + a_j b_i + a b_ij,
//   q = a/b: q_i = (a_i - q b_i)/b, q_ij = (a_ij - q_i b_j - q_j b_i - q b_ij)/b.
#include <cmath>
#include <numbers>
#include <type_traits>

#include "formula/interval_arith.hpp"
#include "formula/interval_jet.hpp"
#include "formula/program.hpp"
#include "formula/tape.hpp"
#include "formula/tape_run.hpp"

namespace footpoint::formula {

namespace {

using namespace interval;

// φ'(A) and φ''(A) over the argument's range A (R = φ(A)), and whether φ is Lipschitz / twice
// continuously differentiable on a neighbourhood of A.
struct Derivatives {
  Interval d1, d2;
  bool lipschitz = true, smooth = true;
};

Interval libm(Op op, const Interval& a) { return IntervalArith::unary(op, a, 0.0); }

// An interval holding a constant c computed to the nearest double (within half an ulp).
Interval nearest(double c) { return outward(c, c); }

// Without `second`, d2 may be left unset where it costs more than a product (IntervalJet1).
Derivatives derivatives(Op op, const Interval& A, const Interval& R, double k, bool second) {
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
      d.d2 = mul(point(-2.0), div(d.d1, A));
      return d;
    case Op::pow_int: {  // n x^(n-1), n (n-1) x^(n-2); n is neither 0 nor 1 on the tape
      const int n = static_cast<int>(k);
      if (n < 0 && A.lo <= 0.0 && A.hi >= 0.0) return singular();
      d.d1 = mul(point(n), IntervalArith::pow_int(A, n - 1));
      if (second) d.d2 = mul(mul(point(n), point(n - 1.0)), IntervalArith::pow_int(A, n - 2));
      return d;
    }
    case Op::pow_real:  // x^k for x > 0: k x^k / x, (k - 1) d1 / x
      if (!std::isfinite(k) || !(A.lo > 0.0)) return singular();
      d.d1 = mul(point(k), div(R, A));
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
      d.d2 = mul(point(2.0), mul(R, d.d1));
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
      d.d2 = mul(point(-2.0), mul(A, sqr(q)));
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
      d.d2 = mul(point(-2.0), mul(R, d.d1));
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
      d.d2 = mul(point(2.0), mul(A, sqr(q)));
      return d;
    }
    default:
      return singular();
  }
}

// J is IntervalJet2<N> (values, gradients, Hessians) or IntervalJet1<N> (no Hessians: every
// Hessian step below is compiled out).
template <int N, class J>
struct IntervalJetArith {
  using T = J;
  static constexpr bool kHessian = std::is_same_v<J, IntervalJet2<N>>;
  using Input = Interval;
  using Output = T;
  static const T& output(const T& a) { return a; }
  static T constant(double c) {
    T r;
    r.v = {c, c};
    return r;
  }
  static T variable(const Input* x, int i) {
    T r;
    r.v = x[i];
    r.g[static_cast<std::size_t>(i)] = {1.0, 1.0};
    return r;
  }
  // The derivative enclosures a false flag leaves invalid hold the whole line; a value undefined
  // somewhere in the box (or nowhere defined) has neither.
  static T& settle(T& r) {
    if (r.v.partial || IntervalArith::bad(r.v)) r.lipschitz = false;
    if (!r.lipschitz) {
      r.smooth = false;
      for (auto& x : r.g) x = entire();
    }
    if constexpr (kHessian)
      if (!r.smooth)
        for (auto& row : r.h)
          for (auto& x : row) x = entire();
    return r;
  }
  // f∘a for φ with derivatives d over a's range.
  static T chain(const T& a, const Interval& value, const Derivatives& d) {
    T r;
    r.v = value;
    r.lipschitz = a.lipschitz && d.lipschitz;
    r.smooth = r.lipschitz && a.smooth && d.smooth;
    if (r.lipschitz)
      for (int i = 0; i < N; ++i) r.g[i] = mul(d.d1, a.g[i]);
    if constexpr (kHessian)
      if (r.smooth)
        for (int i = 0; i < N; ++i)
          for (int j = i; j < N; ++j)
            r.h[j][i] = r.h[i][j] = add(mul(d.d1, a.h[i][j]), mul(d.d2, mul(a.g[i], a.g[j])));
    return settle(r);
  }
  // every derivative times the constant interval s (a linear operation)
  static T scaled(const T& a, const Interval& value, const Interval& s) {
    T r = a;
    r.v = value;
    for (int i = 0; i < N; ++i) r.g[i] = mul(s, a.g[i]);
    if constexpr (kHessian)
      for (int i = 0; i < N; ++i)
        for (int j = 0; j < N; ++j) r.h[i][j] = mul(s, a.h[i][j]);
    return settle(r);
  }
  static T unary(Op op, const T& a, double k) {
    const Interval value = IntervalArith::unary(op, a.v, k);
    switch (op) {
      case Op::add_k: {
        T r = a;
        r.v = value;
        return settle(r);
      }
      case Op::neg:
      case Op::rsub_k:
        return scaled(a, value, point(-1.0));
      case Op::mul_k:
        return scaled(a, value, point(k));
      case Op::div_k:
        return scaled(a, value, div(point(1.0), point(k)));
      case Op::abs:
        // one branch over the whole box: the argument itself or its negative
        if (a.v.lo >= 0.0) return scaled(a, value, point(1.0));
        if (a.v.hi <= 0.0) return scaled(a, value, point(-1.0));
        {  // a kink inside: Lipschitz with |abs'| <= 1, no Hessian
          Derivatives d;
          d.d1 = {-1.0, 1.0};
          d.smooth = false;
          return chain(a, value, d);
        }
      case Op::sign:
        if (a.v.lo > 0.0 || a.v.hi < 0.0) return constant_over_box(value);
        return jump(value);
      default:
        return chain(a, value, derivatives(op, a.v, value, k, kHessian));
    }
  }
  // A function constant over the box (a sign or a truth value that does not change there).
  static T constant_over_box(const Interval& value) {
    T r;
    r.v = value;
    return settle(r);
  }
  // A value that may jump inside the box: no derivative enclosure.
  static T jump(const Interval& value) {
    T r;
    r.v = value;
    r.lipschitz = r.smooth = false;
    return settle(r);
  }
  static T binary(Op op, const T& a, const T& b) {
    const Interval value = IntervalArith::binary(op, a.v, b.v);
    T r;
    r.v = value;
    r.lipschitz = a.lipschitz && b.lipschitz;
    r.smooth = r.lipschitz && a.smooth && b.smooth;
    switch (op) {
      case Op::add:
      case Op::sub: {
        const bool plus = op == Op::add;
        for (int i = 0; i < N; ++i) r.g[i] = plus ? add(a.g[i], b.g[i]) : sub(a.g[i], b.g[i]);
        if constexpr (kHessian)
          for (int i = 0; i < N; ++i)
            for (int j = 0; j < N; ++j)
              r.h[i][j] = plus ? add(a.h[i][j], b.h[i][j]) : sub(a.h[i][j], b.h[i][j]);
        return settle(r);
      }
      case Op::mul:
        if (&a ==
            &b) {  // x * x, one node for both operands: (x^2)_i = 2 x x_i, (x^2)_ij = 2 (x_i x_j + x x_ij)
          for (int i = 0; i < N; ++i) r.g[i] = mul(point(2.0), mul(a.v, a.g[i]));
          if constexpr (kHessian)
            for (int i = 0; i < N; ++i)
              for (int j = i; j < N; ++j)
                r.h[j][i] = r.h[i][j] =
                    mul(point(2.0), add(i == j ? sqr(a.g[i]) : mul(a.g[i], a.g[j]), mul(a.v, a.h[i][j])));
          return settle(r);
        }
        for (int i = 0; i < N; ++i) r.g[i] = add(mul(a.g[i], b.v), mul(a.v, b.g[i]));
        if constexpr (kHessian)
          for (int i = 0; i < N; ++i)
            for (int j = i; j < N; ++j)
              r.h[j][i] = r.h[i][j] = add(add(mul(a.h[i][j], b.v), mul(a.g[i], b.g[j])),
                                          add(mul(a.g[j], b.g[i]), mul(a.v, b.h[i][j])));
        return settle(r);
      case Op::div: {
        if (b.v.lo <= 0.0 && b.v.hi >= 0.0) return jump(value);
        const Interval q = value;
        for (int i = 0; i < N; ++i) r.g[i] = div(sub(a.g[i], mul(q, b.g[i])), b.v);
        if constexpr (kHessian)
          for (int i = 0; i < N; ++i)
            for (int j = i; j < N; ++j)
              r.h[j][i] = r.h[i][j] = div(
                  sub(sub(a.h[i][j], mul(r.g[i], b.g[j])), add(mul(r.g[j], b.g[i]), mul(q, b.h[i][j]))), b.v);
        return settle(r);
      }
      case Op::min:
      case Op::max: {
        // one operand everywhere (min: a <= b over the box takes a; ties are equal values), or a
        // switch inside: Clarke's gradient lies in the hull of both gradients, no Hessian
        const bool a_side = op == Op::min ? a.v.hi <= b.v.lo : a.v.lo >= b.v.hi;
        const bool b_side = op == Op::min ? b.v.hi <= a.v.lo : b.v.lo >= a.v.hi;
        if (!a.v.partial && !b.v.partial && (a_side || b_side)) {
          T s = a_side ? a : b;
          s.v = value;
          return settle(s);
        }
        for (int i = 0; i < N; ++i) r.g[i] = interval::hull(a.g[i], b.g[i]);
        r.smooth = false;
        return settle(r);
      }
      default:  // comparisons and logic: constant where the truth does not change, else a jump
        if (value.lo == value.hi && !value.partial) return constant_over_box(value);
        return jump(value);
    }
  }
  static T select(const T& c, const T& a, const T& b) {  // c ? a : b, and NaN ? a : b is a
    if (IntervalArith::surely_nonzero(c.v)) return a;
    if (IntervalArith::surely_zero(c.v) && !c.v.partial) return b;
    return jump(IntervalArith::hull(a.v, b.v));
  }
};

}  // namespace

template <int N>
void Program::interval_jets2(const Interval* x, IntervalJet2<N>* out) const {
  run<IntervalJetArith<N, IntervalJet2<N>>>(*tape_, x, out);
}

template <int N>
void Program::interval_jets1(const Interval* x, IntervalJet1<N>* out) const {
  run<IntervalJetArith<N, IntervalJet1<N>>>(*tape_, x, out);
}

template void Program::interval_jets2<1>(const Interval*, IntervalJet2<1>*) const;
template void Program::interval_jets2<2>(const Interval*, IntervalJet2<2>*) const;
template void Program::interval_jets2<3>(const Interval*, IntervalJet2<3>*) const;
template void Program::interval_jets1<1>(const Interval*, IntervalJet1<1>*) const;
template void Program::interval_jets1<2>(const Interval*, IntervalJet1<2>*) const;
template void Program::interval_jets1<3>(const Interval*, IntervalJet1<3>*) const;

}  // namespace footpoint::formula
