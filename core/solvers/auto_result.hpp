// How the two curve searches (implicit_curve_auto, parametric_curve_auto) finish their answer:
// the local minima they keep for all_minima, told apart by foot point, and the result at the best;
// and how the implicit searches (curves and surfaces) tell a tie from the points they reached.
#pragma once
#include <array>
#include <vector>

#include "geometry/vec.hpp"
#include "projection/projection_result.hpp"

namespace footpoint::curve {

// Adds the local minimum m (foot point x) to `minima` unless one there has its foot within `same`.
void add_distinct_minimum(std::vector<Minimum>& minima, Vec3 x, double same, const Minimum& m);

// The answer r at the best local minimum found (r's foot, distance and residuals are set):
// converged when its residuals meet the tolerance (`met`), else degenerate; farther than
// options.max_distance, beyond_max_distance with no foot point (withhold_answer). It gets the
// local solve's iterations and last step, the number of solves started, the distinct minima best
// first (options.all_minima, at most options.max_minima) and the solve's trace (options.trace).
void finish_auto_result(ProjectionResult& r, bool met, int iterations, double step, int starts,
                        const Options& options, std::vector<Minimum> minima,
                        std::vector<std::array<double, 3>> trace);

// A point of the geometry a search reached (a solve's end, an edge or singular point) and its
// distance to p.
struct ReachedFoot {
  Vec3 foot;
  double distance;
};

// The answer r's multiplicity among the points reached: tied with the distinct feet (more than
// kDistinctFoot (1 + |foot|) apart) whose distance is within the certificate's gap of r's, the
// answer's first, when there is more than one; unique otherwise.
AnswerMultiplicity tied_feet(const ProjectionResult& r, Vec3 p, const std::vector<ReachedFoot>& reached);

}  // namespace footpoint::curve
