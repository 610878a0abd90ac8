// Program::invariant_translations: the translations of the inputs that leave every formula
// unchanged, read from the tape's structure (no sampling decides).
//
// The argument, by induction over the tape (nodes refer only to earlier ones). Every node is
// classed as
//  - affine: a(x) = c + γ·x, built from the inputs and constants by +, -, negation and
//    multiplication or division by a constant; then a(x + δ) = a(x) + γ·δ exactly;
//  - general: anything else; claimed invariant, n(x + δ) = n(x).
// A general node is an operation on earlier nodes. Its general operands are invariant by
// induction; each affine operand must be invariant too, γ·δ = 0 (a "zero" constraint on δ),
// except as the argument of a periodic function: sin and cos need γ·δ ∈ 2πℤ, tan γ·δ ∈ πℤ (a
// "period" constraint). An affine output needs γ·δ = 0. A δ that meets every constraint leaves
// every node invariant, hence every formula: f(x + δ) = f(x) in real arithmetic, the undefined
// points included (the same operations on the same values). The converse does not hold: the rule
// misses symmetries it cannot read (cos(u)^2 has period π; it finds 2π), never claims one that is
// not there.
//
// The constraints solved: the zero constraints leave a subspace V of dimension n - rank. In V the
// period constraints define a lattice; it is enumerated within the extents asked for, each
// candidate checked against every constraint to rounding level (|q - round(q)| <= 1e-12 |q| for
// q = γ·δ / period). The candidates come from the constraints themselves: along a line (dim V =
// 1), the least common multiple of the constraints' periods (a common multiple of up to 64 times
// the first); in the plane (dim V = 2), integer combinations of the lattice of two independent
// constraints. A direction along which every formula is constant (dim V >= 1 with no period
// constraint across it) is a continuous symmetry: no lattice, none reported.
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "formula/program.hpp"
#include "formula/tape.hpp"

namespace footpoint::formula {

namespace {

constexpr int kMaxInputs = 2;
using Vec = std::array<double, kMaxInputs>;

struct Form {
  bool affine = false;
  Vec gamma{};  // the coefficients of the inputs, when affine
};

struct Constraint {
  Vec gamma;
  double period;  // 0: γ·δ = 0; else γ·δ ∈ period ℤ
};

double dot(const Vec& a, const Vec& b) { return a[0] * b[0] + a[1] * b[1]; }
double length(const Vec& a) { return std::hypot(a[0], a[1]); }
bool nonzero(const Vec& a) { return a[0] != 0.0 || a[1] != 0.0; }

// q within rounding of an integer (q itself not zero unless asked).
bool near_integer(double q) { return std::abs(q - std::round(q)) <= 1e-12 * std::max(1.0, std::abs(q)); }

// The constraints on δ; false when a node's kind is not known to this rule (then no δ is claimed).
bool collect(const Program::Tape& tape, std::vector<Constraint>& out) {
  std::vector<Form> form(tape.nodes.size());
  auto zero = [&](std::int32_t i) {
    if (i >= 0 && form[static_cast<std::size_t>(i)].affine &&
        nonzero(form[static_cast<std::size_t>(i)].gamma))
      out.push_back({form[static_cast<std::size_t>(i)].gamma, 0.0});
  };
  for (std::size_t i = 0; i < tape.nodes.size(); ++i) {
    const Node& n = tape.nodes[i];
    const auto operand = [&](std::int32_t k) -> const Form& { return form[static_cast<std::size_t>(k)]; };
    Form& f = form[i];
    switch (n.op) {
      case Op::constant:
        f.affine = true;
        break;
      case Op::variable:
        f.affine = true;
        f.gamma[static_cast<std::size_t>(n.k)] = 1.0;
        break;
      case Op::add:
      case Op::sub:
        if (operand(n.a).affine && operand(n.b).affine) {
          const double sign = n.op == Op::add ? 1.0 : -1.0;
          f.affine = true;
          for (int k = 0; k < kMaxInputs; ++k)
            f.gamma[k] = operand(n.a).gamma[k] + sign * operand(n.b).gamma[k];
        } else {
          zero(n.a);
          zero(n.b);
        }
        break;
      case Op::neg:
      case Op::add_k:
      case Op::rsub_k:
      case Op::mul_k:
      case Op::div_k:
        if (operand(n.a).affine) {
          const double scale = n.op == Op::neg || n.op == Op::rsub_k ? -1.0
                               : n.op == Op::mul_k                   ? n.k
                               : n.op == Op::div_k                   ? 1.0 / n.k
                                                                     : 1.0;
          // γ/k is kept as γ·(1/k), within rounding of it: the checks' tolerance allows for it
          f.affine = std::isfinite(scale);
          for (int k = 0; k < kMaxInputs; ++k) f.gamma[k] = scale * operand(n.a).gamma[k];
          if (!f.affine) zero(n.a);
        }
        break;
      case Op::sin:
      case Op::cos:
      case Op::tan:
        if (operand(n.a).affine && nonzero(operand(n.a).gamma))
          out.push_back({operand(n.a).gamma, n.op == Op::tan ? std::numbers::pi : 2.0 * std::numbers::pi});
        break;
      case Op::pow:
        return false;  // not on a built tape
      default:         // every other operation: its affine operands must not move
        zero(n.a);
        zero(n.b);
        zero(n.c);
        break;
    }
  }
  for (std::int32_t o : tape.outputs) zero(o);
  return true;
}

// The least t > 0 with t·c_i ∈ period_i ℤ for every (c_i, period_i), c_i != 0; 0 if none within 64
// multiples of the first constraint's period.
double common_period(const std::vector<std::array<double, 2>>& steps) {
  // steps: {c_i, period_i}; t must be a multiple of τ_i = period_i / |c_i|
  const double first = steps[0][1] / std::abs(steps[0][0]);
  for (int m = 1; m <= 64; ++m) {
    const double t = m * first;
    bool all = true;
    for (const auto& s : steps) all = all && near_integer(t * s[0] / s[1]);
    if (all) return t;
  }
  return 0.0;
}

}  // namespace

std::vector<std::vector<double>> Program::invariant_translations(const std::vector<double>& extent,
                                                                 std::size_t max_count) const {
  const int n = tape_->num_inputs;
  if (n < 1 || n > kMaxInputs || static_cast<int>(extent.size()) != n) return {};
  std::vector<Constraint> constraints;
  if (!collect(*tape_, constraints)) return {};
  auto meets_all = [&](const Vec& delta) {
    for (const Constraint& c : constraints) {
      const double q = dot(c.gamma, delta);
      if (c.period == 0.0 ? std::abs(q) > 1e-12 * length(c.gamma) * length(delta)
                          : !near_integer(q / c.period))
        return false;
    }
    return true;
  };
  auto parallel = [](const Vec& a, const Vec& b) {
    return std::abs(a[0] * b[1] - a[1] * b[0]) <= 1e-12 * length(a) * length(b);
  };
  // the candidates, each lexicographically positive and within the extents
  std::vector<Vec> found;
  auto consider = [&](const Vec& delta) {
    const bool positive = delta[0] > 0.0 || (delta[0] == 0.0 && delta[1] > 0.0);
    for (int k = 0; k < n; ++k)
      if (!(std::abs(delta[k]) < extent[static_cast<std::size_t>(k)])) return;
    if (positive && meets_all(delta)) found.push_back(delta);
  };
  // V: the inputs' space less the zero constraints' directions
  std::vector<Vec> zeros;
  for (const Constraint& c : constraints)
    if (c.period == 0.0) zeros.push_back(c.gamma);
  Vec line{};  // V's direction when it is a line
  int dim_v = n;
  if (!zeros.empty()) {
    dim_v = n - 1;
    for (const Vec& z : zeros)
      if (!parallel(z, zeros[0])) dim_v = n - 2;
    if (dim_v == 1) line = {-zeros[0][1], zeros[0][0]};
  } else if (n == 1) {
    line = {1.0, 0.0};
  }
  if (dim_v <= 0) return {};
  if (n == 1 || dim_v == 1) {
    if (n == 1) line = {1.0, 0.0};
    const double scale = std::max(std::abs(line[0]), std::abs(line[1]));
    line = {line[0] / scale, line[1] / scale};
    if (line[0] < 0.0 || (line[0] == 0.0 && line[1] < 0.0)) line = {-line[0], -line[1]};
    std::vector<std::array<double, 2>> steps;
    for (const Constraint& c : constraints)
      if (c.period != 0.0 && std::abs(dot(c.gamma, line)) > 1e-12 * length(c.gamma) * length(line))
        steps.push_back({dot(c.gamma, line), c.period});
    if (steps.empty()) return {};  // constant along the line: a continuous symmetry
    const double t = common_period(steps);
    if (t == 0.0) return {};
    for (int k = 1; found.size() < max_count; ++k) {
      const Vec delta{k * t * line[0], k * t * line[1]};
      const std::size_t before = found.size();
      consider(delta);
      if (found.size() == before) break;  // beyond the extents
    }
  } else {  // a plane: two independent period constraints span the lattice's candidates
    const Constraint* a = nullptr;
    const Constraint* b = nullptr;
    for (const Constraint& c : constraints) {
      if (!a) {
        a = &c;
      } else if (!b && !parallel(a->gamma, c.gamma)) {
        b = &c;
      }
    }
    if (!b) return {};  // constant across a's direction: a continuous symmetry
    // e1, e2 with γa·e1 = Pa, γb·e1 = 0, γa·e2 = 0, γb·e2 = Pb (Cramer)
    const double det = a->gamma[0] * b->gamma[1] - a->gamma[1] * b->gamma[0];
    const Vec e1{a->period * b->gamma[1] / det, -a->period * b->gamma[0] / det};
    const Vec e2{-b->period * a->gamma[1] / det, b->period * a->gamma[0] / det};
    // |m| Pa = |γa·δ| <= |γa|_1 max extent, and the same for n
    auto reach = [&](const Constraint* c) {
      const double r = (std::abs(c->gamma[0]) * extent[0] + std::abs(c->gamma[1]) * extent[1]) / c->period;
      return static_cast<int>(std::min(r, 64.0));
    };
    const int mm = reach(a), nn = reach(b);
    for (int m = -mm; m <= mm; ++m)
      for (int k = -nn; k <= nn; ++k)
        if (m != 0 || k != 0) consider({m * e1[0] + k * e2[0], m * e1[1] + k * e2[1]});
  }
  std::sort(found.begin(), found.end(), [](const Vec& x, const Vec& y) {
    return length(x) != length(y) ? length(x) < length(y) : x < y;  // ties: lexicographic
  });
  if (found.size() > max_count) found.resize(max_count);
  std::vector<std::vector<double>> result;
  for (const Vec& d : found) result.emplace_back(d.begin(), d.begin() + n);
  return result;
}

}  // namespace footpoint::formula
