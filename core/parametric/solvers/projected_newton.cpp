#include "parametric/solvers/projected_newton.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "parametric/solvers/newton_direction.hpp"
#include "parametric/solvers/projection_arc_search.hpp"

namespace footpoint::surface {

namespace {
// Steps along negative curvature from a stationary saddle: this fraction of the domain's width.
constexpr double kEscape = 1e-3;
// A gradient this many tolerances small at an indefinite H is a stationary saddle.
constexpr double kNoiseSteps = 1e3;
// A step at most this x the parameter scale that is not below kShrink x the previous one is
// stagnant; three in a row end the solve (the residual must still be below kStalledResidual).
constexpr double kStagnantStep = 1e-9;
constexpr double kShrink = 0.5;
}  // namespace

LocalSolution projected_newton(const SurfaceFormulas& formulas, const ParamBox& box, const Vec3& p, double u0,
                               double v0, const ConvergenceCriteria& criteria,
                               std::vector<std::array<double, 3>>* trace, const EarlyStop* early,
                               const SurfaceJet* start_jet) {
  const Params<2> lo{box.umin, box.vmin}, hi{box.umax, box.vmax};
  const Params<2> width{box.umax - box.umin, box.vmax - box.vmin};
  const double norm_p = norm(p);
  Params<2> t{std::clamp(u0, lo[0], hi[0]), std::clamp(v0, lo[1], hi[1])};

  LocalSolution sol;
  SurfaceJet jet = start_jet ? *start_jet : formulas.jet(t[0], t[1]);
  Status status = Status::max_iterations;
  ConvergenceTest test(criteria);
  double last_step_inf = std::numeric_limits<double>::infinity();
  int stagnant_steps = 0;
  // the previous iterate (first: the caller's reference point) and its H (upper triangle), for
  // the early stop's Lipschitz estimate
  Params<2> t_prev{0.0, 0.0};
  double H_prev[3] = {0.0, 0.0, 0.0};
  bool have_prev = false;
  if (early && !std::isnan(early->reference_H[0])) {
    t_prev[0] = early->reference_t[0], t_prev[1] = early->reference_t[1];
    H_prev[0] = early->reference_H[0], H_prev[1] = early->reference_H[1], H_prev[2] = early->reference_H[2];
    have_prev = true;
  }
  if (!is_finite(jet)) status = Status::non_finite;
  // the early stop has something to compare with: a minimiser or a distance found before
  const bool may_stop_early =
      early && (early->minimiser_count > 0 || early->cutoff < std::numeric_limits<double>::infinity());

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

    // Newton's direction on the free parameters, with H made positive definite where it is not
    const NewtonDirection direction = newton_direction(H, g, free_);
    Params<2> d = direction.step;
    const bool convex = direction.convex;
    const Params<2> newton_step = d;  // before the cap below (the early stop's δ)
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
    // The stopping test needs the orthogonality residuals only for a short step, or for a
    // gradient at its rounding level (a residual at its floor ends the iteration whatever the
    // step): |g_i| <= 16 eps (|p| + |s|) |s_i| for every free i - tested in squares, with
    // (|p| + |s|)^2 <= 2 (|p|^2 + |s|^2). Otherwise the step is not settled and nothing ends here.
    const double step_scale = criteria.step_scale(t[0], t[1]);
    const bool short_step = step_inf <= std::max(criteria.tolerance, kStagnantStep) * step_scale;
    auto gradient_at_floor = [&] {
      constexpr double noise = 16.0 * std::numeric_limits<double>::epsilon();
      const double floor2 = 2.0 * noise * noise * (norm_p * norm_p + norm2(jet.s));
      return (!free_[0] || !(g[0] * g[0] > floor2 * norm2(jet.su))) &&
             (!free_[1] || !(g[1] * g[1] > floor2 * norm2(jet.sv)));
    };
    Orthogonality o;
    bool done = false;
    if (short_step || gradient_at_floor()) {
      o = orthogonality(p, norm_p, jet.s, jet.su, jet.sv);
      done = test.converged(step_inf, t[0], t[1], o, {free_[0], free_[1]});
    } else {
      test.unsettled();
    }
    // Newton's steps shrink quadratically; tiny steps that stop shrinking are rounding noise made
    // large by a nearly singular H (p near a centre of curvature): the parameters are as good as
    // the formulas' rounding lets them be.
    const bool stagnant = step_inf <= kStagnantStep * step_scale && step_inf > kShrink * last_step_inf;
    stagnant_steps = stagnant ? stagnant_steps + 1 : 0;
    last_step_inf = step_inf;
    if (stagnant_steps >= 3 &&
        std::max(free_[0] ? o.relative[0] : 0.0, free_[1] ? o.relative[1] : 0.0) <= kStalledResidual)
      done = true;
    if (convex && done) {
      status = Status::converged;
      break;
    }
    if (sol.iterations >= criteria.max_iterations) break;
    if (may_stop_early && have_prev) {
      const BasinIterate it{{t[0], t[1]},
                            {t_prev[0], t_prev[1]},
                            {{H[0][0], H[0][1]}, {H[1][0], H[1][1]}},
                            {H_prev[0], H_prev[1], H_prev[2]},
                            {g[0], g[1]},
                            r,
                            jet.s,
                            {newton_step[0], newton_step[1]},
                            {free_[0], free_[1]},
                            direction.definite,
                            direction.det,
                            norm_p};
      const BasinVerdict verdict = test_basin(it, box, *early);
      if (verdict.abandoned) {
        sol.u = verdict.u;
        sol.v = verdict.v;
        sol.jet = jet;
        sol.distance = verdict.distance;
        sol.abandoned = true;
        return sol;
      }
    }
    t_prev[0] = t[0], t_prev[1] = t[1];
    H_prev[0] = H[0][0], H_prev[1] = H[0][1], H_prev[2] = H[1][1];
    have_prev = true;
    if (!convex && step_inf <= kNoiseSteps * criteria.step_bound(t[0], t[1])) {
      // a stationary point with negative curvature: leave it downhill along that direction
      const double len = kEscape * std::min(width[0], width[1]);
      for (int i = 0; i < 2; ++i) d[i] = direction.negative_curvature[static_cast<std::size_t>(i)] * len;
    }

    // Armijo's backtracking along the projection arc (projection_arc_search.hpp)
    const ArcStep step = search_projection_arc(formulas, p, jet, t, d, lo, hi, g, convex, step_scale);
    const bool accepted = step.accepted, vanishes = step.vanishes;
    const Params<2>& tn = step.t;
    const SurfaceJet& jn = step.jet;
    if (!accepted) {  // no decrease to be had: rounding level, or a descent direction lost to it
      // A convex Newton step below the parameters' last bit is convergence whatever the residual
      // says: it is computed from a jet one rounding away from any other at these parameters.
      status = done || (vanishes && convex) ? Status::converged : Status::degenerate;
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
