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
#include "formula/interval_derivatives.hpp"
#include "formula/interval_jet.hpp"
#include "formula/program.hpp"
#include "formula/tape.hpp"
#include "formula/tape_run.hpp"

namespace footpoint::formula {

namespace {

using namespace interval;

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
        return chain(a, value, interval_derivatives(op, a.v, value, k, kHessian));
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
          for (int i = 0; i < N; ++i) r.g[i] = mul(2.0, mul(a.v, a.g[i]));
          if constexpr (kHessian)
            for (int i = 0; i < N; ++i)
              for (int j = i; j < N; ++j)
                r.h[j][i] = r.h[i][j] =
                    mul(2.0, add(i == j ? sqr(a.g[i]) : mul(a.g[i], a.g[j]), mul(a.v, a.h[i][j])));
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

template <int N>
void Program::interval_jets2(const Interval* x, IntervalJet2<N>* out, const BranchChoice& choice) const {
  run<IntervalJetArith<N, IntervalJet2<N>>>(*tape_, x, out, &choice);
}

std::vector<std::int32_t> Program::undecided_conditions(const Interval* x) const {
  std::vector<std::int32_t> nodes;
  thread_local std::vector<Interval> out;
  out.resize(static_cast<std::size_t>(num_outputs()));
  run<IntervalArith>(*tape_, x, out.data(), nullptr, &nodes);
  return nodes;
}

template void Program::interval_jets2<1>(const Interval*, IntervalJet2<1>*) const;
template void Program::interval_jets2<2>(const Interval*, IntervalJet2<2>*) const;
template void Program::interval_jets2<3>(const Interval*, IntervalJet2<3>*) const;
template void Program::interval_jets2<1>(const Interval*, IntervalJet2<1>*, const BranchChoice&) const;
template void Program::interval_jets2<2>(const Interval*, IntervalJet2<2>*, const BranchChoice&) const;
template void Program::interval_jets1<1>(const Interval*, IntervalJet1<1>*) const;
template void Program::interval_jets1<2>(const Interval*, IntervalJet1<2>*) const;
template void Program::interval_jets1<3>(const Interval*, IntervalJet1<3>*) const;

}  // namespace footpoint::formula
