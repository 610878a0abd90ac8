// How many points of a curve are nearest to p (projection/projection_result.hpp, AnswerMultiplicity),
// for auto's answer on a parametric curve:
//  - a continuum where the distance along the curve is flat to second order at an interior foot:
//    φ''(t) = |c'|^2 + <c - p, c''> = |c'|^2 (1 - κ <n, p - c>) vanishes to 1e-8 of |c'|^2, p at the
//    centre of the osculating circle (the centre of a circle: every point is nearest);
//  - tied: the distinct feet (more than 1e-8 (1 + |foot|) apart) among the minima found whose
//    distance is within the certificate's gap of the answer's, the answer's first;
//  - unique otherwise.
// The minima are the local solves' (every sample that could hold the nearest point starts one)
// and the certificate's: a tie hidden from both is one its proof would have had to exclude. Only
// those within the gap have their foot point evaluated.
#pragma once
#include <vector>

#include "parametric/geometry/parametric_curve.hpp"
#include "parametric/solvers/parametric_curve_certificate.hpp"
#include "projection/projection_result.hpp"

namespace footpoint::curve {

AnswerMultiplicity curve_multiplicity(const CurveFormulas& formulas, Vec3 p, const ProjectionResult& r,
                                      const std::vector<CurveMinimum>& found);

}  // namespace footpoint::curve
