#include "solvers/curve/parametric_newton.hpp"

#include <cmath>

#include "solvers/curve/parametric_curve_summary.hpp"

namespace footpoint::curve {

ProjectionResult parametric_newton(const CurveFormulas& formulas, const ParamInterval& domain,
                                   const CurveSampleIndex& index, Vec3 p, const Options& options) {
  std::vector<std::array<double, 3>> trace;
  const IterationControl control = make_control(options, 100, &trace);
  double t = parametric_start(domain, index, p, options);
  Status status = Status::max_iterations;
  double step = 0.0, previous = kInfinity;
  int n = 0;
  while (n < control.max_iterations) {
    const CurveJet j = formulas.jet(t);
    const Vec3 d = j.c - p;
    const double g = dot(d, j.d1);
    const double dg = dot(j.d1, j.d1) + dot(d, j.d2);
    if (!std::isfinite(g) || !std::isfinite(dg)) {
      status = Status::non_finite;
      break;
    }
    if (dg == 0.0) {
      status = Status::degenerate;
      break;
    }
    const double dt = -g / dg;
    t += dt;
    ++n;
    step = std::fabs(dt);
    control.record(dt);
    if (!std::isfinite(t)) {
      status = Status::non_finite;
      break;
    }
    if (control.stop(step, std::fabs(t), previous)) {
      status = Status::converged;
      break;
    }
  }
  return finish_parametric_result(formulas, domain, p, t, "newton", status, n, step, control,
                                  std::move(trace));
}

double bracketed_newton(const CurveFormulas& formulas, Vec3 p, double a, double b, double t0,
                        const IterationControl& control, int& iterations, double& step) {
  double t = t0, previous = kInfinity;
  iterations = 0;
  step = 0.0;
  while (iterations < control.max_iterations) {
    const CurveJet j = formulas.jet(t);
    const Vec3 d = j.c - p;
    const double g = dot(d, j.d1);
    const double dg = dot(j.d1, j.d1) + dot(d, j.d2);
    if (g == 0.0) break;
    if (g < 0.0)
      a = t;  // the minimum lies to the right of t
    else
      b = t;
    // Newton inside the (closed) bracket, else bisection. A converged Newton step lands on t
    // itself, which is a bracket end: the bracket is closed so that this is not taken for an
    // escape.
    double next = dg > 0.0 ? t - g / dg : 0.5 * (a + b);
    if (!(next >= a && next <= b)) next = 0.5 * (a + b);
    ++iterations;
    step = std::fabs(next - t);
    control.record(next - t);
    t = next;
    if (control.stop(step, std::fabs(t), previous) || b - a <= 4e-16 * std::max(1.0, std::fabs(t))) break;
  }
  return t;
}

}  // namespace footpoint::curve
