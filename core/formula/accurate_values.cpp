// Program::accurate_values: the formulas' values at a point to about the rounding of the result
// itself, for the certificates and the refinement of foot points where a curve's equations are
// ill-conditioned (two nearly tangent surfaces: the foot point moves by the residual's rounding
// divided by the sine of the angle between them).
//
// Every node is a double-double value with a radius: a triple (h, l, r) standing for every real
// within r of the exact sum h + l, |l| <= u |h|. The error-free transformations
//   TwoSum(a, b) = (s, e), s = fl(a + b), s + e = a + b exactly     (D. E. Knuth, The Art of
//       Computer Programming, vol. 2, 3rd ed., 1998, Section 4.2.2, Theorem B),
//   TwoProduct(a, b) = (p, e), p = fl(a b), e = fma(a, b, -p), p + e = a b exactly unless the
//       product underflows      (T. Ogita, S. M. Rump, S. Oishi, "Accurate sum and dot product",
//       SIAM J. Sci. Comput. 26 (2005) 1955-1988, Algorithm 3.5),
// give the leading part exactly; what is left is a sum of a few small terms computed in floating
// point, whose rounding error (Higham's γ_k bound for k operations, γ_k <= 1.01 k u here) is added
// to the radius, as are the operands' radii propagated as in ball.hpp's midpoint-radius rules:
//   a ± b:   (s, e) = TwoSum(ha, ±hb), t = (la ± lb) + e,  error <= γ2 (|la| + |lb| + |e|)
//   a × b:   (p, e) = TwoProduct(ha, hb), t = ((ha lb + la hb) + la lb) + e,
//            error <= γ4 (|ha lb| + |la hb| + |la lb| + |e|) + 4η (the small products may underflow),
//            propagated |a| rb + ra |b| + ra rb with |a| <= |ha| + |la|
//   a / k:   q = fl(ha / k), ρ = fma(-q, k, ha) (exact: the remainder of a correctly rounded
//            quotient is representable), t = (ρ + la) / k, error <= γ2 (|ρ| + |la|) / |k| + 2η,
//            propagated ra / |k|
// and (h, l) = TwoSum of the exact part and t, so that |l| <= u |h| again. Radii are computed in
// round to nearest and raised by ball::inflate (ball.hpp), which covers up to 16 roundings.
// The result of formula k is the ball {fl(h + l), r + u |fl(h + l)| + η}: its radius is the
// rounding of the value itself plus O(u^2) of the magnitudes met on the way, where plain ball
// arithmetic has O(u) of them.
// Only the operations of polynomials are evaluated so (constants, variables, +, -, *, integer
// powers >= 0, products and quotients by constants); for any other operation, or where a value
// leaves the range in which TwoProduct is exact (a product or quotient of nonzero values below
// 2^-960, or anything not finite), false is returned.
#include <cmath>
#include <vector>

#include "formula/ball.hpp"
#include "formula/program.hpp"
#include "formula/tape.hpp"

namespace footpoint::formula {

namespace {

using ball::inflate;
using ball::kEta;
using ball::kU;

// 1.01 k u, Higham's γ_k for k u <= 2^-40, rounded up to a multiple of u.
constexpr double kGamma2 = 3.0 * kU;
constexpr double kGamma4 = 5.0 * kU;
// Products below this in magnitude (nonzero) may have an error TwoProduct cannot represent.
constexpr double kTiny = 0x1p-960;

struct Accurate {
  double h = 0.0, l = 0.0;  // the value h + l
  double r = 0.0;           // radius about h + l
};

struct Pair {
  double s, e;
};

Pair two_sum(double a, double b) {
  const double s = a + b;
  const double bb = s - a;
  return {s, (a - (s - bb)) + (b - bb)};
}

Pair two_product(double a, double b) {
  const double p = a * b;
  return {p, std::fma(a, b, -p)};
}

class Evaluator {
 public:
  bool ok = true;

  Accurate add(const Accurate& a, const Accurate& b) {
    const Pair se = two_sum(a.h, b.h);
    const double t = (a.l + b.l) + se.e;
    const Pair hl = two_sum(se.s, t);
    return {hl.s, hl.e, inflate(a.r + b.r + kGamma2 * (std::abs(a.l) + std::abs(b.l) + std::abs(se.e)))};
  }

  static Accurate neg(const Accurate& a) { return {-a.h, -a.l, a.r}; }

  Accurate mul(const Accurate& a, const Accurate& b) {
    const Pair pe = two_product(a.h, b.h);
    if (std::abs(pe.s) < kTiny && a.h != 0.0 && b.h != 0.0) ok = false;
    const double hl = a.h * b.l, lh = a.l * b.h, ll = a.l * b.l;
    const double t = ((hl + lh) + ll) + pe.e;
    const Pair out = two_sum(pe.s, t);
    const double size_a = std::abs(a.h) + std::abs(a.l), size_b = std::abs(b.h) + std::abs(b.l);
    return {out.s, out.e,
            inflate(size_a * b.r + a.r * size_b + a.r * b.r +
                    kGamma4 * (std::abs(hl) + std::abs(lh) + std::abs(ll) + std::abs(pe.e)) + 4.0 * kEta)};
  }

  Accurate div(const Accurate& a, double k) {
    if (!(k != 0.0) || !std::isfinite(k)) {
      ok = false;
      return {};
    }
    const double q = a.h / k;
    if (std::abs(q) < kTiny && a.h != 0.0) ok = false;
    const double rho = std::fma(-q, k, a.h);
    const double t = (rho + a.l) / k;
    const Pair out = two_sum(q, t);
    const double k_abs = std::abs(k);
    return {out.s, out.e,
            inflate(a.r / k_abs + kGamma2 * (std::abs(rho) + std::abs(a.l)) / k_abs + 2.0 * kEta)};
  }

  Accurate power(const Accurate& a, double k) {
    if (!(k >= 0.0) || k != std::floor(k) || k > 1024.0) {
      ok = false;
      return {};
    }
    // Binary powering: a^k as products of repeated squares.
    Accurate result{1.0, 0.0, 0.0};
    Accurate square = a;
    for (auto n = static_cast<unsigned>(k); n > 0; n >>= 1) {
      if (n & 1U) result = mul(result, square);
      if (n > 1) square = mul(square, square);
    }
    return result;
  }
};

}  // namespace

bool Program::accurate_values(const double* x, Ball* out) const {
  const Tape& tape = *tape_;
  thread_local std::vector<Accurate> regs;
  if (regs.size() < tape.nodes.size()) regs.resize(tape.nodes.size());
  Evaluator ev;
  for (std::size_t i = 0; i < tape.nodes.size() && ev.ok; ++i) {
    const Node& n = tape.nodes[i];
    const auto at = [&](std::int32_t j) -> const Accurate& { return regs[static_cast<std::size_t>(j)]; };
    switch (n.op) {
      case Op::constant:
        regs[i] = {n.k, 0.0, 0.0};
        break;
      case Op::variable:
        regs[i] = {x[static_cast<int>(n.k)], 0.0, 0.0};
        break;
      case Op::add:
        regs[i] = ev.add(at(n.a), at(n.b));
        break;
      case Op::sub:
        regs[i] = ev.add(at(n.a), Evaluator::neg(at(n.b)));
        break;
      case Op::mul:
        regs[i] = ev.mul(at(n.a), at(n.b));
        break;
      case Op::neg:
        regs[i] = Evaluator::neg(at(n.a));
        break;
      case Op::add_k:
        regs[i] = ev.add(at(n.a), {n.k, 0.0, 0.0});
        break;
      case Op::rsub_k:
        regs[i] = ev.add({n.k, 0.0, 0.0}, Evaluator::neg(at(n.a)));
        break;
      case Op::mul_k:
        regs[i] = ev.mul(at(n.a), {n.k, 0.0, 0.0});
        break;
      case Op::div_k:
        regs[i] = ev.div(at(n.a), n.k);
        break;
      case Op::pow_int:
        regs[i] = ev.power(at(n.a), n.k);
        break;
      default:
        return false;
    }
    const Accurate& v = regs[i];
    if (!std::isfinite(v.h) || !std::isfinite(v.l) || !std::isfinite(v.r)) return false;
  }
  if (!ev.ok) return false;
  for (int k = 0; k < num_outputs(); ++k) {
    const Accurate& v = regs[static_cast<std::size_t>(tape.outputs[static_cast<std::size_t>(k)])];
    const double mid = v.h + v.l;
    out[k] = {mid, inflate(v.r + kU * std::abs(mid) + kEta)};
  }
  return true;
}

}  // namespace footpoint::formula
