// The curvature circle method (S.-M. Hu, J. Wallner, A second order algorithm for orthogonal projection onto
// curves and surfaces, Computer Aided Geometric Design 22(3), 2005; [GSA] Section 3, eqs. (21)-(22)) for a
// parametric curve. At c(t0): curvature k = |c' x c''| / |c'|^3, radius R = 1 / k, principal
// normal N, centre m = c + R N. The test point p (moved into the osculating plane of a space curve)
// gives the footpoint q on the circle between p and m,
//   q = p + (m - p) w,   w = 1 - R / |m - p|           ([GSA] eqs. (14)-(17)),
// and the parameter step from the circle sharing the curve's second-order Taylor polynomial,
// q - c = dt c' + dt^2 / 2 c'' (eq. (21)): crossing with c'' removes dt^2,
//   dt = det(q - c, c'') / det(c', c'')                (eq. (22), planar),
//   dt = <(q - c) x c'', c' x c''> / |c' x c''|^2      (the same in 3-D).
// Where k = 0 (a straight piece) the circle is the tangent line and the step is the first-order
// dt = <p - c, c'> / |c'|^2.
#pragma once
#include "parametric/geometry/parametric_curve.hpp"
#include "projection/projection_result.hpp"
#include "seeding/curve_sample_index.hpp"

namespace footpoint::curve {

// The method `curvature_circle` from options.initial[0] or the nearest sample's t; outside_domain
// when it converges outside [tmin, tmax].
ProjectionResult curvature_circle(const CurveFormulas& formulas, const ParamInterval& domain,
                                  const CurveSampleIndex& index, Vec3 p, const Options& options);

}  // namespace footpoint::curve
