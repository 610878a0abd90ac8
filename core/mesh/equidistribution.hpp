// Placing n + 1 grid lines on a parameter interval so that each of the n cells holds an equal
// share of a measure of what the cell must resolve (de Boor's equidistribution principle: C. de
// Boor, "Good approximation by splines with variable knots", in Spline Functions and
// Approximation Theory, ISNM 21, Birkhauser 1973, pp. 57-72). The measure is sampled on a fine
// uniform grid: per fine interval its chord length on the geometry and the angle its normal or
// tangent turns through, each normalised by its total and weighted 45 %, plus 10 % of parameter
// length (a flat piece: 90 % length). The cells are then shortest where the geometry bends, no
// cell is longer than about twice what arc length alone would give (at least 45 % of the budget
// goes by length), and none is empty (10 % goes by parameter).
#pragma once
#include <cmath>
#include <vector>

#include "geometry/vec.hpp"

namespace footpoint {

// What one fine interval of a uniform fine grid over [lo, hi] contributes.
struct FineInterval {
  double length = 0.0;  // chord on the geometry (0 where it is not finite)
  double turn = 0.0;    // angle in radians between the normals / tangents at its ends (0 when undefined)
};

struct Measure {
  double length = 0.0;  // sum of the intervals' lengths
  double turn = 0.0;    // sum of their turns
};
Measure total(const std::vector<FineInterval>& fine);
// A total turn below this (radians) is rounding noise of the normals of a flat piece.
inline constexpr double kNoTurn = 1e-6;

// The angle between two directions, atan2(|a x b|, a . b) (accurate near 0 and pi); 0 when either
// is zero or not finite (no direction to turn from).
inline double turn_angle(Vec3 a, Vec3 b) {
  const double angle = std::atan2(norm(cross(a, b)), dot(a, b));
  return norm2(a) > 0.0 && norm2(b) > 0.0 && std::isfinite(angle) ? angle : 0.0;
}

// lines[0] = lo < lines[1] < ... < lines[n] = hi, equidistributing the measure above over the
// uniform fine grid of fine.size() intervals (piecewise-linear inverse of its cumulative sum).
std::vector<double> equidistributed_lines(double lo, double hi, const std::vector<FineInterval>& fine, int n);

}  // namespace footpoint
