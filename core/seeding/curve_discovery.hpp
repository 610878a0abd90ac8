// Finding every piece of an implicit curve inside its box, once per curve (what `auto` of an
// implicit curve precomputes):
//  1. enclosure: the box is subdivided and every cell whose interval enclosure of f1 or f2
//     excludes 0 is discarded (rigorous: no discarded cell holds a point of the curve);
//  2. seeds: the centre of each remaining cell is moved onto the curve (min-norm Newton);
//  3. tracing: from each seed not already covered, the curve is followed in both directions with
//     a predictor-corrector walk of bounded step and turning angle, until it closes, leaves the box
//     (the exact face crossing is added) or reaches a singular point (refined and added);
//  4. coverage: cells holding no sample are examined again, subdivided when their seed fails;
//  5. certification: each kept cell must be small enough that f1 = 0 and f2 = 0 are nearly flat
//     across it (one nearly straight arc per cell), else it is bisected and its sub-cells seeded;
//     past the budget, GeometryError "geometry_too_complex".
// The result is the linked samples of curve_samples.hpp with their spacing h.
#pragma once
#include <cstddef>

#include "seeding/curve_samples.hpp"

namespace footpoint {

class ImplicitEquations;
struct Box3;

struct DiscoveryStats {
  int levels = 0;                  // subdivision depth of the enclosure
  std::size_t cells = 0;           // cells of the enclosure at that depth
  std::size_t interval_tests = 0;  // exclusion tests evaluated (enclosure and coverage)
  int traces = 0;                  // traced pieces (one or more per connected component)
  int face_crossings = 0;
  int singular_points = 0;
  std::size_t certification_tests = 0;  // jets evaluated to certify kept cells as nearly flat
  int unresolved_cells = 0;             // cells kept by the enclosure where no curve point was found
  bool enclosure_truncated = false;     // the enclosure stopped at its cell budget (coarser cells)
  double seconds = 0.0;
};

struct CurveDiscovery {
  CurveSamples samples;
  DiscoveryStats stats;
  double scale = 1.0;  // diagonal of the samples' bounding box (>= tiny): the curve's size
};

CurveDiscovery discover_implicit_curve(const ImplicitEquations& equations, const Box3& box);

}  // namespace footpoint
