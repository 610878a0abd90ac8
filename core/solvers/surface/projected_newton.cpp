#include "solvers/surface/projected_newton.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "solvers/surface/paper_iteration.hpp"

namespace footpoint::surface {

namespace {
// Armijo's sufficient decrease: f(t + Δ) <= f(t) + c <g, Δ>.
constexpr double kSufficientDecrease = 1e-4;
constexpr int kMaxBacktracks = 60;
// H counts as positive semidefinite when its smallest eigenvalue is >= -this x its largest entry
// (rounding of a singular H); eigenvalues are used at no less than this in absolute value.
constexpr double kSemidefinite = 1e-12;
// Steps along negative curvature from a stationary saddle: this fraction of the domain's width.
constexpr double kEscape = 1e-3;
// A gradient this many tolerances small at an indefinite H is a stationary saddle.
constexpr double kNoiseSteps = 1e3;
// Convex steps at most this x the parameter scale are taken without the decrease test (Newton's
// local regime, where f changes by little more than its rounding).
constexpr double kLocalStep = 1e-6;
// A step at most this x the parameter scale that is not below kShrink x the previous one is
// stagnant; three in a row end the solve (the residual must still be below kStalledResidual).
constexpr double kStagnantStep = 1e-9;
constexpr double kShrink = 0.5;

}  // namespace

LocalSolution projected_newton(const SurfaceFormulas& formulas, const ParamBox& box, const Vec3& p, double u0,
                               double v0, const ConvergenceCriteria& criteria,
                               std::vector<std::array<double, 3>>* trace) {
  const double lo[2] = {box.umin, box.vmin}, hi[2] = {box.umax, box.vmax};
  const double width[2] = {box.umax - box.umin, box.vmax - box.vmin};
  double t[2] = {std::clamp(u0, lo[0], hi[0]), std::clamp(v0, lo[1], hi[1])};

  LocalSolution sol;
  SurfaceJet jet = formulas.jet(t[0], t[1]);
  Status status = Status::max_iterations;
  ConvergenceTest test(criteria);
  double last_step_inf = std::numeric_limits<double>::infinity();
  int stagnant_steps = 0;
  if (!is_finite(jet)) status = Status::non_finite;

  while (status == Status::max_iterations) {
    const Vec3 r = jet.s - p;
    const double g[2] = {dot(r, jet.su), dot(r, jet.sv)};
    const double H[2][2] = {{dot(jet.su, jet.su) + dot(r, jet.suu), dot(jet.su, jet.sv) + dot(r, jet.suv)},
                            {dot(jet.su, jet.sv) + dot(r, jet.suv), dot(jet.sv, jet.sv) + dot(r, jet.svv)}};
    bool free_[2];
    for (int i = 0; i < 2; ++i) free_[i] = !((t[i] <= lo[i] && g[i] > 0.0) || (t[i] >= hi[i] && g[i] < 0.0));
    if (!free_[0] && !free_[1]) {  // a corner with the gradient pointing out of the box: KKT point
      status = Status::converged;
      break;
    }

    // Newton direction on the free parameters, with H made positive definite where it is not.
    double d[2] = {0.0, 0.0};
    double neg_dir[2] = {0.0, 0.0};  // direction of negative curvature, if any
    bool convex = true;
    if (free_[0] && free_[1]) {
      // H = λ1 e1 e1^T + λ2 e2 e2^T; the step uses |λ_i| (bounded away from 0): the Newton step
      // where H is positive definite, and a descent step of natural length along negative
      // curvature where it is not
      const double a = H[0][0], b = H[0][1], c = H[1][1];
      const double hs = std::max({std::abs(a), std::abs(b), std::abs(c)});
      const double mid = 0.5 * (a + c), rad = std::sqrt(0.25 * (a - c) * (a - c) + b * b);
      const double l1 = mid - rad, l2 = mid + rad;  // l1 <= l2
      convex = l1 >= -kSemidefinite * hs;
      // unit eigenvector of l1: (b, l1 - a) or (l1 - c, b), whichever is better conditioned
      double e0 = b, e1 = l1 - a;
      if (std::abs(e0) + std::abs(e1) < std::abs(l1 - c) + std::abs(b)) e0 = l1 - c, e1 = b;
      double en = std::sqrt(e0 * e0 + e1 * e1);
      if (!(en > 0.0)) e0 = 1.0, e1 = 0.0, en = 1.0;  // H = λ I
      e0 /= en;
      e1 /= en;
      const double floor_l = std::max(kSemidefinite * hs, std::numeric_limits<double>::min());
      const double g1 = e0 * g[0] + e1 * g[1], g2 = -e1 * g[0] + e0 * g[1];
      const double s1 = g1 / std::max(std::abs(l1), floor_l), s2 = g2 / std::max(std::abs(l2), floor_l);
      d[0] = -(s1 * e0 - s2 * e1);
      d[1] = -(s1 * e1 + s2 * e0);
      if (!convex) neg_dir[0] = e0, neg_dir[1] = e1;
    } else {
      const int i = free_[0] ? 0 : 1;
      const double h = H[i][i];
      convex = h >= -kSemidefinite * std::abs(h);
      d[i] = -g[i] / std::max(std::abs(h), std::numeric_limits<double>::min());
      if (!convex) neg_dir[i] = 1.0;
    }
    // no step longer than the domain
    for (int i = 0; i < 2; ++i)
      if (std::abs(d[i]) > width[i]) {
        const double s = width[i] / std::abs(d[i]);
        d[0] *= s;
        d[1] *= s;
      }
    if (!std::isfinite(d[0]) || !std::isfinite(d[1])) {
      status = Status::non_finite;
      break;
    }

    const double step_inf = std::max(free_[0] ? std::abs(d[0]) : 0.0, free_[1] ? std::abs(d[1]) : 0.0);
    const Orthogonality o = orthogonality(p, jet.s, jet.su, jet.sv);
    bool done = test.converged(step_inf, t[0], t[1], o, {free_[0], free_[1]});
    // Newton's steps shrink quadratically; tiny steps that stop shrinking are rounding noise made
    // large by a nearly singular H (p near a centre of curvature): the parameters are as good as
    // the formulas' rounding lets them be.
    const bool stagnant = step_inf <= kStagnantStep * criteria.step_bound(t[0], t[1]) / criteria.tolerance &&
                          step_inf > kShrink * last_step_inf;
    stagnant_steps = stagnant ? stagnant_steps + 1 : 0;
    last_step_inf = step_inf;
    if (stagnant_steps >= 3 && std::max(free_[0] ? o.relative[0] : 0.0, free_[1] ? o.relative[1] : 0.0) <= kStalledResidual)
      done = true;
    if (convex && done) {
      status = Status::converged;
      break;
    }
    if (sol.iterations >= criteria.max_iterations) break;
    if (!convex && step_inf <= kNoiseSteps * criteria.step_bound(t[0], t[1])) {
      // a stationary point with negative curvature: leave it downhill along that direction
      const double len = kEscape * std::min(width[0], width[1]);
      for (int i = 0; i < 2; ++i) d[i] = neg_dir[i] * len;
    }

    // Armijo backtracking along the projection arc t(α) = clamp(t + α d). The decrease is
    // computed as f(t') - f(t) = ½ (s' - s)·((s' - p) + (s - p)), without the cancellation of two
    // large f for far points. Small convex steps are Newton's local regime: taken as they are.
    bool accepted = false;
    double tn[2] = {t[0], t[1]};
    SurfaceJet jn;
    double alpha = 1.0;
    const Vec3 r0 = jet.s - p;
    const double local_step = kLocalStep * criteria.step_bound(t[0], t[1]) / criteria.tolerance;
    for (int ls = 0; ls < kMaxBacktracks && !accepted; ++ls, alpha *= 0.5) {
      for (int i = 0; i < 2; ++i) tn[i] = std::clamp(t[i] + alpha * d[i], lo[i], hi[i]);
      const double dt0 = tn[0] - t[0], dt1 = tn[1] - t[1];
      if (dt0 == 0.0 && dt1 == 0.0) break;
      const double slope = g[0] * dt0 + g[1] * dt1;
      Vec3 sn;
      if (ls == 0) {
        jn = formulas.jet(tn[0], tn[1]);
        sn = jn.s;
      } else {
        sn = formulas.point(tn[0], tn[1]);
      }
      const double df = 0.5 * dot(sn - jet.s, (sn - p) + r0);
      const bool local = convex && std::max(std::abs(dt0), std::abs(dt1)) <= local_step;
      accepted = is_finite(sn) && std::isfinite(df) && (df <= kSufficientDecrease * slope || local);
      if (accepted && ls > 0) {
        jn = formulas.jet(tn[0], tn[1]);
        accepted = is_finite(jn);
      } else if (accepted) {
        accepted = is_finite(jn);
      }
    }
    if (!accepted) {  // no decrease to be had: rounding level, or a descent direction lost to it
      status = done ? Status::converged : Status::degenerate;
      break;
    }
    const double dt0 = tn[0] - t[0], dt1 = tn[1] - t[1];
    if (trace) trace->push_back({dt0, dt1, 0.0});
    t[0] = tn[0];
    t[1] = tn[1];
    jet = jn;
    ++sol.iterations;
    sol.step_norm = std::sqrt(dt0 * dt0 + dt1 * dt1);
  }

  sol.u = t[0];
  sol.v = t[1];
  sol.jet = jet;
  sol.status = status;
  sol.distance = norm(p - jet.s);
  return sol;
}

}  // namespace footpoint::surface
