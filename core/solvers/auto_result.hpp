// How the two curve searches (implicit_curve_auto, parametric_curve_auto) finish their answer:
// the local minima they keep for all_minima, told apart by foot point, and the result at the best.
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

}  // namespace footpoint::curve
