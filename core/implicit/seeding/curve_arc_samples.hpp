// Samples along the proved arcs of a curve's subdivision (implicit/seeding/curve_cells), linked along the
// curve: the certified replacement of a walk along the curve.
//
// Each arc of a proved cell runs from one located face crossing to the next along the cell's
// monotone coordinate x_k (implicit/seeding/curve_cell_proof). A crossing on a face between two proved
// cells is an end of one arc on each side: the two cells located the same point, in enclosures
// that both hold it, so crossings on the same plane whose enclosures meet are joined. The arcs
// then chain into the pieces of the curve: closed loops, or paths that end on the box's faces
// (the crossing is the exact box-face point) or next to an unproved box (a singular point).
// Along each arc, samples are added between its ends by bisecting the x_k-range: the midpoint
// slice x_k = t meets the arc in the cell's only point of the curve on that slice (proof (a) of
// curve_cell_proof.hpp), found by Newton in the slice, until neighbours are at most max_step
// apart and the tangent turns by at most max_turn between them. So every arc of every proved cell
// holds samples: no piece of the curve, however small, is left without them. A chain is then
// thinned by the same criterion: from each kept point, the farthest point of the chain within
// max_step whose tangent, and every tangent between, stays within max_turn of the chord is the
// next kept (the chain's ends are always kept); where that point falls short of max_step by more
// than a tenth because the next is too far, a point of the curve placed on the stretch between
// them at 0.97 max_step is kept instead. The subdivision's cells are as small as its
// proofs need, which is no measure of how densely `auto` needs samples: without the thinning a
// curve in many small cells has a sample at every face crossing (two to five times as many).
// Within max_step of an end next to an unproved box (a singular point), more of the chain's points
// are kept: of those, each whose successor is more than twice as far from the end along the
// chain, so that the kept path lengths at most double from one to the next wherever the chain has
// a point between (where two neighbours of the chain are further apart, so are the kept ones: no
// point is added there); the tangents do not tell the curvature there (a cusp's grows without
// bound).
#pragma once
#include "geometry/compile_budget.hpp"
#include "implicit/geometry/implicit_curve.hpp"
#include "implicit/seeding/curve_cells.hpp"
#include "seeding/curve_samples.hpp"

namespace footpoint {

struct ArcSampling {
  double max_step = 0.0;
  // 0.15 rad between neighbouring tangents: the arc exceeds the chord by at most 0.1 %.
  double max_turn = 0.15;
};

struct ArcPieces {
  int pieces = 0;          // chains of arcs
  int closed = 0;          // of which loops
  int face_crossings = 0;  // ends on the box's faces
  int open_ends = 0;       // ends next to unproved boxes
};

// Appends the samples of every proved arc to `samples`, linked along the curve.
ArcPieces sample_proved_arcs(const ImplicitEquations& equations, const Box3& box, const CurveCells& cells,
                             const ArcSampling& settings, CurveSamples& samples, CompileBudget& budget);

}  // namespace footpoint
