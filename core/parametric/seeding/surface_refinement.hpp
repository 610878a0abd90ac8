// Sub-boxes of a surface's cells with their rigorous enclosures, bisected on demand by the
// certificates (parametric/solvers/surface_certificate.hpp) and kept for every later point: the
// enclosures do not depend on the point, and the points of a batch meet the same places where the
// compiled cells are too coarse to prove anything (near the answers of many points, along folds).
//
// Thread-safe without locks: the two halves of a box are computed by the first thread that needs
// them and published through the box's atomic pointer (compare-and-swap; a thread that loses the
// race drops its own copy). Published halves are never changed or freed before the refinement is.
// The number of published pairs is capped (max_pairs, a few MB); past it, halves are computed
// into the caller's scratch and not kept.
#pragma once
#include <array>
#include <atomic>
#include <cstddef>
#include <memory>

#include "formula/program.hpp"
#include "parametric/geometry/box_enclosure.hpp"
#include "parametric/geometry/params.hpp"

namespace footpoint {

struct SubBoxPair;

struct SubBox {
  Params<2> lo{}, hi{};
  BoxEnclosure<2> enclosure;  // s, its second partials and the metric over the box
  PointEnclosure<2> centre;   // s, s_u, s_v at the centre, enclosed
  bool split_u = true;        // its halves split it along u (it is longer along u on the surface)
  mutable std::atomic<const SubBoxPair*> halves{nullptr};

  SubBox() = default;
  // [lo, hi] inside the box of `ancestor` (the enclosure of the box it was halved from): the
  // centred form from the ancestor and a ball jet at the box's centre (parametric/geometry/
  // box_enclosure.hpp: derive_enclosure), which costs no evaluation over the box and tightens with
  // it (s in O(h^2) and s_u, s_v in O(h) about the centre, the ancestor's second derivatives);
  // with `evaluate`, or where the ancestor is not smooth (a kink of the formulas crosses it, and the
  // smaller box may be smooth), also an interval jet over the box (enclose_box), and the tighter
  // of the two enclosures.
  SubBox(const formula::Program& program, const BoxEnclosure<2>& ancestor, const Params<2>& lo,
         const Params<2>& hi, bool evaluate);
  SubBox(const SubBox&) = delete;
  SubBox& operator=(const SubBox&) = delete;
  ~SubBox();
};

struct SubBoxPair {
  // [lo, hi] halved along u (split_u) or v
  SubBoxPair(const formula::Program& program, const BoxEnclosure<2>& ancestor, const Params<2>& lo,
             const Params<2>& hi, bool split_u, bool evaluate);
  SubBox half[2];
};

class SurfaceRefinement {
 public:
  SurfaceRefinement(formula::Program program, std::size_t cells, std::size_t max_pairs);
  ~SurfaceRefinement();
  SurfaceRefinement(const SurfaceRefinement&) = delete;
  SurfaceRefinement& operator=(const SurfaceRefinement&) = delete;

  // Where the halves of compiled cell `cell` are published.
  std::atomic<const SubBoxPair*>& cell_slot(std::size_t cell) const { return cell_halves_[cell]; }
  // The halves of [lo, hi] split along u (split_u) or v, each inside `ancestor`'s box (the box
  // halved, `of_cell` when it is a compiled cell): published under `slot`, computed first if need
  // be; past the cap computed into `scratch`. Each half's enclosure is the centred form from the
  // ancestor (SubBox), with an interval jet over the half as well for the halves of a compiled cell
  // and wherever the formulas are not a sum of monomials. A sum of monomials has its ball jets
  // from the table of powers (formula/polynomial.hpp), cheap beside an interval jet of the tape
  // over a box, and the centred form's second derivatives, the cell halves', are kept tight by the
  // evaluation at the first level; for other formulas (elementary functions) the interval jet's
  // second derivatives over the small box are what the Hessian bounds of far points need
  // (Σ (s_k - p_k) ∂²s_k grows with the distance). The choice depends on the box and the formulas
  // only, never on the point: a certificate does not depend on the points answered before it.
  const SubBoxPair& halves(std::atomic<const SubBoxPair*>& slot, const BoxEnclosure<2>& ancestor,
                           const Params<2>& lo, const Params<2>& hi, bool split_u, bool of_cell,
                           std::unique_ptr<SubBoxPair>& scratch) const;
  // What the refinement may take: the cap's worth of pairs (reserved, reported up front).
  std::size_t reserved_bytes() const { return max_pairs_ * sizeof(SubBoxPair); }
  // The pairs kept (at most max_pairs), plus the places threads hold while they decide.
  std::size_t pairs() const { return pairs_.load(std::memory_order_relaxed); }

 private:
  formula::Program program_;
  bool sum_of_monomials_;
  std::size_t cells_;
  std::size_t max_pairs_;
  std::unique_ptr<std::atomic<const SubBoxPair*>[]> cell_halves_;
  mutable std::atomic<std::size_t> pairs_{0};
};

}  // namespace footpoint
