// How every iterative method reads the request's Options (tolerance, iteration budget), and the
// stopping rule of the curve solvers (implicit curves and surfaces' paper methods, parametric
// curves). The parametric surfaces' methods read the Options here too but stop by a rule of their
// own (parametric/solvers/surface_convergence.hpp), which differs in substance: it tests the step
// and the orthogonality residual together, against the domain's parameter scale, with the
// residual's rounding floor and a stall count, and masks the residual of a parameter held on its
// bound; the rule here stops on the step alone, against max(1, |X|), and the residuals are judged
// once the iteration has stopped (a stall is reported as such, degenerate). Either rule in the
// other's place would stop the iterations at other steps, and so change their answers.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "projection/projection_result.hpp"

namespace footpoint {

// The default relative step tolerance: 1e-15 is a few units in the last place, the iterates have
// stopped moving.
inline constexpr double kDefaultTolerance = 1e-15;

// options.tolerance when given (> 0), else kDefaultTolerance.
inline double step_tolerance(const Options& options) {
  return options.tolerance > 0.0 ? options.tolerance : kDefaultTolerance;
}

// options.max_iterations when given (> 0), else the method's own budget.
inline int iteration_budget(const Options& options, int method_default) {
  return options.max_iterations > 0 ? options.max_iterations : method_default;
}

}  // namespace footpoint

namespace footpoint::curve {

struct IterationControl {
  // Stop when the step is below step_tolerance * max(1, |X|) (relative position / parameter
  // step).
  double step_tolerance = kDefaultTolerance;
  // Rounding floor: a step below floor_factor * step_tolerance * max(1, |X|) that no longer
  // shrinks is rounding noise of the update formula, not progress; the iteration stops there too.
  double floor_factor = 100.0;
  // A result is `converged` only when its residuals (|f_i| / |grad f_i| relative to max(1, |X|),
  // and the orthogonality residual) are below this: exact derivatives leave only the rounding of
  // f and grad f near the foot point, far below 1e-12.
  double residual_tolerance = 1e-12;
  int max_iterations = 200;
  std::vector<std::array<double, 3>>* trace = nullptr;  // per-iteration increments, when asked
  // A converged result farther than this is reported as beyond_max_distance.
  double max_distance = std::numeric_limits<double>::infinity();

  void record(double a, double b = 0.0, double c = 0.0) const {
    if (trace) trace->push_back({a, b, c});
  }
  enum class Progress {
    running,    // keep iterating
    converged,  // the step is below step_tolerance: stop
    at_floor,   // the step is at the rounding floor and no longer shrinks: stop if the residuals
                // are met, otherwise (a slowly converging iteration) go on
  };
  // Classifies the step `step` just taken at a point of size `size`; `previous` carries the last
  // step between calls (start it at kInfinity).
  Progress progress(double step, double size, double& previous) const {
    const double scale = std::max(1.0, size);
    const double last = previous;
    previous = step;
    if (step <= step_tolerance * scale) return Progress::converged;
    if (step <= floor_factor * step_tolerance * scale && step >= last) return Progress::at_floor;
    return Progress::running;
  }
  // For quadratically convergent iterations (Newton): stop at the tolerance or at the floor.
  bool stop(double step, double size, double& previous) const {
    return progress(step, size, previous) != Progress::running;
  }
};

// Options -> control. `default_max_iterations` is the method's own budget (slow first-order
// iterations need more); options.tolerance, when given, sets both tolerances.
inline IterationControl make_control(const Options& options, int default_max_iterations,
                                     std::vector<std::array<double, 3>>* trace) {
  IterationControl c;
  c.step_tolerance = step_tolerance(options);
  if (options.tolerance > 0.0) c.residual_tolerance = std::max(options.tolerance, c.residual_tolerance);
  c.max_iterations = iteration_budget(options, default_max_iterations);
  c.trace = options.trace ? trace : nullptr;
  c.max_distance = options.max_distance;
  return c;
}

inline constexpr double kInfinity = std::numeric_limits<double>::infinity();

// The status of a result at `distance` that its method judged `status`.
inline Status within_max_distance(Status status, double distance, const IterationControl& control) {
  return status == Status::converged && distance > control.max_distance ? Status::beyond_max_distance
                                                                        : status;
}

}  // namespace footpoint::curve
