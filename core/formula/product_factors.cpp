// The factors at the top of a formula's product: Program::square_free takes every repeated one
// once, Program::factor_systems splits the curve into the curves of the factors.
//
// Formula k is read from its output node down through the operations that multiply: a product
// a * b, a negation -a, a constant multiple or quotient a * c, a / c (c finite and nonzero) and an
// integer power a^m (m >= 1). What they multiply are its factors g_1, ..., g_r (any other node; a
// finite nonzero constant is dropped), so that f = c g_1^m_1 ... g_r^m_r with c finite and
// nonzero. Where formula k has a power m >= 2 or the same factor (the same tape node: common
// subexpressions are shared) twice, it is replaced by the product g_1 ... g_r of its distinct
// factors. At every x:
//  - the new formula is defined exactly where the old one is (both need every g_i defined, and
//    an integer power, a product, a negation or a constant multiple of defined values is defined);
//  - it vanishes exactly where the old one does (a product of real numbers vanishes iff a factor
//    does, and c != 0).
// So the zero set is the same set of points. Where f vanishes to order m_i >= 2 on {g_i = 0}, the
// square-free product vanishes to first order there: (x^2 + y^2 - 1)^2, singular at every point of
// its circle (∇f = 0), becomes the regular circle x^2 + y^2 - 1. Repeated factors that are not
// the same node ((x - 1) (1 - x)) are not recognised: that formula stays as written.
#include <algorithm>
#include <cmath>
#include <vector>

#include "formula/program.hpp"
#include "formula/tape.hpp"

namespace footpoint::formula {

namespace {

bool finite_nonzero(double k) { return std::isfinite(k) && k != 0.0; }

// The factors of node `root`, left to right; `repeated` is set when a power m >= 2 or a factor met
// twice shows the formula is not square-free. An explicit stack: a product of a formula's length
// is a chain of thousands of nodes.
void factors(const Program::Tape& tape, std::int32_t root, std::vector<std::int32_t>& out, bool& repeated) {
  std::vector<std::int32_t> pending{root};
  while (!pending.empty()) {
    const std::int32_t i = pending.back();
    pending.pop_back();
    const Node& n = tape.nodes[static_cast<std::size_t>(i)];
    switch (n.op) {
      case Op::mul:
        pending.push_back(n.b);
        pending.push_back(n.a);
        continue;
      case Op::neg:
        pending.push_back(n.a);
        continue;
      case Op::mul_k:
      case Op::div_k:
        if (finite_nonzero(n.k)) {
          pending.push_back(n.a);
          continue;
        }
        break;
      case Op::pow_int:
        if (n.k >= 1.0) {
          if (n.k >= 2.0) repeated = true;
          pending.push_back(n.a);
          continue;
        }
        break;
      case Op::constant:
        if (finite_nonzero(n.k)) continue;
        break;
      default:
        break;
    }
    if (std::find(out.begin(), out.end(), i) != out.end())
      repeated = true;
    else
      out.push_back(i);
  }
}

// True when every node below `root` is an operation defined at every real input: a polynomial's
// (+, -, *, constant multiples and quotients, integer powers >= 0) and exp, sin, cos, atan, sinh,
// cosh, tanh, asinh, abs, min, max of such.
bool defined_everywhere(const Program::Tape& tape, std::int32_t root) {
  std::vector<bool> seen(tape.nodes.size(), false);
  std::vector<std::int32_t> pending{root};
  while (!pending.empty()) {
    const std::int32_t i = pending.back();
    pending.pop_back();
    if (i < 0 || seen[static_cast<std::size_t>(i)]) continue;
    seen[static_cast<std::size_t>(i)] = true;
    const Node& n = tape.nodes[static_cast<std::size_t>(i)];
    switch (n.op) {
      case Op::constant:
        if (!std::isfinite(n.k)) return false;
        break;
      case Op::div_k:
        if (!finite_nonzero(n.k)) return false;
        break;
      case Op::pow_int:
        if (n.k < 0.0) return false;
        break;
      case Op::variable:
      case Op::add:
      case Op::sub:
      case Op::mul:
      case Op::neg:
      case Op::add_k:
      case Op::mul_k:
      case Op::rsub_k:
      case Op::exp:
      case Op::sin:
      case Op::cos:
      case Op::atan:
      case Op::sinh:
      case Op::cosh:
      case Op::tanh:
      case Op::asinh:
      case Op::abs:
      case Op::min:
      case Op::max:
        break;
      default:
        return false;
    }
    pending.push_back(n.a);
    pending.push_back(n.b);
    pending.push_back(n.c);
  }
  return true;
}

// The tape computing `outputs` from `tape`'s nodes, pruned, with its polynomial form.
Program::Tape with_outputs(const Program::Tape& tape, std::vector<std::int32_t> outputs) {
  Program::Tape t = tape;
  t.outputs = std::move(outputs);
  Program::Tape reduced = live_part(t);
  reduced.polynomial = polynomial_form(reduced);
  return reduced;
}

}  // namespace

std::vector<Program> Program::factor_systems(std::size_t max_systems) const {
  // The factors each formula splits into: its distinct factors when all are defined everywhere
  // and there are at most max_systems of them, else the formula itself.
  std::vector<std::vector<std::int32_t>> split;
  std::size_t systems = 1;
  for (const std::int32_t output : tape_->outputs) {
    std::vector<std::int32_t> distinct;
    bool repeated = false;
    factors(*tape_, output, distinct, repeated);
    bool total = !distinct.empty() && distinct.size() <= max_systems;
    for (const std::int32_t g : distinct) total = total && defined_everywhere(*tape_, g);
    if (!total) distinct.assign(1, output);
    systems *= distinct.size();
    split.push_back(std::move(distinct));
  }
  if (systems <= 1 || systems > max_systems) return {square_free()};
  std::vector<Program> out;
  std::vector<std::size_t> choice(split.size(), 0);  // one factor of each formula, odometer order
  for (std::size_t s = 0; s < systems; ++s) {
    std::vector<std::int32_t> outputs;
    for (std::size_t k = 0; k < split.size(); ++k) outputs.push_back(split[k][choice[k]]);
    Program p;
    p.tape_ = std::make_shared<const Tape>(with_outputs(*tape_, std::move(outputs)));
    out.push_back(std::move(p));
    for (std::size_t k = split.size(); k-- > 0;) {
      if (++choice[k] < split[k].size()) break;
      choice[k] = 0;
    }
  }
  return out;
}

Program Program::square_free() const {
  Tape tape = *tape_;
  bool changed = false;
  for (std::int32_t& output : tape.outputs) {
    std::vector<std::int32_t> distinct;
    bool repeated = false;
    factors(tape, output, distinct, repeated);
    if (!repeated || distinct.empty()) continue;
    std::int32_t product = distinct.front();
    for (std::size_t i = 1; i < distinct.size(); ++i) {
      tape.nodes.push_back({Op::mul, product, distinct[i], -1, 0.0});
      product = static_cast<std::int32_t>(tape.nodes.size() - 1);
    }
    output = product;
    changed = true;
  }
  if (!changed) return *this;
  Program p;
  p.tape_ = std::make_shared<const Tape>(with_outputs(tape, tape.outputs));
  return p;
}

}  // namespace footpoint::formula
