// Formulas that are sums of monomials, evaluated term by term. Internal to core/formula.
//
// Polynomial surfaces are written as sums of monomials (the hybrid paper's Example 2:
// u^6 + u^5*v + ... + 1). On the tape such a formula is a long chain of pow_int, mul and add nodes;
// its second-order jet is cheaper computed per monomial c x^a y^b z^d straight from a table of
// powers: the value c x^a y^b z^d, the gradient c a x^(a-1) y^b z^d, ..., the Hessian
// c a (a-1) x^(a-2) y^b z^d, c a b x^(a-1) y^(b-1) z^d, ... (exact to rounding, no dependency
// between terms). Nothing is expanded: a formula qualifies only if the tape's additions already
// form a chain of single terms ((t1 + t2) + t3 ...; a product or a constant multiple of a sum
// does not qualify), so the terms are summed in the tape's own order and the result keeps the
// tape's accuracy (summing in another order, or distributing a product over a sum, can lose
// digits to cancellation that the written formula does not have).
#pragma once
#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "formula/ball.hpp"
#include "formula/jet.hpp"

namespace footpoint::formula {

struct Monomial {
  double c = 0.0;  // coefficient
  // |c - the exact coefficient| at most: the tape's constants are exact, each operation that
  // folded them into c (a product, 1/k, a power) rounded once more (ball jets need it).
  double c_error = 0.0;
  std::array<std::int16_t, 3> e{};             // exponent of each variable
  std::array<double, 3> ce{};                  // c e_j: the gradient's coefficients
  std::array<std::array<double, 3>, 3> cee{};  // c e_j e_k (j != k), c e_j (e_j - 1): the Hessian's
  // With two variables, the coefficients in the pairs the evaluation multiplies:
  // (c, c e_0 e_1), (c e_0, c e_1), (c e_0 (e_0 - 1), c e_1 (e_1 - 1)).
  alignas(16) std::array<double, 6> pairs{};
};

struct PolynomialForm {
  static constexpr int kMaxDegree = 64;  // per variable; higher powers stay on the tape
  static constexpr std::size_t kMaxTerms = 4096;
  std::vector<Monomial> terms;  // the terms of formula k: [first[k], first[k+1])
  std::vector<std::uint32_t> first;
  std::array<int, 3> max_degree{};  // highest exponent of each variable
  std::size_t memory_bytes() const { return terms.capacity() * sizeof(Monomial) + first.capacity() * 4; }
};

// Second-order jets of every formula (N = the number of variables).
template <int N>
void polynomial_jets2(const PolynomialForm& poly, const double* x, Jet2<N>* out);

// Ball jets of every formula (ball.hpp's contract: the exact value and gradient at x lie in the
// balls), term by term. Each term c x^a y^b z^d is a product of at most K = a + b + d + N + 1
// correctly rounded factors, so it is within γ_K of the exact product of c and the powers; the
// sum of n terms in the tape's order adds γ_(n-1) of the sum of their magnitudes S (N. J.
// Higham, Accuracy and Stability of Numerical Algorithms, 2nd ed., SIAM 2002, Sections 3.1 and
// 4.2); the coefficients' own errors add Σ c_error |x^a y^b z^d|. With γ_j <= 1.01 j u here
// (j u <= 2^-40), radius = inflate(1.25 (n + K + 2) u S + 1.25 Σ c_error |monomial|) covers
// all of it. The relative model needs every product to stay a normal number: false (nothing
// written) when a nonzero product falls below 2^-1000 or anything overflows, and the tape's own
// ball arithmetic is used instead.
template <int N>
bool polynomial_ball_jets1(const PolynomialForm& poly, const double* x, BallJet1<N>* out);

}  // namespace footpoint::formula
