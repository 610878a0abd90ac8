// Rigorous lower bounds on the distance from a point p to a parametric surface (N = 2) or curve
// (N = 1) over a parameter box B, from a BoxEnclosure of B (parametric/geometry/box_enclosure.hpp):
//
//  - zero order: the distance from p to the box holding s(B);
//  - second order, from one point q of B with s(q), ∂s(q) enclosed (PointEnclosure): for
//    f(t) = ½|s(t) - p|^2, Taylor's theorem on the segment from q to t (inside B, B convex) gives
//      f(q + δ) = f(q) + ∇f(q)·δ + ½ δᵀ ∇²f(ξ) δ,
//      ∇f = Jᵀ (s - p),   ∇²f = JᵀJ + Σ_k (s_k - p_k) ∇²s_k,
//    and with the entries of ∇²f enclosed over B (HessianBounds: a lower bound of each diagonal
//    entry, an interval for the off-diagonal one), δᵀ ∇²f(ξ) δ >= Σ_i h_ii δ_i^2 + 2 h_01 δ_0 δ_1
//    where h_01 is the interval's lower end where δ_0 δ_1 >= 0 and its upper end where
//    δ_0 δ_1 <= 0. In each quadrant of δ around q (where also the gradient's enclosure has its worst
//    sign) the right side is a fixed quadratic, whose minimum over the quadrant's rectangle is
//    bounded from below exactly (quadratic_lower_bound). Where q is the minimiser of f and ∇²f
//    is positive definite on B, the bound is f(q) less the rounding: the certificate of a foot
//    point. Where q is any other point (a cell's centre), it bounds the cell from below.
//
// Rounding. The enclosures are rigorous; the arithmetic combining them here is in round to
// nearest, and each bound is lowered by a bound on its own rounding: every quantity below is a
// sum of at most a few dozen products of enclosed numbers, whose computed value is within
// 64 u (the sum of the magnitudes of its terms) of the exact one (N. J. Higham, Accuracy and
// Stability of Numerical Algorithms, 2nd ed., SIAM 2002, Section 3.1, γ_n with n <= 32).
#pragma once
#include <array>
#include <cstddef>
#include <limits>
#include <type_traits>
#include <vector>

#include "geometry/vec.hpp"
#include "parametric/geometry/box_enclosure.hpp"
#include "parametric/geometry/params.hpp"

namespace footpoint {

// The relative rounding allowance of a computed bound (see above): 64 u.
inline constexpr double kBoundRounding = 64.0 * 0x1p-53;

// A lower bound of the squared distance from p to the box s_mid ± s_rad.
double box_distance2_lower(const Vec3& s_mid, const Vec3& s_rad, const Vec3& p);

// ∇²f over a box: h_ii >= diagonal_lo[i]; off_lo <= h_01 <= off_hi (N = 2). Not `valid` unless
// the enclosure is smooth.
template <int N>
struct HessianBounds {
  std::array<double, N> diagonal_lo{};
  double off_lo = 0.0, off_hi = 0.0;
  bool valid = false;
  // A lower bound of the smallest eigenvalue of every matrix these entries allow (-inf if not
  // valid): the smallest eigenvalue of [a b; b c] grows with a and c and falls with |b|.
  double smallest_eigenvalue() const;
};
template <int N>
HessianBounds<N> hessian_bounds(const BoxEnclosure<N>& box, const Vec3& p);

// f(q) and ∇f(q) enclosed: f(q) >= f_lo, and |∇f(q)_i - g_i| <= g_rad_i.
template <int N>
struct GradientEnclosure {
  double f_lo = 0.0;
  std::array<double, N> g{}, g_rad{};
};
template <int N>
GradientEnclosure<N> enclose_gradient(const PointEnclosure<N>& q, const Vec3& p);

// A lower bound of f over the box [lo, hi], which holds q: the second-order form above.
// -inf where the Hessian bounds are not valid. A bound of at least `enough` is returned as soon as
// one is found (the separable bound with the smallest eigenvalue is tried first).
template <int N>
double second_order_lower_bound(const GradientEnclosure<N>& at_q, const Params<N>& q, const Params<N>& lo,
                                const Params<N>& hi, const HessianBounds<N>& hessian,
                                double enough = std::numeric_limits<double>::infinity());

// A lower bound of min over lo <= δ <= hi of g·δ + ½ δᵀ H δ (H symmetric, N = 1 or 2), lo <= 0 <= hi
// not required. For a positive semidefinite H, the value at an approximate minimiser δ̂ plus
// min over the box of ∇(δ̂)·(δ - δ̂) (convexity: the tangent plane lies below); otherwise the
// minimum is on the boundary, and the same for each edge's one-dimensional quadratic.
double quadratic_lower_bound(const std::array<double, 2>& g, const std::array<std::array<double, 2>, 2>& H,
                             const Params<2>& lo, const Params<2>& hi);
double quadratic_lower_bound_1d(double g, double h, double lo, double hi);

// The monotonicity test (E. Hansen and G. W. Walster, Global Optimization Using Interval
// Analysis, 2nd ed., Dekker 2004, Section 12.4): the partial derivatives ∂_i f = <∂_i s, s - p>
// over the box [lo, hi], enclosed from the first partials at its centre c (`centre`, enclosed) and
// the box's second partials (∂_i s(t) = ∂_i s(c) + Σ_j ∂_i∂_j s(ξ) (t_j - c_j)). Returns, per
// parameter, +1 where ∂_i f > 0 over the whole box, -1 where it is < 0, 0 otherwise. A box where f
// rises along t_i and whose low face along i is not on the domain's edge holds no minimiser of f
// over the domain: from any of its points, a step to lower t_i stays in the domain and lowers f.
template <int N>
std::array<int, N> gradient_signs(const BoxEnclosure<N>& box, const PointEnclosure<N>& centre, const Vec3& p);

// The distance that a lower bound of f = ½ d^2 gives: sqrt(2 f), rounded down (0 for f <= 0).
double distance_from_f_lower(double f_lower);

// Conditions of selects (c ? a : b) undecided over one box beyond which branch_lower_bound gives
// up: 2^4 evaluations of the pieces.
inline constexpr std::size_t kMaxBranchConditions = 4;

// A lower bound of the distance from p over the box [lo, hi] of formulas with selects whose
// condition is undecided there (the switch of a piecewise formula crosses the box), where the
// enclosure of the formulas themselves is not smooth: each point of the box has one truth value
// of each such condition, so the least over the choices of values of a bound of the distance to
// the formulas with the branches they take, over the whole box, bounds it
// (Program::undecided_conditions, BranchChoice). Each choice's bound: zero order, and where its formulas are
// smooth over the box, second order from the centre and from each point of `near` (known minimisers, clamped
// into the box). The least bound when every choice's reaches `enough` (the box closes); else 0, as without
// such selects, with more than kMaxBranchConditions, or where a choice's formulas are not finite over the
// box.
template <int N>
double branch_lower_bound(const formula::Program& program, const Vec3& p, const Params<N>& lo,
                          const Params<N>& hi, const std::vector<Params<N>>& near, double enough);

}  // namespace footpoint
