// A NURBS curve or surface cut at its knots into Bézier pieces, each a formula of the engine: on a
// knot span (a pair of spans for a surface) the curve is a rational polynomial, given exactly by
// its Bézier control points ([PieglTiller] L. Piegl, W. Tiller, The NURBS Book, 2nd ed., Springer
// 1997, sec. 5.4 "Decomposition of B-spline curves and surfaces"). They are computed here by
// blossoming: the Bézier point k of the span [a, b] of a degree-p curve is its blossom
// f(a, ..., a, b, ..., b) (p - k a's, k b's), which is de Boor's algorithm with the r-th level's
// parameter the r-th argument ([PieglTiller] sec. 5.2, eq. (5.x)-style triangular scheme;
// L. Ramshaw, Blossoms are polar forms, CAGD 6 (1989) 323-358). A surface's net is the tensor
// product: every row's blossom in v, then the columns' in u.
//
// Each piece's formula is in the span's local parameters s = (u - a) / (b - a) in [0, 1] (and t
// for v): the Bézier form
//   C(s) = Σ_k w_k P_k B_k^p(s) / Σ_k w_k B_k^p(s),   B_k^p(s) = binom(p, k) s^k (1 - s)^(p - k),
// written in the power basis, Σ_j a_j s^j with a_j = binom(p, j) Σ_{k<=j} binom(j, k) (-1)^(j-k) w_k P_k
// ([PieglTiller] eq. (6.x), the matrix form of the Bernstein basis), so that a non-rational piece
// is a sum of monomials and the engine evaluates and encloses it as one (formula/polynomial.hpp);
// the quotient is left out when every weight is 1. Its control points also bound it: with
// positive weights a rational Bézier piece lies in the convex hull of its (Euclidean) control
// points ([PieglTiller] property P4.9), so the box of those points, widened by their rounding,
// holds every point of the piece.
//
// Limits: the pieces' control points and power-basis coefficients are rounded results of the
// blossom and of the change of basis (a few units in the last place of the net's magnitude, times
// 2^p): a piece's formula is the NURBS to that accuracy, and the box is widened by 2^-40 of the
// net's magnitude to hold the exact piece too.
#pragma once
#include <array>
#include <vector>

#include "formula/program.hpp"
#include "geometry/box3.hpp"
#include "parametric/geometry/nurbs.hpp"
#include "parametric/geometry/parametric_curve.hpp"
#include "parametric/geometry/parametric_surface.hpp"

namespace footpoint::nurbs {

struct CurvePiece {
  ParamInterval span;                         // [U_i, U_{i+1}]
  formula::Program program;                   // s in [0, 1] -> x, y[, z]
  Box3 hull;                                  // holds every point of the piece
  std::vector<std::array<double, 4>> bezier;  // the weighted Bézier points (w x, w y, w z, w)
};

struct SurfacePiece {
  ParamBox span;                              // [U_i, U_{i+1}] x [V_j, V_{j+1}]
  formula::Program program;                   // (s, t) in [0, 1]^2 -> x, y, z
  Box3 hull;                                  // holds every point of the piece
  std::vector<std::array<double, 4>> bezier;  // b_kl at k * (q + 1) + l, weighted as above
};

// One piece per non-empty knot span, in increasing parameter (surfaces: u-major). Throws
// formula::FormulaError too_complex when a piece's formula passes max_nodes operations.
std::vector<CurvePiece> bezier_pieces(const Curve& curve, std::size_t max_nodes);
std::vector<SurfacePiece> bezier_pieces(const Surface& surface, std::size_t max_nodes);

}  // namespace footpoint::nurbs
