// Newton's method for the foot point on a parametric curve: the stationarity condition of
// phi(t) = |c(t) - p|^2 / 2,
//   g(t) = phi'(t) = <c(t) - p, c'(t)> = 0,   g'(t) = |c'(t)|^2 + <c(t) - p, c''(t)>,
// with exact derivatives: t <- t - g / g'.
#pragma once
#include "parametric/geometry/parametric_curve.hpp"
#include "projection/projection_result.hpp"
#include "seeding/curve_sample_index.hpp"
#include "solvers/iteration_control.hpp"

namespace footpoint::curve {

// The method `newton`: unconstrained Newton from options.initial[0] or the nearest sample's t.
// outside_domain when it converges outside [tmin, tmax].
ProjectionResult parametric_newton(const CurveFormulas& formulas, const ParamInterval& domain,
                                   const CurveSampleIndex& index, Vec3 p, const Options& options);

// Safeguarded Newton inside the bracket [a, b] where g(a) <= 0 <= g(b) (a minimum of phi lies
// inside): a Newton step that leaves the bracket, or that a non-positive g' makes meaningless, is
// replaced by bisection. Starts at t0 in [a, b]. Returns the parameter; iterations counted.
double bracketed_newton(const CurveFormulas& formulas, Vec3 p, double a, double b, double t0,
                        const IterationControl& control, int& iterations, double& step);

}  // namespace footpoint::curve
