// Finding every piece of an implicit curve inside its box, once per curve (what `auto` of an
// implicit curve precomputes), by interval arithmetic only:
//  1. enclosure (implicit/seeding/curve_enclosure): the box is subdivided and every cell whose interval
//     enclosure of f1 or f2 excludes 0 is discarded;
//  2. proof (implicit/seeding/curve_cells, curve_cell_proof): every remaining cell is proved empty, or to
//     hold arcs monotone along a coordinate whose ends are located on its faces, or bisected until
//     it is; what no bisection down to the finest level proves (around singular points, where
//     T = ∇f1 × ∇f2 vanishes) stays as small unproved boxes;
//  3. samples (implicit/seeding/curve_arc_samples): the proved arcs chained into the curve's pieces and
//     sampled along them, linked;
//  4. singular points: in each cluster of unproved boxes, Newton on the singular system
//     (implicit/geometry/singular_point) finds the singular point, and Krawczyk's test isolates it where it
//     is a regular zero of that system; a cluster without one gets a point of the curve (Newton
//     from its centre) as a sample.
// Past the cell budget: GeometryError geometry_too_complex, saying what was reached.
// The result is the linked samples of curve_samples.hpp with their spacing h, and the proved cells
// with their enclosures, which the certificates of projected points use.
#pragma once
#include <cstddef>
#include <vector>

#include "geometry/compile_budget.hpp"
#include "implicit/seeding/curve_cell_tree.hpp"
#include "implicit/seeding/curve_cells.hpp"
#include "seeding/curve_samples.hpp"

namespace footpoint {

class ImplicitEquations;
struct Box3;

struct DiscoveryStats {
  int levels = 0;                    // subdivision depth of the enclosure
  std::size_t cells = 0;             // cells of the enclosure at that depth
  std::size_t interval_tests = 0;    // exclusion tests of the enclosure
  std::size_t cells_examined = 0;    // cells the proof examined (enclosure cells and their parts)
  std::size_t proved_cells = 0;      // cells holding proved arcs
  std::size_t unproved_boxes = 0;    // cells left unproved at the finest level
  std::size_t evaluations = 0;       // interval evaluations of the proof
  int deepest = 0;                   // bisections below the enclosure's cells
  int pieces = 0;                    // chains of proved arcs (one or more per connected component)
  int closed_pieces = 0;             // of which loops
  int face_crossings = 0;            // crossings of the box's faces
  int singular_points = 0;           // singular points found in the unproved boxes
  int isolated_singular_points = 0;  // of which proved alone in a small box (regular zeros)
  bool enclosure_truncated = false;  // the enclosure stopped at its cell budget (coarser cells)
  double seconds = 0.0;
};

struct CurveDiscovery {
  CurveSamples samples;
  CurveCells cells;
  CurveCellTree tree;
  std::vector<Box3> singular_enclosures;  // boxes each holding exactly one singular point
  DiscoveryStats stats;
  double scale = 1.0;  // diagonal of the samples' bounding box (>= tiny): the curve's size
  std::size_t memory_bytes() const;
};

CurveDiscovery discover_implicit_curve(const ImplicitEquations& equations, const Box3& box,
                                       CompileBudget& budget);

}  // namespace footpoint
