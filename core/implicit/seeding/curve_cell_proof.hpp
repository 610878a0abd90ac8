// What one cell of the subdivision holds, proved with interval arithmetic ([Snyder]: a region where
// the curve is globally parameterizable along a coordinate, with its boundary points located).
//
// Over a closed cell B (interval jets, implicit/geometry/implicit_curve.hpp):
//  - empty when the enclosure of f1 or f2 over B excludes 0: its range, or the mean value form
//    f(c) + ∇f(B)·(B - c) about the centre c (both rigorous);
//  - monotone arcs when a component T_k of T = ∇f1 × ∇f2 ([Curve] eq. (7)) is bounded away from 0
//    over B (its enclosure is T(B) ∩ (T(c) + Σ_j ∂_j T(B) (B_j - c_j)), both rigorous). Then
//    (a) each slice x_k = t of B meets the curve at most once: the Jacobian of (f1, f2) in the
//        other two coordinates has determinant ±T_k, and in space T_k is also bounded away from
//        0 over the natural enclosure ∇f1(B) × ∇f2(B), the range of the determinants of the
//        matrices whose rows are gradients at different points, so every matrix of the slice's
//        interval Jacobian is nonsingular and (f1, f2) is one-to-one on the slice (mean value
//        theorem row by row; in the plane the slice's one row is taken at one point);
//    (b) so the curve in B is a union of arcs, each the graph of a smooth function of x_k over an
//        interval (implicit function theorem), with pairwise disjoint x_k-ranges: no closed loop,
//        no end inside B, no singular point (T ≠ 0);
//    (c) each arc meets the boundary of B at its two ends. The points of the curve on the faces
//        of B are located (implicit/seeding/face_crossings), each alone in a small box; when every one is a
//        regular zero of its face's system strictly inside the face (the curve crosses the face
//        there, at no edge), they are exactly the ends of the arcs: sorted by x_k they pair up,
//        (0, 1), (2, 3), ..., one pair per arc. No crossing at all: B holds no point of the curve.
// A cell where no T_k is bounded away from 0, or whose faces are not decided, is left unproved
// (the caller subdivides it). The enclosures computed on the way are kept for the certificates of
// the points projected later (implicit/solvers/implicit_curve_certificate).
#pragma once
#include <cstddef>
#include <limits>
#include <vector>

#include "implicit/geometry/implicit_curve.hpp"
#include "implicit/seeding/face_crossings.hpp"

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
// critical points beyond it (implicit/solvers/implicit_curve_certificate).
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

// A capsule around one arc of a proved cell: every point of the arc lies within `radius` of the
// segment [a, b] between the located points of its two ends (a before b along x_axis).
// With the arc the graph x_j = φ_j(t) of t = x_axis over [a*_k, b*_k] (a*, b* its true ends, in
// the ends' enclosures) and the chord c(t) through a*, b*, g = φ_j - c_j vanishes at both ends and
//  - φ_j' = T_j / T_k ∈ R_j = T_j(B) / T_k(B), the chord's slope too (mean value theorem), so
//    |g(t)| <= w(R_j) min(t - a*_k, b*_k - t) <= w(R_j) L / 2;
//  - |g(t)| <= max |φ_j''| (t - a*_k)(b*_k - t) / 2 <= max |φ_j''| L² / 8 (the interpolation
//    error of the chord), with φ_j'' = Σ_m ∂_m(T_j / T_k) T_m / T_k enclosed from T(B), ∂T(B);
// where L >= b*_k - a*_k. The arc and the chord agree in x_k, so their distance at t is at most
// the root of the sum of squares of the per-coordinate bounds; the segment [a, b] between the
// computed end points lies within the larger diameter of the two enclosures of the true chord.
struct ArcCapsule {
  Vec3 a, b;
  double radius = 0.0;
};
ArcCapsule arc_capsule(const CellBounds& bounds, int axis, const FaceCrossing& start,
                       const FaceCrossing& end);
// A box holding every point of the capsule (and so of its arc).
Box3 capsule_box(const ArcCapsule& c);

struct CellProof {
  CellVerdict verdict = CellVerdict::unproved;
  UnprovedReason reason = UnprovedReason::none;
  int axis = -1;                        // arcs: the coordinate x_k they are monotone in
  std::vector<FaceCrossing> crossings;  // arcs: sorted by x_k; arc i joins 2i and 2i + 1
  std::vector<ArcCapsule> capsules;     // arcs: arc i's capsule
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
