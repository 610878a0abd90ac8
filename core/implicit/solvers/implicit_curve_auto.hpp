// `auto` for implicit curves: the global nearest point of the curve inside its box.
//  1. The nearest sample s0 of the curve's samples (implicit/seeding/curve_discovery) gives
//     d* <= |p - s0| =: d0, and every curve point is within h/2 of a sample (h the spacing), so the
//     nearest point has a sample within d0 + h/2 of p.
//  2. Candidates: the samples within that radius that are discrete local minima of the distance
//     along the curve (k-d tree query, seeding/curve_sample_index), nearest first.
//  3. From each candidate, while its distance minus h/2 can still beat the best found: Newton on
//     the Lagrange system (lagrange_newton), checked to be a minimum near its start inside the box,
//     else a monotone descent along the curve (curve_descent). Box-face crossings and singular
//     points are candidates as they are (exact points, refined at discovery).
//  4. The certificate (implicit/solvers/implicit_curve_certificate, unless options.certify is false):
//     a rigorous lower bound of the distance over the whole curve in the box, from the certified
//     subdivision of discovery, and whether it meets the answer.
// A curve that is the union of factor curves (implicit/seeding/discovered_curve.hpp) is searched on each,
// nearest first; a foot on two of them is a singular point of the union. The certificate bounds
// the distance to each, L the least.
// options.initial is not used: the search is global. With all_minima every discrete local minimum
// of the samples is refined and the distinct minima are returned, best first.
#pragma once
#include <span>

#include "implicit/geometry/implicit_curve.hpp"
#include "implicit/seeding/discovered_curve.hpp"
#include "projection/projection_result.hpp"

namespace footpoint::curve {

// The curve is the union of `factors` (at least one), discovered in `box`.
ProjectionResult implicit_curve_auto(std::span<const DiscoveredCurve* const> factors, const Box3& box, Vec3 p,
                                     const Options& options);

}  // namespace footpoint::curve
