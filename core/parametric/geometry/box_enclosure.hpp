// What interval arithmetic proves about a parametric surface (N = 2) or curve (N = 1) over a
// closed box of its parameters, independently of any point projected: an enclosure of s, of its
// second partial derivatives and of the metric <s_i, s_j> over the box (outward-rounded interval
// jets of the formula tape, formula/interval_jet.hpp). The distance bounds of
// parametric/geometry/distance_bound.hpp combine it with a point p.
// Also the rigorous evaluation of s and its first partials at one point (PointEnclosure, from the
// tape's ball jets, formula/ball.hpp).
#pragma once
#include <array>
#include <utility>

#include "formula/program.hpp"
#include "geometry/vec.hpp"
#include "parametric/geometry/params.hpp"

namespace footpoint {

template <int N>
struct BoxEnclosure {
  static constexpr int kPairs = N * (N + 1) / 2;  // (i, j) with i <= j: 00 | 00, 01, 11
  // The index of the pair (i, j) (or (j, i)) in the arrays below: row i of the upper triangle
  // starts after the i rows above it, of N, N - 1, ... entries.
  static constexpr int pair(int i, int j) {
    if (i > j) std::swap(i, j);
    return i * N - i * (i - 1) / 2 + (j - i);
  }
  Params<N> lo{}, hi{};  // the parameter box
  // s over the box: every s(t) has |s_k(t) - s_mid_k| <= s_rad_k. Valid when `bounded`, and for
  // the t where s is finite when `finite_part`.
  Vec3 s_mid, s_rad;
  // ∂²s/∂t_i∂t_j over the box, pair index as above. Valid when `smooth`.
  std::array<Vec3, kPairs> d2_mid{}, d2_rad{};
  // <s_i, s_j> over the box: metric_lo <= <s_i, s_j> <= metric_hi (metric_lo >= 0 for i == j).
  // Valid when `smooth`.
  std::array<double, kPairs> metric_lo{}, metric_hi{};
  // s is defined and finite at every point of the box (the interval values are finite).
  bool bounded = false;
  // s is finite somewhere in the box (bounded, or defined on part of it with finite interval
  // values there: formula/interval.hpp's `partial`), and s_mid ± s_rad holds those points.
  bool finite_part = false;
  // No point of the box is in the formulas' domain (an empty interval value): no point of the
  // geometry comes from the box.
  bool empty = false;
  // s is twice continuously differentiable on the box (the interval jets' `smooth` flag for x, y
  // and z): the second-order data holds.
  bool smooth = false;
};

// The enclosure of `program` (inputs t_1..t_N, outputs x, y[, z]) over the box [lo, hi]; with
// `choice`, of the formulas with its selects replaced by their branches.
template <int N>
BoxEnclosure<N> enclose_box(const formula::Program& program, const Params<N>& lo, const Params<N>& hi,
                            const formula::BranchChoice* choice = nullptr);

// s and its first partials at one point, each exact value within `*_rad` of the stored one, per
// coordinate (from a ball jet, or from a point jet and a bound on its rounding).
template <int N>
struct PointEnclosure {
  Vec3 s, s_rad;
  std::array<Vec3, N> ds{}, ds_rad{};
  bool valid = false;  // the formulas are defined and differentiable at the point (balls finite)
};

// The rigorous evaluation at t (Program::ball_jets1; with `choice`, of the formulas with its
// selects replaced by their branches).
template <int N>
PointEnclosure<N> enclose_point(const formula::Program& program, const Params<N>& t,
                                const formula::BranchChoice* choice = nullptr);

// The enclosure over a box B inside `ancestor`'s box from a rigorous evaluation at B's centre c
// (centred forms, Taylor's theorem with the ancestor's second derivatives on the segment from c):
//   s(t)  ∈ s(c) + J(c) δ + ½ δᵀ [∂²s] δ,   J(t) ∈ J(c) + [∂²s] δ,   δ = t - c, |δ_i| <= h_i,
// the metric as interval products of those J, the second derivatives the ancestor's. Costs one ball
// jet instead of an interval jet, and tightens with B (the ancestor's [∂²s] times h). Nothing
// (not bounded) where the ancestor is not smooth or the centre's evaluation not valid.
BoxEnclosure<2> derive_enclosure(const BoxEnclosure<2>& ancestor, const Params<2>& lo, const Params<2>& hi,
                                 const PointEnclosure<2>& centre);

// Both enclosures of one box hold; their intersection is kept (s and the metric from whichever is
// tighter per coordinate, the second derivatives likewise).
BoxEnclosure<2> intersect(const BoxEnclosure<2>& a, const BoxEnclosure<2>& b);

}  // namespace footpoint
