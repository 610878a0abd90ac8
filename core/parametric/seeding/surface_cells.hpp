// What `auto` precomputes once per parametric surface and reuses for every point: an adaptive
// subdivision of the parameter domain into cells (a binary tree as built), searched through a
// bounding-volume hierarchy over the cells' boxes in space (4-ary), with
//  - per cell: the jet of s at the cell's centre (value, first and second partials), and ρ, a bound
//    on |s(t) - (s_c + s_u δu + s_v δv)| over the cell (the tangent-plane model's error, estimated
//    from 16 samples plus twice the quadratic model's error there, which bounds the gap between the
//    samples), and ρ2, the same for the quadratic model (twice its sampled error);
//  - per node of the hierarchy: an axis-aligned box containing s over its cells. For a cell it is
//    the formula engine's interval enclosure over the cell's rectangle (rigorous, outward
//    rounded); a node's box is the union of its children's. dist(p, box) is a lower bound on the
//    distance from p to that part of the surface.
// Cells are split (where the tangent-plane model is worse), worst cell first, until the
// tangent-plane model is good to `flatness` of the cell's size, so that the Newton model of a
// cell predicts where the distance is least, and most points need a single local solve.
//
// The budget adapts to the surface: the cells a surface needs grow with how much it bends and
// with the domain's extent relative to its features (S1 on [-3,3]^2: 728 cells for flatness
// 0.05; the same formulas on [-25,25]^2, 8 periods each way: ~50,000). Three tiers of cells:
//  - fine (ρ <= flatness x extent): the search trusts the cell's models: the tangent-plane lower
//    bound, the Newton model's claim that the minimum lies in a neighbour, and merging a
//    candidate with a minimum found within a cell of its model's minimiser;
//  - coarse (ρ <= resolved_flatness x extent): the same, except that a candidate is merged only
//    with a minimum found inside the cell (a coarse model can put the minimum a cell off, and two
//    minima can lie a cell apart, as near folds where s_u x s_v -> 0);
//  - unresolved: no model bound, no claim, no merging: solved from its model's minimiser.
// Fine and coarse cells are "resolved". Refinement, worst cell first, pursues `flatness` up to
// `target_cells` cells, then `resolved_flatness` up to the memory cap `max_bytes`.
// The trade-off: finer cells give tighter bounds, better starts and fewer local solves, but a
// longer compile (two binary nodes per cell), more memory (memory_bytes(), ~355 bytes per cell)
// and, for points near a surface that covers itself many times, more cells to visit.
// On the [-25,25]^2 surface (bench/surface_bench.cpp, A1): all fine at flatness 0.05 would take
// ~50,000 cells and 17 MB; a fixed budget of 4096 cells leaves every cell unresolved (~30 local
// solves per point); the defaults give ~4,300 cells (target 4096, then on to 0.25), 1.5 MB, and
// per point about a third of the local solves of that fixed budget. S1-S3 reach flatness 0.05
// within the target (394-2306 cells).
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "geometry/compile_budget.hpp"
#include "parametric/geometry/box_enclosure.hpp"
#include "parametric/geometry/parametric_surface.hpp"
#include "parametric/geometry/self_covering.hpp"
#include "parametric/seeding/surface_refinement.hpp"

namespace footpoint {

struct SurfaceSeedingOptions {
  // Uniform subdivision first, to at least this many cells: no feature narrower than a cell of
  // this grid is missed by the error estimate.
  int min_cells = 256;
  // The target: refine while ρ > flatness x the cell's extent on the surface (chord length) and
  // the tree has fewer than target_cells cells.
  double flatness = 0.05;
  int target_cells = 4096;
  // The requirement: refine while ρ > resolved_flatness x extent, up to max_bytes; a cell within
  // it is resolved.
  double resolved_flatness = 0.25;
  // Memory cap of the cells and the tree (memory_bytes()): about 8,400 cells. Refinement stops
  // there whatever the flatness.
  std::size_t max_bytes = std::size_t{4} << 20;
  // The certificates' sub-boxes kept for later points (surface_refinement.hpp): at most this many
  // pairs a cell, and at least min_refinement_pairs in all (about 1 KB a pair, allocated as they are
  // made but counted in memory_bytes() up front).
  std::size_t refinement_pairs_per_cell = 4;
  std::size_t min_refinement_pairs = 4096;
};

// Laid out for the search: what the first test of a visit reads (the frame, ρ, the flags and s_c)
// comes first, in the cell's first two cache lines.
struct alignas(64) SurfaceCell {
  // The rectangle in the tangent plane that holds the cell's tangent parallelogram
  // {s_c + s_u δu + s_v δv}: centred at s_c, axes e1 = s_u/|s_u|, e2 = n x e1 (n = the unit
  // normal), half-widths half1 = |s_u| hu + |<s_v, e1>| hv, half2 = |<s_v, e2>| hv (hu, hv the
  // cell's half-widths in u and v). The cell lies within ρ of it. framed = false where
  // s_u x s_v = 0 (no plane).
  Vec3 e1, e2, unit_normal;
  double half1 = 0.0, half2 = 0.0;
  double rho = 0.0;  // tangent-plane model error bound (see above)
  bool framed = false;
  bool finite = true;                             // the centre jet is finite
  bool resolved = true;                           // ρ <= resolved_flatness x extent
  bool fine = true;                               // ρ <= flatness x extent
  SurfaceJet centre;                              // s and its partials at ((u0+u1)/2, (v0+v1)/2)
  double u0 = 0.0, u1 = 0.0, v0 = 0.0, v1 = 0.0;  // the parameter rectangle
  // The tangent plane's metric at the centre (first fundamental form E, F, G), for the Newton
  // model of every visit past the tangent-plane rule (parametric/solvers/surface_auto.cpp).
  double E = 0.0, F = 0.0, G = 0.0;
  double rho2 = 0.0;    // the same as ρ for the quadratic (Taylor) model
  double extent = 0.0;  // largest chord of the cell on the surface
  double uc() const { return 0.5 * (u0 + u1); }
  double vc() const { return 0.5 * (v0 + v1); }
};

// What the certificate of an answer needs of a cell (parametric/solvers/surface_certificate.hpp):
// rigorous, independent of the point projected, next to the cell's estimates above.
struct SurfaceCellBounds {
  BoxEnclosure<2> enclosure;  // s, its second partials and the metric over the cell
  // The stored centre jet (SurfaceCell::centre) against the exact values at the cell's centre:
  // |s(c)_k - centre.s_k| <= s_rad_k, and the same for s_u, s_v (from a ball jet at c).
  Vec3 s_rad, su_rad, sv_rad;
  // The tangent-plane model's error, proved: |s(t) - (s_c + s_u δu + s_v δv)| <= rho over the
  // cell for the stored centre jet (its rounding above, plus the second-order remainder
  // ½ δᵀ|∂²s|δ with the magnitudes of the enclosure); +inf where the cell is not smooth.
  double rho = 0.0;
  bool centre_valid = false;  // the ball jet at the centre is finite
};

// A corner of the parameter domain and its point of the surface.
struct SurfaceCorner {
  double u = 0.0, v = 0.0;
  SurfaceJet jet;  // s and its partials there: a local solve that starts at the corner needs no evaluation
  bool finite = false;
};

// A node of the search hierarchy: 2-4 children, each a node or a cell (a leaf). The children's
// boxes are stored in the node, coordinate by coordinate (lo[c][k], hi[c][k] for child k), so that
// the walk gets all four box distances from one node's memory in a few vector operations. An
// unused slot has an empty box (lo = +inf, hi = -inf): its distance is infinite.
struct SurfaceCellNode {
  static constexpr int kWidth = 4;
  alignas(32) double lo[3][kWidth];
  double hi[3][kWidth];
  // child >= 0: a node; child < 0: the leaf holding cell ~child (i.e. -child - 1)
  std::int32_t child[kWidth];
  int children = 0;
};

class SurfaceCells {
 public:
  // The cells cover the box less the rectangles `covering` shows to add no point of the surface
  // (parametric/geometry/self_covering.hpp): the search and the certificates see each point of the surface
  // from fewer parameter copies.
  // Built within `budget` (geometry/compile_budget.hpp).
  SurfaceCells(const SurfaceFormulas& formulas, const ParamBox& box, CompileBudget& budget,
               const SurfaceSeedingOptions& options = {}, const SelfCovering& covering = {});

  // nodes()[0] is the root, unless the tree is a single cell (then nodes() is empty).
  const std::vector<SurfaceCellNode>& nodes() const { return nodes_; }
  const std::vector<SurfaceCell>& cells() const { return cells_; }
  // Parallel to cells(): their rigorous bounds.
  const std::vector<SurfaceCellBounds>& bounds() const { return bounds_; }
  // The translations the cells were built with: every parameter point of the box has its copies
  // t + Σ k_i δ_i in the box, which the cells do not search.
  const SelfCovering& covering() const { return covering_; }
  // The cells' sub-boxes, bisected on demand by the certificates and kept (thread-safe).
  const SurfaceRefinement& refinement() const { return *refinement_; }
  // The box containing the whole surface (the root's).
  const Vec3& lo() const { return lo_; }
  const Vec3& hi() const { return hi_; }
  // The domain's corners (umin, vmin), (umax, vmin), (umin, vmax), (umax, vmax): minima of their
  // own, which `auto` compares with its answer (a cell's model cannot tell a corner from an edge
  // minimum within the model's error of it).
  const std::array<SurfaceCorner, 4>& corners() const { return corners_; }
  std::size_t memory_bytes() const;
  // Memory per cell, an upper bound: the cell and a node (a tree with n >= 2 leaves whose nodes
  // have at least two children each has fewer than n nodes).
  static constexpr std::size_t bytes_per_cell() { return sizeof(SurfaceCell) + sizeof(SurfaceCellNode); }
  // The certificates' part of memory_bytes(), outside the cap (max_bytes caps the search's cells
  // and tree): the cells' rigorous bounds (sizeof(SurfaceCellBounds) a cell) and the sub-boxes
  // the refinement may keep.
  std::size_t bounds_bytes() const {
    return bounds_.capacity() * sizeof(SurfaceCellBounds) + refinement_->reserved_bytes();
  }

  // Lower bounds on |p - x|^2 over each child's box of `node` (0 inside it, +inf for an unused slot).
  static void box_distances2(const SurfaceCellNode& node, const Vec3& p,
                             double out[SurfaceCellNode::kWidth]) {
    // GCC/Clang vector extensions, two lanes (one SSE2 register) at a time
    typedef double Pair __attribute__((vector_size(2 * sizeof(double))));
    const Pair zero = {0.0, 0.0};
    const double q[3] = {p.x, p.y, p.z};
    for (int k = 0; k < SurfaceCellNode::kWidth; k += 2) {
      Pair sum = zero;
      for (int c = 0; c < 3; ++c) {
        Pair lo, hi;
        __builtin_memcpy(&lo, &node.lo[c][k], sizeof lo);
        __builtin_memcpy(&hi, &node.hi[c][k], sizeof hi);
        const Pair qc = {q[c], q[c]};
        const Pair below = lo - qc, above = qc - hi;  // at most one is positive
        Pair d = below > above ? below : above;
        d = d > zero ? d : zero;
        sum += d * d;
      }
      __builtin_memcpy(&out[k], &sum, sizeof sum);
    }
  }
  // The same for the root box.
  double root_distance2(const Vec3& p) const;

 private:
  struct SpaceLeaf {
    Vec3 lo, hi;  // the cell's box
    std::int32_t cell;
  };
  std::int32_t build_space_tree(std::vector<SpaceLeaf>& leaves, std::size_t begin, std::size_t end);
  std::vector<SurfaceCellNode> nodes_;
  std::vector<SurfaceCell> cells_;
  std::vector<SurfaceCellBounds> bounds_;
  std::unique_ptr<SurfaceRefinement> refinement_;
  std::array<SurfaceCorner, 4> corners_;
  Vec3 lo_, hi_;
  SelfCovering covering_;
};

}  // namespace footpoint
