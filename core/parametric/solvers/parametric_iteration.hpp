// The loop shared by the local methods of a parametric curve (newton, curvature_circle): from t0
// (options.initial[0], else the parameter of the sample nearest p) repeat t <- t + dt(t), exactly
// as the method computes it, with no clamping to [tmin, tmax], until the step stops moving
// (iteration_control.hpp), then finish_parametric_result: converged only inside the domain (else
// outside_domain) and with the orthogonality residual met (else degenerate: a stall). With
// options.trace every step (dt, 0, 0) is recorded.
#pragma once
#include <array>
#include <cmath>
#include <vector>

#include "parametric/geometry/parametric_curve.hpp"
#include "parametric/solvers/parametric_curve_summary.hpp"
#include "projection/projection_result.hpp"
#include "seeding/curve_sample_index.hpp"
#include "solvers/iteration_control.hpp"

namespace footpoint::curve {

// What one iteration of a method returns: the step, or why there is none.
struct ParamStep {
  double dt = 0.0;
  Status failure = Status::converged;  // degenerate / non_finite stop the iteration
};

// What a step at the rounding floor (no longer shrinking) concludes: a quadratically convergent
// iteration (Newton) has converged there; a linearly convergent one (the curvature circle, [GSA]
// Remark 2) only when the orthogonality residual meets the tolerance too, else it goes on.
enum class AtFloor { converged, converged_if_orthogonal };

// `step(jet)` computes the method's ParamStep from the jet of c at the iterate.
template <class Step>
ProjectionResult iterate_parametric(const char* method, const CurveFormulas& formulas,
                                    const ParamInterval& domain, const CurveSampleIndex& index, Vec3 p,
                                    const Options& options, int default_max_iterations, AtFloor at_floor,
                                    Step&& step) {
  std::vector<std::array<double, 3>> trace;
  const IterationControl control = make_control(options, default_max_iterations, &trace);
  double t = parametric_start(domain, index, p, options);
  Status status = Status::max_iterations;
  double last = 0.0, previous = kInfinity;
  int n = 0;
  while (n < control.max_iterations) {
    const ParamStep s = step(formulas.jet(t));
    if (s.failure != Status::converged) {
      status = s.failure;
      break;
    }
    t += s.dt;
    ++n;
    last = std::fabs(s.dt);
    control.record(s.dt);
    if (!std::isfinite(t)) {
      status = Status::non_finite;
      break;
    }
    const IterationControl::Progress progress = control.progress(last, std::fabs(t), previous);
    if (progress == IterationControl::Progress::converged ||
        (progress == IterationControl::Progress::at_floor &&
         (at_floor == AtFloor::converged ||
          parametric_residual_met(parametric_result(formulas, domain, p, t, method), control)))) {
      status = Status::converged;
      break;
    }
  }
  return finish_parametric_result(formulas, domain, p, t, method, status, n, last, control, std::move(trace));
}

}  // namespace footpoint::curve
