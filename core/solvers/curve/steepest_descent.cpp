#include "solvers/curve/steepest_descent.hpp"

#include <cmath>

#include "solvers/curve/implicit_curve_summary.hpp"

namespace footpoint::curve {
namespace {

// Iterates farther than this from the origin (relative to the start) have left any sensible region.
constexpr double kDivergence = 1e12;

// One Newton step onto f_i = 0 along grad f_i: x - f_i / |grad f_i|^2 grad f_i (eq. (9)).
bool newton_onto_surface(const ImplicitJet& j, int i, Vec3 x, Vec3& out) {
  const double g2 = norm2(j.grad[i]);
  if (!(g2 > 0.0)) return false;
  out = x - (j.f[i] / g2) * j.grad[i];
  return true;
}

}  // namespace

Vec3 paper_start(Vec3 p, const Options& options, bool planar) {
  if (options.initial) {
    const auto& s = *options.initial;
    return {s[0], s[1], planar ? 0.0 : s[2]};
  }
  return p - Vec3{0.1, 0.1, planar ? 0.0 : 0.1};
}

Landing land_on_curve(const ImplicitEquations& equations, Vec3 x0, const IterationControl& control) {
  Landing out;
  out.x = x0;
  const double limit = kDivergence * std::max(1.0, norm(x0));
  double previous = kInfinity;
  for (int n = 0;; ++n) {
    const ImplicitJet jx = equations.jet(out.x);
    if (!std::isfinite(jx.f[0]) || !std::isfinite(jx.f[1])) {
      out.status = Status::non_finite;
      return out;
    }
    // Termination of Algorithm 1: |f1(X)| and |f2(X)| below epsilon (here relative, scaled by
    // the gradients, so that the test does not depend on how f is normalised).
    const double size = std::max(1.0, norm(out.x));
    const double eps = control.step_tolerance * size;
    if (std::fabs(jx.f[0]) <= eps * norm(jx.grad[0]) && std::fabs(jx.f[1]) <= eps * norm(jx.grad[1])) {
      out.status = Status::converged;
      return out;
    }
    if (n >= control.max_iterations) {
      out.status = Status::max_iterations;
      return out;
    }
    Vec3 y, x1;
    if (!newton_onto_surface(jx, 0, out.x, y)) {
      out.status = Status::degenerate;
      return out;
    }
    const ImplicitJet jy = equations.jet(y);
    if (!newton_onto_surface(jy, 1, y, x1)) {
      out.status = Status::degenerate;
      return out;
    }
    if (take_paper_step(equations, x1, x1, n, limit, previous, control, false, out)) return out;
  }
}

bool paper_iteration_done(const ImplicitEquations& equations, Vec3 p, Vec3 x, double step, double& previous,
                          const IterationControl& control, bool with_orthogonality) {
  if (control.progress(step, norm(x), previous) == IterationControl::Progress::running) return false;
  return foot_residuals_met(equations, p, x, control, with_orthogonality);
}

bool take_paper_step(const ImplicitEquations& equations, Vec3 p, Vec3 x1, int n, double limit,
                     double& previous, const IterationControl& control, bool with_orthogonality,
                     Landing& out) {
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
  if (paper_iteration_done(equations, p, x1, out.step, previous, control, with_orthogonality)) {
    out.status = Status::converged;
    return true;
  }
  return false;
}

ProjectionResult paper_result(const ImplicitEquations& equations, const Box3& box, Vec3 p, Vec3 x,
                              const char* method, Status status, int iterations, double step,
                              const IterationControl& control, bool with_orthogonality) {
  ProjectionResult r = implicit_result(equations, box, p, x, method);
  r.summary.iterations = iterations;
  r.summary.step_norm = step;
  r.summary.starts = 1;
  if (status == Status::converged) {
    // `converged` only when the foot-point conditions hold: on the curve and orthogonal. A method
    // that only lands on the curve (Algorithm 1) reports not_orthogonal there; iterates that stopped
    // moving where the residuals are not small are a stall, reported as degenerate.
    if (!implicit_residuals_met(r.summary, x, control, with_orthogonality))
      status = Status::degenerate;
    else if (!with_orthogonality && !implicit_residuals_met(r.summary, x, control, true))
      status = Status::not_orthogonal;
    else if (!box.contains(x, 1e-12 * std::max(1.0, norm(x))))
      status = Status::outside_domain;
  }
  r.summary.status = within_max_distance(status, r.distance, control);
  return r;
}

ProjectionResult steepest_descent(const ImplicitEquations& equations, const Box3& box, Vec3 p,
                                  const Options& options) {
  auto landed = [](const Landing& l, const IterationControl&) { return l; };
  return land_then(equations, box, p, options, "steepest_descent", landed, /*with_orthogonality=*/false);
}

}  // namespace footpoint::curve
