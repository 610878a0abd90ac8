// Recognising sums of monomials on the tape and evaluating their jets term by term (polynomial.hpp).
#include "formula/polynomial.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "formula/elementary.hpp"
#include "formula/tape.hpp"

namespace footpoint::formula {

namespace {

// What a node is, read bottom-up: a single term c x^a y^b z^d, a chain of sums whose deepest part
// comes first, or neither.
struct NodeForm {
  enum class Kind : std::uint8_t { neither, term, sum } kind = Kind::neither;
  Monomial term;                     // kind == term
  std::int32_t child = -1;           // kind == sum: the sum below (its terms come first), or -1
  double child_sign = 1.0;           // ... multiplied by this sign (a - (b + c), -(a + b))
  std::array<Monomial, 2> leaves{};  // ... then these terms, signs folded into their coefficients
  int num_leaves = 0;
};

// An upper bound of a coefficient's error: the bound computed in round to nearest (a few roundings
// of non-negative terms, covered by the factor) plus one rounding of the coefficient itself,
// u |c| + η (ball.hpp's bound of an underflow).
double error_bound(double propagated, double c) {
  return (propagated + 0x1p-53 * std::abs(c)) * (1.0 + 0x1p-40) + 2.0 * ball::kEta;
}

Monomial constant_term(double c) {
  Monomial m;
  m.c = c;
  return m;
}

// m times an exact double s: exact for s = ±1.
Monomial scaled(Monomial m, double s) {
  if (s == 1.0 || s == -1.0) {
    m.c *= s;
    return m;
  }
  m.c *= s;
  m.c_error = error_bound(std::abs(s) * m.c_error, m.c);
  return m;
}

// m divided by an exact double k, as m times fl(1/k): |fl(1/k) - 1/k| <= u |fl(1/k)| + η.
Monomial divided(Monomial m, double k) {
  const double q = 1.0 / k;
  const double before = std::abs(m.c), before_error = m.c_error;
  m.c *= q;
  m.c_error = error_bound(before_error / std::abs(k) + before * (0x1p-53 * std::abs(q) + ball::kEta), m.c);
  return m;
}

Monomial product(const Monomial& a, const Monomial& b) {
  Monomial m;
  m.c = a.c * b.c;
  m.c_error = error_bound(std::abs(a.c) * b.c_error + std::abs(b.c) * a.c_error + a.c_error * b.c_error, m.c);
  for (int i = 0; i < 3; ++i) m.e[i] = static_cast<std::int16_t>(a.e[i] + b.e[i]);
  return m;
}

bool acceptable(const Monomial& m) {
  if (!std::isfinite(m.c)) return false;
  for (auto e : m.e)
    if (e < 0 || e > PolynomialForm::kMaxDegree) return false;
  return true;
}

NodeForm term_form(const Monomial& m) {
  NodeForm f;
  if (!acceptable(m)) return f;
  f.kind = NodeForm::Kind::term;
  f.term = m;
  return f;
}

// a + s b for two forms, at least one of them a single term.
NodeForm sum_form(const NodeForm& a, std::int32_t a_node, const NodeForm& b, std::int32_t b_node, double s) {
  using K = NodeForm::Kind;
  NodeForm f;
  if (a.kind == K::neither || b.kind == K::neither) return f;
  f.kind = K::sum;
  if (a.kind == K::term && b.kind == K::term) {
    f.leaves = {a.term, scaled(b.term, s)};
    f.num_leaves = 2;
  } else if (a.kind == K::sum && b.kind == K::term) {  // (a's chain) + s b
    f.child = a_node;
    f.leaves[0] = scaled(b.term, s);
    f.num_leaves = 1;
  } else if (a.kind == K::term && b.kind == K::sum) {  // a + s (b's chain) = s (b's chain) + a, exactly
    f.child = b_node;
    f.child_sign = s;
    f.leaves[0] = a.term;
    f.num_leaves = 1;
  } else {
    f.kind = K::neither;  // a sum of two sums: another order of summation
  }
  return f;
}

NodeForm read_node(const Node& node, const std::vector<NodeForm>& forms) {
  using K = NodeForm::Kind;
  const NodeForm* a = node.a >= 0 ? &forms[node.a] : nullptr;
  const NodeForm* b = node.b >= 0 ? &forms[node.b] : nullptr;
  switch (node.op) {
    case Op::constant:
      return term_form(constant_term(node.k));
    case Op::variable: {
      Monomial m = constant_term(1.0);
      m.e[static_cast<int>(node.k)] = 1;
      return term_form(m);
    }
    case Op::add:
      return sum_form(*a, node.a, *b, node.b, 1.0);
    case Op::sub:
      return sum_form(*a, node.a, *b, node.b, -1.0);
    case Op::add_k:
      return sum_form(*a, node.a, term_form(constant_term(node.k)), -1, 1.0);
    case Op::rsub_k:
      return sum_form(term_form(constant_term(node.k)), -1, *a, node.a, -1.0);
    case Op::neg:
      if (a->kind == K::term) return term_form(scaled(a->term, -1.0));
      if (a->kind == K::sum) {
        NodeForm f;
        f.kind = K::sum;
        f.child = node.a;
        f.child_sign = -1.0;
        return f;
      }
      return {};
    case Op::mul_k:
      return a->kind == K::term ? term_form(scaled(a->term, node.k)) : NodeForm{};
    case Op::div_k:
      return a->kind == K::term ? term_form(divided(a->term, node.k)) : NodeForm{};
    case Op::mul:
      return a->kind == K::term && b->kind == K::term ? term_form(product(a->term, b->term)) : NodeForm{};
    case Op::pow_int: {
      if (a->kind != K::term || node.k < 0 || node.k > PolynomialForm::kMaxDegree) return {};
      Monomial m = a->term;
      const int k = static_cast<int>(node.k);
      // c^k by binary powering, within (k + 1) u |c^k| + k η of the power of the computed c
      // (interval_arith.hpp's bound); |c^k - (c ± e)^k| <= k (|c| + e)^(k - 1) e.
      const double c = std::abs(m.c), e = m.c_error;
      m.c = pow_int(m.c, k);
      m.c_error = e == 0.0 ? 0.0 : error_bound(k * pow_int(c + e, k - 1) * e, 0.0) * (1.0 + 0x1p-40);
      m.c_error = error_bound(m.c_error + (k + 1.0) * 0x1p-53 * std::abs(m.c) + k * ball::kEta, m.c);
      for (auto& e : m.e) e = static_cast<std::int16_t>(e * k);
      return term_form(m);
    }
    default:
      return {};
  }
}

// The terms of a formula in the tape's order of summation; false if there are too many.
bool append_terms(const std::vector<NodeForm>& forms, std::int32_t node, std::vector<Monomial>& out) {
  std::vector<std::pair<std::int32_t, double>> path;  // from the output down the chain of sums
  double sign = 1.0;
  for (std::int32_t at = node; at >= 0; at = forms[at].kind == NodeForm::Kind::sum ? forms[at].child : -1) {
    path.emplace_back(at, sign);
    if (forms[at].kind == NodeForm::Kind::sum) sign *= forms[at].child_sign;
  }
  for (auto it = path.rbegin(); it != path.rend(); ++it) {  // deepest first
    const NodeForm& f = forms[it->first];
    if (f.kind == NodeForm::Kind::term) out.push_back(scaled(f.term, it->second));
    for (int l = 0; l < f.num_leaves; ++l) out.push_back(scaled(f.leaves[l], it->second));
    if (out.size() > PolynomialForm::kMaxTerms) return false;
  }
  return true;
}

}  // namespace

std::optional<PolynomialForm> polynomial_form(const Program::Tape& tape) {
  if (tape.num_inputs < 1 || tape.num_inputs > 3) return std::nullopt;
  std::vector<NodeForm> forms(tape.nodes.size());
  for (std::size_t i = 0; i < tape.nodes.size(); ++i) forms[i] = read_node(tape.nodes[i], forms);
  PolynomialForm poly;
  for (auto out : tape.outputs) {
    if (forms[out].kind == NodeForm::Kind::neither) return std::nullopt;
    poly.first.push_back(static_cast<std::uint32_t>(poly.terms.size()));
    if (!append_terms(forms, out, poly.terms)) return std::nullopt;
  }
  poly.first.push_back(static_cast<std::uint32_t>(poly.terms.size()));
  for (auto& m : poly.terms) {
    for (int j = 0; j < 3; ++j) {
      poly.max_degree[j] = std::max<int>(poly.max_degree[j], m.e[j]);
      m.ce[j] = m.c * m.e[j];
      for (int k = 0; k < 3; ++k)
        m.cee[j][k] = m.c * (j == k ? m.e[j] * (m.e[j] - 1.0) : 1.0 * m.e[j] * m.e[k]);
    }
    m.pairs = {m.c, m.cee[0][1], m.ce[0], m.ce[1], m.cee[0][0], m.cee[1][1]};
  }
  return poly;
}

namespace {

template <int N>
void polynomial_jets2_any(const PolynomialForm& poly, const double* x, Jet2<N>* out) {
  // pw[i][2 + e] = x_i^e; pw[i][0] and pw[i][1] stand for x^-2 and x^-1 and hold 0, so that a
  // derivative of an exponent 0 or 1 reads a zero (its coefficient is zero as well).
  double pw[N][PolynomialForm::kMaxDegree + 3];
  for (int i = 0; i < N; ++i) {
    pw[i][0] = pw[i][1] = 0.0;
    pw[i][2] = 1.0;
    for (int e = 1; e <= poly.max_degree[i]; ++e) pw[i][2 + e] = pw[i][1 + e] * x[i];
  }
  const std::size_t num_outputs = poly.first.size() - 1;
  for (std::size_t k = 0; k < num_outputs; ++k) {
    Jet2<N> acc;
    for (std::uint32_t t = poly.first[k]; t < poly.first[k + 1]; ++t) {
      const Monomial& m = poly.terms[t];
      double p0[N], p1[N], p2[N];  // x_i^e_i, x_i^(e_i - 1), x_i^(e_i - 2)
      for (int i = 0; i < N; ++i) {
        p0[i] = pw[i][2 + m.e[i]];
        p1[i] = pw[i][1 + m.e[i]];
        p2[i] = pw[i][m.e[i]];
      }
      // others(j, k): the product of p0 over the variables other than j and k.
      auto others = [&](int j, int l) {
        double r = 1.0;
        for (int i = 0; i < N; ++i)
          if (i != j && i != l) r *= p0[i];
        return r;
      };
      Jet2<N> term;
      term.v = m.c * (p0[0] * others(0, 0));
      for (int j = 0; j < N; ++j) term.g[j] = m.ce[j] * (p1[j] * others(j, j));
      for (int j = 0; j < N; ++j) {
        term.h[j][j] = m.cee[j][j] * (p2[j] * others(j, j));
        for (int l = j + 1; l < N; ++l)
          term.h[j][l] = term.h[l][j] = m.cee[j][l] * (p1[j] * p1[l] * others(j, l));
      }
      acc.v += term.v;  // from +0: 0 + t is t, and a zero term stays +0
      for (int j = 0; j < N; ++j) acc.g[j] += term.g[j];
      for (int j = 0; j < N; ++j)
        for (int l = 0; l < N; ++l) acc.h[j][l] += term.h[j][l];
    }
    out[k] = acc;
  }
}

// Two variables (surfaces), in pairs of doubles: per term
//   (v, h_uv) = (c, c a b)           * (u^a, u^(a-1)) * (v^b, v^(b-1))
//   (g_u, g_v) = (c a, c b)          * (u^(a-1), u^a) * (v^b, v^(b-1))
//   (h_uu, h_vv) = (c a(a-1), c b(b-1)) * (u^(a-2), u^a) * (v^b, v^(b-2))
// with tables of power pairs, so that a term costs six multiplications and three additions of pairs.
typedef double Pair __attribute__((vector_size(16)));

Pair pair(double a, double b) { return Pair{a, b}; }

void polynomial_jets2_uv(const PolynomialForm& poly, const double* x, Jet2<2>* out) {
  constexpr int kSize = PolynomialForm::kMaxDegree + 1;
  // For the exponent e of u: (u^e, u^(e-1)), (u^(e-1), u^e), (u^(e-2), u^e); of v: (v^e, v^(e-1)),
  // (v^e, v^(e-2)). Negative powers stand for the zero coefficient they meet and are stored as 0.
  Pair u01[kSize], u10[kSize], u20[kSize], v01[kSize], v02[kSize];
  auto fill = [&](double t, int degree, auto&& store) {
    double p2 = 0.0, p1 = 0.0, p0 = 1.0;  // t^(e-2), t^(e-1), t^e
    for (int e = 0; e <= degree; ++e) {
      store(e, p0, p1, p2);
      p2 = p1;
      p1 = p0;
      p0 *= t;
    }
  };
  fill(x[0], poly.max_degree[0], [&](int e, double p0, double p1, double p2) {
    u01[e] = pair(p0, p1);
    u10[e] = pair(p1, p0);
    u20[e] = pair(p2, p0);
  });
  fill(x[1], poly.max_degree[1], [&](int e, double p0, double p1, double p2) {
    v01[e] = pair(p0, p1);
    v02[e] = pair(p0, p2);
  });
  const std::size_t num_outputs = poly.first.size() - 1;
  for (std::size_t k = 0; k < num_outputs; ++k) {
    Pair vh = pair(0.0, 0.0), g = vh, h = vh;
    for (std::uint32_t t = poly.first[k]; t < poly.first[k + 1]; ++t) {
      const Monomial& m = poly.terms[t];
      const int a = m.e[0], b = m.e[1];
      Pair c0, c1, c2;  // (loaded straight from the term; a local array would go through the stack)
      std::memcpy(&c0, m.pairs.data(), sizeof c0);
      std::memcpy(&c1, m.pairs.data() + 2, sizeof c1);
      std::memcpy(&c2, m.pairs.data() + 4, sizeof c2);
      vh += c0 * (u01[a] * v01[b]);
      g += c1 * (u10[a] * v01[b]);
      h += c2 * (u20[a] * v02[b]);
    }
    Jet2<2>& r = out[k];
    r.v = vh[0];
    r.g = {g[0], g[1]};
    r.h = {{{h[0], vh[1]}, {vh[1], h[1]}}};
  }
}

}  // namespace

template <int N>
void polynomial_jets2(const PolynomialForm& poly, const double* x, Jet2<N>* out) {
  if constexpr (N == 2)
    polynomial_jets2_uv(poly, x, out);
  else
    polynomial_jets2_any<N>(poly, x, out);
}

template <int N>
bool polynomial_ball_jets1(const PolynomialForm& poly, const double* x, BallJet1<N>* out) {
  constexpr double kU = 0x1p-53, kSmallest = 0x1p-1000;
  bool tiny = false;  // a nonzero product below 2^-1000 (or one that underflowed to 0)
  const auto times = [&tiny](double a, double b) {
    const double r = a * b;
    tiny = tiny || (std::abs(r) < kSmallest && a != 0.0 && b != 0.0);
    return r;
  };
  // pw[i][1 + e] = x_i^e for e >= 0, pw[i][0] = 0 (the exponent -1 of a derivative of x^0)
  double pw[N][PolynomialForm::kMaxDegree + 2];
  for (int i = 0; i < N; ++i) {
    pw[i][0] = 0.0;
    pw[i][1] = 1.0;
    for (int e = 1; e <= poly.max_degree[i]; ++e) pw[i][1 + e] = times(pw[i][e], x[i]);
  }
  const std::size_t num_outputs = poly.first.size() - 1;
  for (std::size_t k = 0; k < num_outputs; ++k) {
    // value and gradient: the computed sum, the sum of the terms' magnitudes, the coefficients'
    // errors times the monomials' magnitudes
    double v = 0.0, v_mag = 0.0, v_err = 0.0;
    std::array<double, N> g{}, g_mag{}, g_err{};
    int factors = 0;
    const std::uint32_t begin = poly.first[k], end = poly.first[k + 1];
    for (std::uint32_t t = begin; t < end; ++t) {
      const Monomial& m = poly.terms[t];
      int degree = 0;
      double mono = 1.0;  // x^a y^b z^d
      for (int i = 0; i < N; ++i) {
        mono = times(mono, pw[i][1 + m.e[i]]);
        degree += m.e[i];
      }
      factors = std::max(factors, degree + N + 2);
      const double term = times(m.c, mono);
      v += term;
      v_mag += std::abs(term);
      v_err += m.c_error * std::abs(mono);
      for (int j = 0; j < N; ++j) {
        if (m.e[j] == 0) continue;
        // c e_j x_j^(e_j - 1) times the other powers; the coefficient c e_j rounded once more
        double d = 1.0;
        for (int i = 0; i < N; ++i) d = times(d, pw[i][i == j ? m.e[i] : 1 + m.e[i]]);
        const double ce = times(m.c, m.e[j]);
        const double dt = times(ce, d);
        g[j] += dt;
        g_mag[j] += std::abs(dt);
        g_err[j] += (m.e[j] * m.c_error + kU * std::abs(ce)) * std::abs(d);
      }
    }
    // (the error terms' own products may underflow: at most ball.hpp's η each)
    const double n = static_cast<double>(end - begin);
    const double rel = 1.25 * (n + factors + 2) * kU, underflows = 2.0 * n * ball::kEta;
    BallJet1<N>& o = out[k];
    o.v = {v, ball::inflate(rel * v_mag + 1.25 * v_err) + underflows};
    for (int j = 0; j < N; ++j) o.g[j] = {g[j], ball::inflate(rel * g_mag[j] + 1.25 * g_err[j]) + underflows};
    o.defined = o.differentiable = true;
    bool finite = std::isfinite(o.v.mid) && std::isfinite(o.v.rad);
    for (int j = 0; j < N; ++j) finite = finite && std::isfinite(o.g[j].mid) && std::isfinite(o.g[j].rad);
    if (!finite || tiny) return false;
  }
  return true;
}

template bool polynomial_ball_jets1<1>(const PolynomialForm&, const double*, BallJet1<1>*);
template bool polynomial_ball_jets1<2>(const PolynomialForm&, const double*, BallJet1<2>*);
template bool polynomial_ball_jets1<3>(const PolynomialForm&, const double*, BallJet1<3>*);

template void polynomial_jets2<1>(const PolynomialForm&, const double*, Jet2<1>*);
template void polynomial_jets2<2>(const PolynomialForm&, const double*, Jet2<2>*);
template void polynomial_jets2<3>(const PolynomialForm&, const double*, Jet2<3>*);

}  // namespace footpoint::formula
