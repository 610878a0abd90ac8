#include "implicit/solvers/paper_iteration.hpp"

#include <algorithm>
#include <cmath>

#include "implicit/solvers/implicit_curve_summary.hpp"

namespace footpoint::curve {

Vec3 paper_start(Vec3 p, const Options& options, bool planar) {
  if (options.initial) {
    const auto& s = *options.initial;
    return {s[0], s[1], planar ? 0.0 : s[2]};
  }
  return p - Vec3{0.1, 0.1, planar ? 0.0 : 0.1};
}

bool newton_onto_surface(const ImplicitJet& j, int i, Vec3 x, Vec3& out) {
  const double g2 = norm2(j.grad[i]);
  if (!(g2 > 0.0)) return false;
  out = x - (j.f[i] / g2) * j.grad[i];
  return true;
}

bool paper_iteration_done(const ImplicitEquations& equations, const PaperGoal& goal, Vec3 x, double step,
                          double& previous, const IterationControl& control) {
  if (control.progress(step, norm(x), previous) == IterationControl::Progress::running) return false;
  return foot_residuals_met(equations, goal.p, x, control, goal.orthogonal);
}

bool take_paper_step(const ImplicitEquations& equations, const PaperGoal& goal, Vec3 x1, int n, double limit,
                     double& previous, const IterationControl& control, Landing& out) {
  if (!is_finite(x1)) {
    out.status = Status::non_finite;
    return true;
  }
  const Vec3 dx = x1 - out.x;
  out.step = norm(dx);
  out.x = x1;
  out.iterations = n + 1;
  control.record(dx.x, dx.y, dx.z);
  if (norm(x1) > limit) {
    out.status = Status::diverged;
    return true;
  }
  if (paper_iteration_done(equations, goal, x1, out.step, previous, control)) {
    out.status = Status::converged;
    return true;
  }
  return false;
}

ProjectionResult paper_result(const ImplicitEquations& equations, const Box3& box, Vec3 p, const char* method,
                              const Landing& end, const IterationControl& control, const PaperGoal& goal,
                              std::vector<std::array<double, 3>> trace) {
  const Vec3 x = end.x;
  ProjectionResult r = implicit_result(equations, box, p, x, method);
  r.summary.iterations = end.iterations;
  r.summary.step_norm = end.step;
  r.summary.starts = 1;
  Status status = end.status;
  if (status == Status::converged) {
    if (!implicit_residuals_met(r.summary, x, control, goal.orthogonal))
      status = Status::degenerate;
    else if (!goal.orthogonal && !implicit_residuals_met(r.summary, x, control, true))
      status = Status::not_orthogonal;
    else if (!box.contains(x, 1e-12 * std::max(1.0, norm(x))))
      status = Status::outside_domain;
  }
  r.summary.status = within_max_distance(status, r.distance, control);
  r.trace = std::move(trace);
  return r;
}

}  // namespace footpoint::curve
