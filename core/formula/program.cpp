// Evaluation of the expression tape: one forward pass over the nodes, for plain values, for
// second- and third-order jets (exact derivatives by the chain and Leibniz rules) and for intervals.
#include "formula/program.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "formula/elementary.hpp"
#include "formula/interval_arith.hpp"
#include "formula/tape.hpp"
#include "formula/tape_run.hpp"

namespace footpoint::formula {

namespace {

// ---- plain values -----------------------------------------------------------------------------
struct ValueArith {
  using T = double;
  using Input = double;
  using Output = T;
  static const T& output(const T& a) { return a; }
  static T constant(double c) { return c; }
  static T variable(const Input* x, int i) { return x[i]; }
  [[gnu::always_inline]] static T unary(Op op, const T& a, double k) { return unary_value(op, a, k); }
  [[gnu::always_inline]] static T binary(Op op, const T& a, const T& b) { return binary_value(op, a, b); }
  static const T& select(const T& c, const T& a, const T& b) { return c != 0.0 ? a : b; }
};

// ---- second-order jets: value, gradient, Hessian ------------------------------------------------
// The leaves of a jet tape, any order: a constant (no derivatives) and an input variable x_i
// (gradient e_i, no higher derivatives), built in registers (no entry indexed by i at run time) and
// stored whole: a jet stored by parts and read back by pairs of doubles would stall the load on
// store forwarding.
template <class J, int N>
struct JetLeaves {
  using T = J;
  using Input = double;
  using Output = T;
  static const T& output(const T& a) { return a; }
  static T constant(double c) {
    T r;
    r.v = c;
    return r;
  }
  static T variable(const Input* x, int i) {
    T r;
    r.v = x[i];
    for (int k = 0; k < N; ++k) r.g[k] = k == i ? 1.0 : 0.0;
    return r;
  }
};

template <int N>
struct Jet2Arith : JetLeaves<Jet2<N>, N> {
  using T = Jet2<N>;
  using JetLeaves<Jet2<N>, N>::constant;
  // Chain rule: (f∘a)_i = f' a_i,  (f∘a)_ij = f' a_ij + f'' a_i a_j.
  [[gnu::always_inline]] static T chain(const T& a, const double d[4]) {
    T r;
    r.v = d[0];
    for (int i = 0; i < N; ++i) r.g[i] = d[1] * a.g[i];
    for (int i = 0; i < N; ++i)
      for (int j = i; j < N; ++j) r.h[j][i] = r.h[i][j] = d[1] * a.h[i][j] + d[2] * a.g[i] * a.g[j];
    return r;
  }
  [[gnu::always_inline]] static T unary(Op op, const T& a, double k) {
    T r;
    switch (op) {  // linear ops with a constant: every derivative scales or passes through
      case Op::add_k:
        r = a;
        r.v += k;
        return r;
      case Op::mul_k:
      case Op::div_k:
      case Op::rsub_k:
      case Op::neg: {
        const double s = op == Op::mul_k ? k : (op == Op::div_k ? 1.0 / k : -1.0);
        r.v = unary_value(op, a.v, k);
        for (int i = 0; i < N; ++i) r.g[i] = s * a.g[i];
        for (int i = 0; i < N; ++i)
          for (int j = 0; j < N; ++j) r.h[i][j] = s * a.h[i][j];
        return r;
      }
      default: {
        double d[4];
        unary_derivatives(op, a.v, k, 2, d);
        return chain(a, d);
      }
    }
  }
  [[gnu::always_inline]] static T binary(Op op, const T& a, const T& b) {
    T r;
    switch (op) {
      case Op::add:
      case Op::sub: {
        const double s = op == Op::add ? 1.0 : -1.0;
        r.v = op == Op::add ? a.v + b.v : a.v - b.v;
        for (int i = 0; i < N; ++i) r.g[i] = a.g[i] + s * b.g[i];
        for (int i = 0; i < N; ++i)
          for (int j = 0; j < N; ++j) r.h[i][j] = a.h[i][j] + s * b.h[i][j];
        return r;
      }
      case Op::mul:  // Leibniz: (ab)_ij = a_ij b + a_i b_j + a_j b_i + a b_ij
        r.v = a.v * b.v;
        for (int i = 0; i < N; ++i) r.g[i] = a.g[i] * b.v + a.v * b.g[i];
        for (int i = 0; i < N; ++i)
          for (int j = i; j < N; ++j)
            r.h[j][i] = r.h[i][j] = a.h[i][j] * b.v + a.g[i] * b.g[j] + a.g[j] * b.g[i] + a.v * b.h[i][j];
        return r;
      case Op::div:  // q = a/b from a = q b:  q_i = (a_i - q b_i)/b,  q_ij = (a_ij - q_i b_j - q_j b_i - q
                     // b_ij)/b
        r.v = a.v / b.v;
        for (int i = 0; i < N; ++i) r.g[i] = (a.g[i] - r.v * b.g[i]) / b.v;
        for (int i = 0; i < N; ++i)
          for (int j = i; j < N; ++j)
            r.h[j][i] = r.h[i][j] = (a.h[i][j] - r.g[i] * b.g[j] - r.g[j] * b.g[i] - r.v * b.h[i][j]) / b.v;
        return r;
      case Op::min:
        return a.v <= b.v ? a : b;
      case Op::max:
        return a.v >= b.v ? a : b;
      default:
        return constant(binary_value(op, a.v, b.v));
    }
  }
  static const T& select(const T& c, const T& a, const T& b) { return c.v != 0.0 ? a : b; }
};

// ---- second-order jets in two variables, in pairs of doubles -----------------------------------------
// The surfaces' case (u, v). A register holds (v, 0), (g_u, g_v), (h_uu, h_uv), (h_vu, h_vv), each an
// aligned pair of doubles that every operation reads and writes whole, so that a node's result is
// forwarded from its stores to the next node's loads (the generic jet, seven doubles read and
// written in the compiler's own mix of single and paired accesses, stalls on store forwarding).
// The arithmetic and the order of every sum are those of Jet2Arith; the Hessian is made exactly
// symmetric by copying h_uv into h_vu.
typedef double Pair __attribute__((vector_size(16)));

struct PairJet {
  Pair v, g, h0, h1;  // v = (value, 0)
};

struct Jet2PairArith {
  using T = PairJet;
  using Input = double;
  using Output = Jet2<2>;
  static Pair splat(double x) { return Pair{x, x}; }
  static Pair value(double x) { return Pair{x, 0.0}; }
  static Pair mirror(const Pair& h0, const Pair& h1) { return Pair{h0[1], h1[1]}; }  // h_vu := h_uv
  static Output output(const T& a) {
    Output r;
    r.v = a.v[0];
    r.g = {a.g[0], a.g[1]};
    r.h = {{{a.h0[0], a.h0[1]}, {a.h1[0], a.h1[1]}}};
    return r;
  }
  static T constant(double c) { return {value(c), Pair{0.0, 0.0}, Pair{0.0, 0.0}, Pair{0.0, 0.0}}; }
  static T variable(const Input* x, int i) {
    return {value(x[i]), i == 0 ? Pair{1.0, 0.0} : Pair{0.0, 1.0}, Pair{0.0, 0.0}, Pair{0.0, 0.0}};
  }
  static T scaled(const T& a, double s, double v) {
    const Pair k = splat(s);
    return {value(v), k * a.g, k * a.h0, k * a.h1};
  }
  // (f∘a)_i = f' a_i,  (f∘a)_ij = f' a_ij + (f'' a_i) a_j.
  [[gnu::always_inline]] static T chain(const T& a, const double d[4]) {
    const Pair d1 = splat(d[1]);
    const Pair h0 = d1 * a.h0 + splat(d[2] * a.g[0]) * a.g;
    const Pair h1 = d1 * a.h1 + splat(d[2] * a.g[1]) * a.g;
    return {value(d[0]), d1 * a.g, h0, mirror(h0, h1)};
  }
  [[gnu::always_inline]] static T unary(Op op, const T& a, double k) {
    switch (op) {
      case Op::add_k:
        return {value(a.v[0] + k), a.g, a.h0, a.h1};
      case Op::mul_k:
        return scaled(a, k, a.v[0] * k);
      case Op::div_k:
        return scaled(a, 1.0 / k, a.v[0] / k);
      case Op::rsub_k:
        return scaled(a, -1.0, k - a.v[0]);
      case Op::neg:
        return scaled(a, -1.0, -a.v[0]);
      default: {
        double d[4];
        unary_derivatives(op, a.v[0], k, 2, d);
        return chain(a, d);
      }
    }
  }
  [[gnu::always_inline]] static T binary(Op op, const T& a, const T& b) {
    switch (op) {
      case Op::add:
        return {a.v + b.v, a.g + b.g, a.h0 + b.h0, a.h1 + b.h1};
      case Op::sub:
        return {a.v - b.v, a.g - b.g, a.h0 - b.h0, a.h1 - b.h1};
      case Op::mul: {  // Leibniz: (ab)_ij = a_ij b + a_i b_j + a_j b_i + a b_ij
        const Pair av = splat(a.v[0]), bv = splat(b.v[0]);
        const Pair h0 = a.h0 * bv + splat(a.g[0]) * b.g + a.g * splat(b.g[0]) + av * b.h0;
        const Pair h1 = a.h1 * bv + splat(a.g[1]) * b.g + a.g * splat(b.g[1]) + av * b.h1;
        return {value(a.v[0] * b.v[0]), a.g * bv + av * b.g, h0, mirror(h0, h1)};
      }
      case Op::div: {  // q = a/b:  q_i = (a_i - q b_i)/b,  q_ij = (a_ij - q_i b_j - q_j b_i - q b_ij)/b
        const double q = a.v[0] / b.v[0];
        const Pair bv = splat(b.v[0]), qv = splat(q);
        const Pair g = (a.g - qv * b.g) / bv;
        const Pair h0 = (a.h0 - splat(g[0]) * b.g - g * splat(b.g[0]) - qv * b.h0) / bv;
        const Pair h1 = (a.h1 - splat(g[1]) * b.g - g * splat(b.g[1]) - qv * b.h1) / bv;
        return {value(q), g, h0, mirror(h0, h1)};
      }
      case Op::min:
        return a.v[0] <= b.v[0] ? a : b;
      case Op::max:
        return a.v[0] >= b.v[0] ? a : b;
      default:
        return constant(binary_value(op, a.v[0], b.v[0]));
    }
  }
  static const T& select(const T& c, const T& a, const T& b) { return c.v[0] != 0.0 ? a : b; }
};

// ---- third-order jets ------------------------------------------------------------------------
template <int N>
struct Jet3Arith : JetLeaves<Jet3<N>, N> {
  using T = Jet3<N>;
  using JetLeaves<Jet3<N>, N>::constant;
  // Faà di Bruno to third order:
  //   (f∘a)_ijk = f' a_ijk + f'' (a_ij a_k + a_ik a_j + a_jk a_i) + f''' a_i a_j a_k.
  [[gnu::always_inline]] static T chain(const T& a, const double d[4]) {
    T r;
    r.v = d[0];
    for (int i = 0; i < N; ++i) r.g[i] = d[1] * a.g[i];
    for (int i = 0; i < N; ++i)
      for (int j = 0; j < N; ++j) r.h[i][j] = d[1] * a.h[i][j] + d[2] * a.g[i] * a.g[j];
    for (int i = 0; i < N; ++i)
      for (int j = 0; j < N; ++j)
        for (int k = 0; k < N; ++k)
          r.t[i][j][k] = d[1] * a.t[i][j][k] +
                         d[2] * (a.h[i][j] * a.g[k] + a.h[i][k] * a.g[j] + a.h[j][k] * a.g[i]) +
                         d[3] * a.g[i] * a.g[j] * a.g[k];
    return r;
  }
  [[gnu::always_inline]] static T unary(Op op, const T& a, double k) {
    double d[4];
    unary_derivatives(op, a.v, k, 3, d);
    return chain(a, d);
  }
  // Leibniz to third order: sum over the ways to split {i,j,k} between the two factors.
  static double leibniz3(const T& a, const T& b, int i, int j, int k) {
    return a.t[i][j][k] * b.v + a.h[i][j] * b.g[k] + a.h[i][k] * b.g[j] + a.h[j][k] * b.g[i] +
           a.g[i] * b.h[j][k] + a.g[j] * b.h[i][k] + a.g[k] * b.h[i][j] + a.v * b.t[i][j][k];
  }
  [[gnu::always_inline]] static T binary(Op op, const T& a, const T& b) {
    T r;
    switch (op) {
      case Op::add:
      case Op::sub: {
        const double s = op == Op::add ? 1.0 : -1.0;
        r.v = op == Op::add ? a.v + b.v : a.v - b.v;
        for (int i = 0; i < N; ++i) r.g[i] = a.g[i] + s * b.g[i];
        for (int i = 0; i < N; ++i)
          for (int j = 0; j < N; ++j) {
            r.h[i][j] = a.h[i][j] + s * b.h[i][j];
            for (int k = 0; k < N; ++k) r.t[i][j][k] = a.t[i][j][k] + s * b.t[i][j][k];
          }
        return r;
      }
      case Op::mul:
        r.v = a.v * b.v;
        for (int i = 0; i < N; ++i) r.g[i] = a.g[i] * b.v + a.v * b.g[i];
        for (int i = 0; i < N; ++i)
          for (int j = 0; j < N; ++j) {
            r.h[i][j] = a.h[i][j] * b.v + a.g[i] * b.g[j] + a.g[j] * b.g[i] + a.v * b.h[i][j];
            for (int k = 0; k < N; ++k) r.t[i][j][k] = leibniz3(a, b, i, j, k);
          }
        return r;
      case Op::div: {
        // q = a/b: solve a = q b order by order; (q b)_ijk = leibniz3(q, b) contains q_ijk b.
        r.v = a.v / b.v;
        for (int i = 0; i < N; ++i) r.g[i] = (a.g[i] - r.v * b.g[i]) / b.v;
        for (int i = 0; i < N; ++i)
          for (int j = 0; j < N; ++j)
            r.h[i][j] = (a.h[i][j] - r.g[i] * b.g[j] - r.g[j] * b.g[i] - r.v * b.h[i][j]) / b.v;
        for (int i = 0; i < N; ++i)
          for (int j = 0; j < N; ++j)
            for (int k = 0; k < N; ++k) {
              r.t[i][j][k] = 0.0;
              r.t[i][j][k] = (a.t[i][j][k] - leibniz3(r, b, i, j, k)) / b.v;
            }
        return r;
      }
      case Op::min:
        return a.v <= b.v ? a : b;
      case Op::max:
        return a.v >= b.v ? a : b;
      default:
        return constant(binary_value(op, a.v, b.v));
    }
  }
  static const T& select(const T& c, const T& a, const T& b) { return c.v != 0.0 ? a : b; }
};

}  // namespace

Program Program::compile(const std::vector<NamedFormula>& formulas, const std::vector<std::string>& variables,
                         const std::map<std::string, double>& constants, const CompileLimits& limits) {
  return from_tape(build_tape(formulas, variables, constants, limits));
}

Program Program::from_tape(Tape tape) {
  Program p;
  tape.polynomial = polynomial_form(tape);
  p.tape_ = std::make_shared<const Tape>(std::move(tape));
  return p;
}

double Program::constant_value(const NamedFormula& formula, const std::map<std::string, double>& constants,
                               const CompileLimits& limits) {
  const Program p = compile({formula}, {}, constants, limits);
  double value = 0.0;
  p.values(nullptr, &value);
  return value;
}

int Program::num_inputs() const { return tape_->num_inputs; }
int Program::num_outputs() const { return static_cast<int>(tape_->outputs.size()); }
std::size_t Program::num_nodes() const { return tape_->nodes.size(); }
bool Program::sum_of_monomials() const { return tape_->polynomial.has_value(); }
std::size_t Program::memory_bytes() const {
  return sizeof(Tape) + tape_->nodes.capacity() * sizeof(Node) +
         (tape_->polynomial ? tape_->polynomial->memory_bytes() : 0) +
         tape_->outputs.capacity() * sizeof(std::int32_t);
}

void Program::values(const double* x, double* out) const { run<ValueArith>(*tape_, x, out); }

template <int N>
void Program::jets2(const double* x, Jet2<N>* out) const {
  if (tape_->polynomial) return polynomial_jets2<N>(*tape_->polynomial, x, out);
  if constexpr (N == 2)
    run<Jet2PairArith>(*tape_, x, out);
  else
    run<Jet2Arith<N>>(*tape_, x, out);
}

template <int N>
void Program::jets3(const double* x, Jet3<N>* out) const {
  run<Jet3Arith<N>>(*tape_, x, out);
}

void Program::intervals(const Interval* x, Interval* out) const { run<IntervalArith>(*tape_, x, out); }

template void Program::jets2<1>(const double*, Jet2<1>*) const;
template void Program::jets2<2>(const double*, Jet2<2>*) const;
template void Program::jets2<3>(const double*, Jet2<3>*) const;
template void Program::jets3<1>(const double*, Jet3<1>*) const;
template void Program::jets3<2>(const double*, Jet3<2>*) const;
template void Program::jets3<3>(const double*, Jet3<3>*) const;

}  // namespace footpoint::formula
