// What one cell of the subdivision holds, proved with interval arithmetic ([Snyder]: a region where
// the curve is globally parameterizable along a coordinate, with its boundary points located).
//
// Over a closed cell B (interval jets, geometry/implicit_curve.hpp):
//  - empty when the enclosure of f1 or f2 over B excludes 0: its range, or the mean value form
//    f(c) + ∇f(B)·(B - c) about the centre c (both rigorous);
//  - monotone arcs when a component T_k of T = ∇f1 × ∇f2 ([Curve] eq. (7)) is bounded away from 0
//    over B (its enclosure is T(B) ∩ (T(c) + Σ_j ∂_j T(B) (B_j - c_j)), both rigorous). Then
//    (a) each slice x_k = t of B meets the curve at most once: the Jacobian of (f1, f2) in the
//        other two coordinates has determinant ±T_k, and every matrix of its interval enclosure
//        is nonsingular, so (f1, f2) is one-to-one on the slice (mean value theorem row by row);
//    (b) so the curve in B is a union of arcs, each the graph of a smooth function of x_k over an
//        interval (implicit function theorem), with pairwise disjoint x_k-ranges: no closed loop,
//        no end inside B, no singular point (T ≠ 0);
//    (c) each arc meets the boundary of B at its two ends. The points of the curve on the faces
//        of B are located (seeding/face_crossings), each alone in a small box; when every one is a
//        regular zero of its face's system strictly inside the face (the curve crosses the face
//        there, at no edge), they are exactly the ends of the arcs: sorted by x_k they pair up,
//        (0, 1), (2, 3), ..., one pair per arc. No crossing at all: B holds no point of the curve.
// A cell where no T_k is bounded away from 0, or whose faces are not decided, is left unproved
// (the caller subdivides it). The enclosures computed on the way are kept for the certificates of
// the points projected later (solvers/curve/implicit_curve_certificate).
#pragma once
#include <cstddef>
#include <limits>
#include <vector>

#include "geometry/implicit_curve.hpp"
#include "seeding/face_crossings.hpp"

namespace footpoint {

// Enclosures over a proved cell, for bounding f1, f2 and F = ⟨T, p - X⟩ over its sub-boxes.
struct CellBounds {
  Vec3 center;
  std::array<Interval, 2> f_center{};  // f1, f2 at the centre
  std::array<IVec3, 2> grad{};         // ∇f1, ∇f2 over the cell
  IVec3 tangent{};                     // T over the cell
  IVec3 tangent_center{};              // T at the centre
  IMat3 tangent_derivatives{};         // ∂T/∂x_j over the cell (row j)
};

// Enclosures of ∇f1, ∇f2, T and ∂T/∂x_j over the cell enlarged by half its edges on every side
// (clipped to the curve's box): a certificate's Krawczyk test over the enlarged box proves the
// answer the only critical point near the cell's boundary too, and rules out the cell from
// critical points beyond it (solvers/curve/implicit_curve_certificate).
struct EnlargedBounds {
  Box3 box;
  bool valid = false;  // the formulas are smooth over the enlarged box
  std::array<IVec3, 2> grad{};
  IVec3 tangent{};
  IMat3 tangent_derivatives{};
};
EnlargedBounds enlarged_bounds(const ImplicitEquations& equations, const Box3& cell, const Box3& domain);

enum class CellVerdict {
  empty,     // no point of the curve in the cell
  arcs,      // monotone arcs with located ends
  unproved,  // to be subdivided
};

enum class UnprovedReason {
  none,
  tangent_may_vanish,  // no component of T bounded away from 0 (a singular point, or a cell too large)
  faces_undecided,     // a face crossing not isolated, at an edge, or a touching point
  not_smooth,          // a formula not twice differentiable (or not defined) somewhere in the cell
  loose,               // the enclosures are wider than asked for (CellBounds): a smaller cell is wanted
};

struct CellProof {
  CellVerdict verdict = CellVerdict::unproved;
  UnprovedReason reason = UnprovedReason::none;
  int axis = -1;                        // arcs: the coordinate x_k they are monotone in
  std::vector<FaceCrossing> crossings;  // arcs: sorted by x_k; arc i joins 2i and 2i + 1
  CellBounds bounds;                    // arcs: the enclosures above
  std::size_t evaluations = 0;          // interval evaluations made
};

// The largest relative width of the enclosures of ∇f1, ∇f2, T and ∂T/∂x_j over a cell of the
// given longest edge (widths against the norms of the midpoints, in quadrature; ∂T/∂x_j against
// the larger of its midpoint and |T| / edge).
double looseness(const CellBounds& bounds, double edge);

// The proof for the closed cell `cell` (positive extent along every axis of the curve's space).
// A cell whose bounds are looser than `max_looseness` is left unproved (reason loose) before its
// faces are searched.
// `faces` (optional) shares the face searches between neighbouring cells.
CellProof prove_cell(const ImplicitEquations& equations, const Box3& cell,
                     double max_looseness = std::numeric_limits<double>::infinity(),
                     FaceCrossingCache* faces = nullptr);

}  // namespace footpoint
