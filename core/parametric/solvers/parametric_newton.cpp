#include "parametric/solvers/parametric_newton.hpp"

#include <cmath>

#include "parametric/solvers/parametric_iteration.hpp"

namespace footpoint::curve {

ProjectionResult parametric_newton(const CurveFormulas& formulas, const ParamInterval& domain,
                                   const CurveSampleIndex& index, Vec3 p, const Options& options) {
  auto newton = [&](const CurveJet& j) {
    const Vec3 d = j.c - p;
    const double g = dot(d, j.d1);
    const double dg = dot(j.d1, j.d1) + dot(d, j.d2);
    ParamStep s;
    if (!std::isfinite(g) || !std::isfinite(dg))
      s.failure = Status::non_finite;
    else if (dg == 0.0)
      s.failure = Status::degenerate;
    else
      s.dt = -g / dg;
    return s;
  };
  return iterate_parametric("newton", formulas, domain, index, p, options, 100, AtFloor::converged, newton);
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
