// The certified subdivision of an implicit curve's box: every cell of the enclosure
// (implicit/seeding/curve_enclosure) is proved empty or to hold monotone arcs with located ends
// (implicit/seeding/curve_cell_proof), or bisected until it is; what stays unproved at the finest level
// allowed is kept as a small box (the neighbourhood of a singular point, where T = ∇f1 × ∇f2
// vanishes, of a point where a formula is not smooth, or of a curve touching a face).
// Nothing is dropped without a proof: every point of the curve in the box lies in a proved cell
// (on one of its arcs) or in an unproved box.
#pragma once
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "geometry/compile_budget.hpp"
#include "implicit/seeding/curve_cell_proof.hpp"
#include "implicit/seeding/curve_enclosure.hpp"

namespace footpoint {

struct ProvedCell {
  Box3 box;
  int axis = 0;                     // the arcs are monotone in x_axis
  std::int32_t first_crossing = 0;  // its ends: CurveCells::crossings[first, first + count)
  std::int32_t crossing_count = 0;  // sorted by x_axis; arc i joins ends 2i and 2i + 1
  CellBounds bounds;
  EnlargedBounds around;
};

struct UnprovedBox {
  Box3 box;
  UnprovedReason reason = UnprovedReason::none;
};

struct CurveCells {
  std::vector<ProvedCell> cells;
  std::vector<FaceCrossing> crossings;
  // The capsules of the arcs (implicit/seeding/curve_cell_proof), cell c's in capsule_begin[c] up to
  // capsule_begin[c + 1]: apart from the cells' bulky enclosures, which a certificate reads only
  // for the few cells its capsules do not rule out.
  std::vector<ArcCapsule> capsules;
  std::vector<std::int32_t> capsule_begin{0};
  std::vector<UnprovedBox> unproved;
  std::size_t examined = 0;     // cells examined (prove_cell calls)
  std::size_t evaluations = 0;  // interval evaluations
  int deepest = 0;              // bisections below the enclosure's cells reached

  std::span<const ArcCapsule> arc_capsules(std::size_t cell) const {
    return {capsules.data() + capsule_begin[cell], capsules.data() + capsule_begin[cell + 1]};
  }
};

struct SubdivisionSettings {
  // Bisections below an enclosure cell before a cell is kept unproved: 2^-14 of a cell (itself
  // ~1/48 of the curve) is far below the distances a certificate tells apart.
  int max_extra_levels = 14;
  // Cells examined before the curve is refused as too intricate for its box (geometry_too_complex).
  std::size_t max_cells = 40000;
  // A proved cell whose enclosures of ∇f1, ∇f2, T and ∂T/∂x_j are wider than this fraction of
  // their midpoints is bisected again (at most max_tightening levels below the enclosure): the
  // certificates of projected points test Krawczyk's contraction ‖I - Y G'(B)‖ < 1 on the cell
  // with these enclosures (implicit/solvers/implicit_curve_certificate), and loose ones fail it.
  double tightness = 0.15;
  int max_tightening = 4;
};

// Throws GeometryError geometry_too_complex past settings.max_cells, and passes on compile_timeout
// (geometry/compile_budget.hpp), both saying what was reached.
CurveCells subdivide_curve(const ImplicitEquations& equations, const CurveEnclosure& enclosure,
                           CompileBudget& budget, const SubdivisionSettings& settings = {});
// The same, filling `out` as it goes.
void subdivide(const ImplicitEquations& equations, const CurveEnclosure& enclosure,
               const SubdivisionSettings& settings, CurveCells& out, CompileBudget& budget);

}  // namespace footpoint
