// The Summary of a foot point c(t) of p on a parametric curve: the orthogonality residual
// |<p - c, c'>| / (|p - c| |c'|) (at an end of the parameter interval, the first-order optimality
// residual of the distance restricted to the interval instead), and where c(t) lies.
#pragma once
#include <array>
#include <vector>

#include "parametric/geometry/curve_closure.hpp"
#include "parametric/geometry/parametric_curve.hpp"
#include "projection/projection_result.hpp"
#include "seeding/curve_sample_index.hpp"
#include "solvers/iteration_control.hpp"

namespace footpoint::curve {

// A result for c(t) as the foot of p: dim, num_params 1, params[0] = t, foot, distance,
// orthogonality, location (endpoint when t is tmin or tmax, unless the curve closes smoothly there:
// then the ends are one interior point) and on_boundary; params[0] is closed_representative(t). When p is
// (almost) on the curve the orthogonality is measured against max(|p - c|, 1e-3 max(1, |c|)).
ProjectionResult parametric_result(const CurveFormulas& formulas, const ParamInterval& domain, Vec3 p,
                                   double t, const char* method, const CurveClosure& closure = {});

// The parameter a closed curve's two ends name once (closure.periodic ["t"]): c(tmax) = c(tmin),
// and answers report tmin. Every other t is kept.
inline double closed_representative(const ParamInterval& domain, double t, const CurveClosure& closure) {
  return closure.closed && t == domain.tmax ? domain.tmin : t;
}

// The curve's two ends are one point with one tangent: no end is an endpoint.
inline bool joins_smoothly(const CurveClosure& closure) { return closure.closed && closure.smooth; }

// Whether the result's orthogonality meets the control's residual tolerance.
bool parametric_residual_met(const ProjectionResult& r, const IterationControl& control);

// The result of a local method's loop that ended at t with `status` after `iterations` steps, the
// last of length `step`: converged only if t is in the domain (else outside_domain) and the
// residual meets the tolerance (else degenerate: the iterates stalled); max_distance applied.
ProjectionResult finish_parametric_result(const CurveFormulas& formulas, const ParamInterval& domain, Vec3 p,
                                          double t, const char* method, Status status, int iterations,
                                          double step, const IterationControl& control,
                                          std::vector<std::array<double, 3>> trace);

// The start of a local method: options.initial[0], else the parameter of the sample nearest p (the
// samples of `index`, t in their params), else the middle of the domain.
double parametric_start(const ParamInterval& domain, const CurveSampleIndex& index, Vec3 p,
                        const Options& options);

}  // namespace footpoint::curve
