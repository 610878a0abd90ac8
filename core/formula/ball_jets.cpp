// First-order ball jets of the tape (formula/ball.hpp): value and gradient of every formula at a
// point, each a ball that holds the exact value of the compiled formula there.
//   (φ∘a)_i = φ'(a) a_i,   (ab)_i = a_i b + a b_i,   q = a/b: q_i = (a_i - q b_i)/b
// with every product and sum a ball operation. The unary functions the surfaces and curves use
// most (sin, cos, exp, ln, sqrt, integer powers) have bounds of their own: φ(m) and φ'(m) with
// their rounding, plus sup |φ'| r and sup |φ''| r over the ball [m - r, m + r]; the others
// take their value and derivative enclosures over that ball from the interval arithmetic
// (interval_arith.hpp, interval_derivatives.hpp), whose ranges are then written as balls.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "formula/ball.hpp"
#include "formula/interval_arith.hpp"
#include "formula/interval_derivatives.hpp"
#include "formula/program.hpp"
#include "formula/tape.hpp"
#include "formula/tape_run.hpp"

namespace footpoint::formula {

namespace {

using ball::inflate;
using ball::kEta;
using ball::kU;
using ball::rounding;

// The C library's margin (interval_arith.hpp: 8 ulps, four times glibc's largest listed error).
double libm_error(double c) { return 0x1p-48 * std::abs(c) + 8.0 * kEta; }

// φ over the ball a: its value and its derivative, each a ball; `defined` false where φ is
// undefined or jumps within the ball, `differentiable` false at a kink within it (then
// `derivative` holds Clarke's generalized derivative).
struct UnaryBall {
  Ball value, derivative;
  bool defined = true, differentiable = true;
};

UnaryBall undefined() {
  UnaryBall u;
  u.defined = u.differentiable = false;
  return u;
}

Ball from_interval(const Interval& x) { return {interval::mid(x), interval::rad(x)}; }

// Through the interval arithmetic: the ranges of φ and φ' over [m - r, m + r].
UnaryBall through_intervals(Op op, const Ball& a, double k) {
  const Interval A = interval::outward(a.mid - a.rad, a.mid + a.rad);
  const Interval R = IntervalArith::unary(op, A, k);
  if (IntervalArith::bad(R) || R.partial) return undefined();
  const Derivatives d = interval_derivatives(op, A, R, k);
  if (!d.lipschitz) return undefined();
  return {from_interval(R), from_interval(d.d1), true, d.smooth};
}

// The value m_v = φ(m) with its error e_v, the derivative m_d = φ'(m) with its error e_d, and
// L1 >= sup |φ'|, L2 >= sup |φ''| over the ball.
UnaryBall propagated(double m_v, double e_v, double m_d, double e_d, double L1, double L2, double r) {
  return {{m_v, inflate(L1 * r + e_v)}, {m_d, inflate(L2 * r + e_d)}, true, true};
}

UnaryBall unary_ball(Op op, const Ball& a, double k) {
  const double m = a.mid, r = a.rad;
  switch (op) {
    case Op::sin:
    case Op::cos: {  // |sin'|, |sin''|, |cos'|, |cos''| <= 1
      const double s = std::sin(m), c = std::cos(m);
      return op == Op::sin ? propagated(s, libm_error(s), c, libm_error(c), 1.0, 1.0, r)
                           : propagated(c, libm_error(c), -s, libm_error(s), 1.0, 1.0, r);
    }
    case Op::exp: {  // exp' = exp'' = exp <= exp(m) (1 + 2r) on the ball for r <= 1
      if (!(r <= 1.0)) return through_intervals(op, a, k);
      const double e = std::exp(m);
      const double sup = (e + libm_error(e)) * (1.0 + 2.0 * r) * (1.0 + 4.0 * kU);
      return propagated(e, libm_error(e), e, libm_error(e), sup, sup, r);
    }
    case Op::ln:
    case Op::log2:
    case Op::log10: {  // c ln x: c/x, c/x^2 with x >= m - r > 0
      const double low = (m - r) * (1.0 - 4.0 * kU);
      if (!(low > 0.0)) return through_intervals(op, a, k);
      const double c = op == Op::ln ? 1.0 : (op == Op::log2 ? std::numbers::log2e : std::numbers::log10e);
      const double v = op == Op::ln ? std::log(m) : (op == Op::log2 ? std::log2(m) : std::log10(m));
      const double d = c / m;  // c is the double nearest the constant: one more rounding
      const double L1 = c / low * (1.0 + 4.0 * kU), L2 = L1 / low * (1.0 + 4.0 * kU);
      return propagated(v, libm_error(v), d, 3.0 * kU * std::abs(d) + kEta, L1, L2, r);
    }
    case Op::sqrt: {  // 1/(2 sqrt x), 1/(4 x sqrt x) with x >= m - r > 0
      const double low = (m - r) * (1.0 - 4.0 * kU);
      if (!(low > 0.0)) return through_intervals(op, a, k);
      const double s = std::sqrt(m), d = 0.5 / s;  // sqrt correctly rounded; d two roundings
      const double L1 = 0.5 / std::sqrt(low) * (1.0 + 4.0 * kU), L2 = 0.5 * L1 / low * (1.0 + 4.0 * kU);
      return propagated(s, rounding(s), d, 3.0 * kU * std::abs(d) + kEta, L1, L2, r);
    }
    case Op::pow_int: {  // x^n, n >= 2: n x^(n-1), n (n-1) x^(n-2), |x| <= |m| + r
      const int n = static_cast<int>(k);
      if (n < 2) return through_intervals(op, a, k);
      // binary powering: relative error gamma_{n-1} <= n u, widened as interval_arith.hpp does
      auto power_error = [n](double p) { return (n + 1.0) * kU * std::abs(p) + n * kEta; };
      const double v = pow_int(m, n), pm1 = pow_int(m, n - 1), d = n * pm1;
      const double e_v = power_error(v), e_d = n * power_error(pm1) + rounding(d);
      if (r == 0.0) return propagated(v, e_v, d, e_d, 0.0, 0.0, 0.0);  // an exact argument
      const double top = (std::abs(m) + r) * (1.0 + 2.0 * kU);
      const double L1 = n * pow_int(top, n - 1) * (1.0 + (n + 4.0) * kU);
      const double L2 = n * (n - 1.0) * pow_int(top, n - 2) * (1.0 + (n + 4.0) * kU);
      return propagated(v, e_v, d, e_d, L1, L2, r);
    }
    case Op::abs:
      if (ball::positive(a)) return {a, ball::exact(1.0), true, true};
      if (ball::negative(a)) return {ball::neg(a), ball::exact(-1.0), true, true};
      return {{std::abs(m), r}, {0.0, 1.0}, true, false};  // a kink inside: 1-Lipschitz
    case Op::sign:
      if (ball::positive(a)) return {ball::exact(1.0), ball::exact(0.0), true, true};
      if (ball::negative(a)) return {ball::exact(-1.0), ball::exact(0.0), true, true};
      return undefined();  // a jump inside
    default:
      return through_intervals(op, a, k);
  }
}

template <int N>
struct BallJet1Arith {
  using T = BallJet1<N>;
  using Input = double;
  using Output = T;
  static const T& output(const T& a) { return a; }
  static T constant(double c) {
    T r;
    r.v = ball::exact(c);
    return r;
  }
  static T variable(const Input* x, int i) {
    T r;
    r.v = ball::exact(x[i]);
    r.g[static_cast<std::size_t>(i)] = ball::exact(1.0);
    return r;
  }
  static T undefined_jet() {
    T r;
    r.v = {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()};
    r.defined = r.differentiable = false;
    return r;
  }
  // every derivative through the linear map x -> s x (s an exact double)
  static T scaled(const T& a, const Ball& value, double s) {
    T r = a;
    r.v = value;
    for (auto& g : r.g) g = ball::scale(g, s);
    return r;
  }
  static T unary(Op op, const T& a, double k) {
    if (!a.defined) return a;
    switch (op) {
      case Op::neg:
        return scaled(a, ball::neg(a.v), -1.0);
      case Op::add_k: {
        T r = a;
        r.v = ball::add(a.v, ball::exact(k));
        return r;
      }
      case Op::mul_k:
        return scaled(a, ball::scale(a.v, k), k);
      case Op::rsub_k:
        return scaled(a, ball::sub(ball::exact(k), a.v), -1.0);
      case Op::div_k: {
        T r = a;
        r.v = ball::div(a.v, ball::exact(k));
        for (auto& g : r.g) g = ball::div(g, ball::exact(k));
        return r;
      }
      case Op::rdiv_k: {  // k/x: derivative -(k/x)/x
        if (!(ball::positive(a.v) || ball::negative(a.v))) return undefined_jet();
        T r = a;
        r.v = ball::div(ball::exact(k), a.v);
        const Ball d = ball::neg(ball::div(r.v, a.v));
        for (auto& g : r.g) g = ball::mul(d, g);
        return r;
      }
      default: {
        const UnaryBall u = unary_ball(op, a.v, k);
        if (!u.defined) return undefined_jet();
        T r;
        r.v = u.value;
        r.differentiable = a.differentiable && u.differentiable;
        for (int i = 0; i < N; ++i) r.g[i] = ball::mul(u.derivative, a.g[i]);
        return r;
      }
    }
  }
  static T binary(Op op, const T& a, const T& b) {
    if (!a.defined || !b.defined) return undefined_jet();
    T r;
    r.differentiable = a.differentiable && b.differentiable;
    switch (op) {
      case Op::add:
        r.v = ball::add(a.v, b.v);
        for (int i = 0; i < N; ++i) r.g[i] = ball::add(a.g[i], b.g[i]);
        return r;
      case Op::sub:
        r.v = ball::sub(a.v, b.v);
        for (int i = 0; i < N; ++i) r.g[i] = ball::sub(a.g[i], b.g[i]);
        return r;
      case Op::mul:
        r.v = ball::mul(a.v, b.v);
        for (int i = 0; i < N; ++i) r.g[i] = ball::add(ball::mul(a.g[i], b.v), ball::mul(a.v, b.g[i]));
        return r;
      case Op::div:
        if (!(ball::positive(b.v) || ball::negative(b.v))) return undefined_jet();
        r.v = ball::div(a.v, b.v);
        for (int i = 0; i < N; ++i) r.g[i] = ball::div(ball::sub(a.g[i], ball::mul(r.v, b.g[i])), b.v);
        return r;
      case Op::min:
      case Op::max: {
        // one operand over the whole balls, or a switch inside: min(x, y) is within max(ra, rb)
        // of min(ma, mb), and Clarke's gradient lies in the hull of both gradients
        const Ball d = ball::sub(b.v, a.v);  // b - a
        const bool a_side = op == Op::min ? d.mid >= d.rad : -d.mid >= d.rad;
        const bool b_side = op == Op::min ? -d.mid >= d.rad : d.mid >= d.rad;
        if (a_side) return a;
        if (b_side) return b;
        r.v = {op == Op::min ? std::min(a.v.mid, b.v.mid) : std::max(a.v.mid, b.v.mid),
               std::max(a.v.rad, b.v.rad)};
        for (int i = 0; i < N; ++i) r.g[i] = ball::hull(a.g[i], b.g[i]);
        r.differentiable = false;
        return r;
      }
      default: {  // comparisons and logic: a constant where the truth is decided, else a jump
        const double t = decided(op, a.v, b.v);
        if (std::isnan(t)) return undefined_jet();
        return constant(t);
      }
    }
  }
  // The truth value 0 or 1 where it is the same for every value in the balls, else NaN.
  static double decided(Op op, const Ball& a, const Ball& b) {
    constexpr double undecided = std::numeric_limits<double>::quiet_NaN();
    const bool exact = a.rad == 0.0 && b.rad == 0.0;
    const Ball d = ball::sub(a, b);
    const bool greater = exact ? a.mid > b.mid : ball::positive(d);
    const bool less = exact ? a.mid < b.mid : ball::negative(d);
    const bool equal = exact && a.mid == b.mid;
    auto truth = [&](bool surely_true, bool surely_false) {
      return surely_true ? 1.0 : (surely_false ? 0.0 : undecided);
    };
    auto nonzero = [](const Ball& x) { return ball::positive(x) || ball::negative(x); };
    auto zero = [](const Ball& x) { return x.mid == 0.0 && x.rad == 0.0; };
    switch (op) {
      case Op::lt:
        return truth(less, greater || equal);
      case Op::le:
        return truth(less || equal, greater);
      case Op::gt:
        return truth(greater, less || equal);
      case Op::ge:
        return truth(greater || equal, less);
      case Op::eq:
        return truth(equal, less || greater);
      case Op::ne:
        return truth(less || greater, equal);
      case Op::logical_and:
        return truth(nonzero(a) && nonzero(b), zero(a) || zero(b));
      case Op::logical_or:
        return truth(nonzero(a) || nonzero(b), zero(a) && zero(b));
      default:
        return undecided;
    }
  }
  static T select(const T& c, const T& a, const T& b) {  // c ? a : b
    if (!c.defined) return undefined_jet();
    if (ball::positive(c.v) || ball::negative(c.v)) return a;
    if (c.v.mid == 0.0 && c.v.rad == 0.0) return b;
    return undefined_jet();
  }
};

}  // namespace

namespace {

// A value whose ball overflowed holds nothing.
template <int N>
void settle_defined(BallJet1<N>* out, int n) {
  for (int k = 0; k < n; ++k)
    out[k].defined = out[k].defined && std::isfinite(out[k].v.mid) && std::isfinite(out[k].v.rad);
}

}  // namespace

template <int N>
void Program::ball_jets1(const double* x, BallJet1<N>* out) const {
  if (tape_->polynomial && polynomial_ball_jets1<N>(*tape_->polynomial, x, out)) return;
  run<BallJet1Arith<N>>(*tape_, x, out);
  settle_defined(out, num_outputs());
}

template <int N>
void Program::ball_jets1(const double* x, BallJet1<N>* out, const BranchChoice& choice) const {
  run<BallJet1Arith<N>>(*tape_, x, out, &choice);
  settle_defined(out, num_outputs());
}

template void Program::ball_jets1<1>(const double*, BallJet1<1>*) const;
template void Program::ball_jets1<2>(const double*, BallJet1<2>*) const;
template void Program::ball_jets1<3>(const double*, BallJet1<3>*) const;
template void Program::ball_jets1<1>(const double*, BallJet1<1>*, const BranchChoice&) const;
template void Program::ball_jets1<2>(const double*, BallJet1<2>*, const BranchChoice&) const;

}  // namespace footpoint::formula
