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
// Newton's last step: a convex step short next to the length over which the partials change,
// |Δ|∞ |s''| <= kTaylorStep min(|s_u|, |s_v|) (|s''| the largest second partial), moves the jet
// as its own Taylor expansion says, to rounding:
//   s(t + Δ) = s + s_u Δu + s_v Δv + ½ (s_uu Δu^2 + 2 s_uv Δu Δv + s_vv Δv^2) + O(|Δ|^3 s''')
//   s_u(t + Δ) = s_u + s_uu Δu + s_uv Δv + O(|Δ|^2 s''')   (likewise s_v; s'' + O(|Δ| s''')),
// where, with s''' of the order of |s''|^2 / |s'| (a surface that changes on one length scale),
// the remainders are about (|Δ| |s''| / |s'|)^2 <= 1e-16 relative: the rounding of s and its
// partials. Such a step takes the expanded jet instead of evaluating the formulas - not twice in
// a row, so that a slow (not quadratic) convergence still sees a fresh evaluation every other
// step. The step after it tests convergence there as after any other.
constexpr double kTaylorStep = 1e-8;
// A step at most this x the parameter scale that is not below kShrink x the previous one is
// stagnant; three in a row end the solve (the residual must still be below kStalledResidual).
constexpr double kStagnantStep = 1e-9;
constexpr double kShrink = 0.5;
// The early stop (projected_newton.hpp): the Lipschitz constant of H is estimated from its change
// over the last step, times this; ties within kTie (relative) of the cutoff count as not better.
constexpr double kLipschitzSafety = 4.0;
constexpr double kTie = 1e-13;

}  // namespace

LocalSolution projected_newton(const SurfaceFormulas& formulas, const ParamBox& box, const Vec3& p, double u0,
                               double v0, const ConvergenceCriteria& criteria,
                               std::vector<std::array<double, 3>>* trace, const EarlyStop* early,
                               const SurfaceJet* start_jet) {
  const double lo[2] = {box.umin, box.vmin}, hi[2] = {box.umax, box.vmax};
  const double width[2] = {box.umax - box.umin, box.vmax - box.vmin};
  const double norm_p = norm(p);
  double t[2] = {std::clamp(u0, lo[0], hi[0]), std::clamp(v0, lo[1], hi[1])};

  LocalSolution sol;
  SurfaceJet jet = start_jet ? *start_jet : formulas.jet(t[0], t[1]);
  Status status = Status::max_iterations;
  ConvergenceTest test(criteria);
  double last_step_inf = std::numeric_limits<double>::infinity();
  int stagnant_steps = 0;
  bool expanded = false;  // the jet is the Taylor expansion of the previous one
  // the previous iterate (first: the caller's reference point) and its H (upper triangle), for
  // the early stop's Lipschitz estimate
  double t_prev[2] = {0.0, 0.0}, H_prev[3] = {0.0, 0.0, 0.0};
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

    // Newton direction on the free parameters, with H made positive definite where it is not.
    double d[2] = {0.0, 0.0};
    double neg_dir[2] = {0.0, 0.0};  // direction of negative curvature, if any
    bool convex = true;
    const double a = H[0][0], b = H[0][1], c = H[1][1];
    const double hs = std::max({std::abs(a), std::abs(b), std::abs(c)});
    const double det = a * c - b * b;
    // H positive definite with λ1 = det / λ2 >= det / (a + c) >= kSemidefinite hs: the Newton
    // step itself (what the eigen-decomposition below gives there, without its square roots)
    const bool definite = free_[0] && free_[1] && a > 0.0 && det >= kSemidefinite * hs * (a + c);
    if (definite) {
      d[0] = -(c * g[0] - b * g[1]) / det;
      d[1] = -(a * g[1] - b * g[0]) / det;
    } else if (free_[0] && free_[1]) {
      // H = λ1 e1 e1^T + λ2 e2 e2^T; the step uses |λ_i| (bounded away from 0): the Newton step
      // where H is positive definite, and a descent step of natural length along negative
      // curvature where it is not
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
    const double newton_step[2] = {d[0], d[1]};  // before the cap below (the early stop's δ)
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
    // on a face (one parameter held on its bound): the free one and the held one
    const bool on_face = free_[0] != free_[1];
    const int fi = free_[0] ? 0 : 1, hj = 1 - fi;
    if (may_stop_early && have_prev && (definite || (on_face && H[fi][fi] > 0.0))) {
      // the Newton step on the free parameters, and the smaller eigenvalue of H there
      const double* delta = newton_step;
      const double lambda_min =
          definite ? det / (0.5 * (a + c) + std::sqrt(0.25 * (a - c) * (a - c) + b * b))  // det / λ2
                   : H[fi][fi];
      // the ball around t (or the point t + δ) inside the domain - on a face, along the free
      // parameter (the held one is on its bound)
      auto within = [&](double c0, double c1, double radius) {
        const bool in0 =
            c0 - radius > lo[0] && c0 + radius<hi[0], in1 = c1 - radius> lo[1] && c1 + radius < hi[1];
        return (in0 || !free_[0]) && (in1 || !free_[1]);
      };
      // the early stop (projected_newton.hpp)
      const double dt0 = t[0] - t_prev[0], dt1 = t[1] - t_prev[1];
      const double dH0 = H[0][0] - H_prev[0], dH1 = H[0][1] - H_prev[1], dH2 = H[1][1] - H_prev[2];
      const double dH2n = dH0 * dH0 + 2.0 * dH1 * dH1 + dH2 * dH2, dt2 = dt0 * dt0 + dt1 * dt1;
      const double dn2 = delta[0] * delta[0] + delta[1] * delta[1];
      // L |δ| <= λ/4 in squares, the square roots only when it holds
      if (dt2 > 0.0 &&
          kLipschitzSafety * kLipschitzSafety * dH2n * dn2 <= 0.0625 * lambda_min * lambda_min * dt2) {
        const double L = kLipschitzSafety * std::sqrt(dH2n / dt2);
        const double dn = std::sqrt(dn2);
        const double R = 2.0 * dn;  // the ball holding the basin's only stationary point
        // on a face, the held parameter's gradient pushes out of the box over the whole ball (it
        // changes by at most |H_ij| R + L R^2 there), so the solve stays on the face: the 1-D
        // problem along it is the basin's
        const bool held = !on_face || std::abs(g[hj]) > std::abs(b) * R + L * R * R;
        if (held && within(t[0], t[1], R)) {
          for (int i = 0; i < early->minimiser_count; ++i) {
            const double m0 = early->minimisers[i][0], m1 = early->minimisers[i][1];
            if (on_face && (hj == 0 ? m0 : m1) != t[hj]) continue;  // not on this face
            const double e0 = m0 - t[0], e1 = m1 - t[1];
            if (e0 * e0 + e1 * e1 <= R * R) {
              sol.u = m0;
              sol.v = m1;
              sol.jet = jet;
              sol.distance = std::numeric_limits<double>::infinity();
              sol.abandoned = true;
              return sol;
            }
          }
        }
        // the predicted minimiser inside the box (on a face: inside the face): the box does not
        // cut the basin off
        const bool inside = held && within(t[0] + delta[0], t[1] + delta[1], 0.0);
        if (inside && early->cutoff < std::numeric_limits<double>::infinity()) {
          // 2 min f >= |r|^2 + <g, δ> - (8/3) L |δ|^3
          const double low2 =
              dot(r, r) + (g[0] * delta[0] + g[1] * delta[1]) - (8.0 / 3.0) * L * dn * dn * dn;
          const double tie =
              kTie * early->cutoff + 32.0 * std::numeric_limits<double>::epsilon() * (norm_p + norm(jet.s));
          if (low2 >= 0.0 && std::sqrt(low2) >= early->cutoff - tie) {
            sol.u = t[0] + delta[0];
            sol.v = t[1] + delta[1];
            sol.jet = jet;
            sol.distance = std::sqrt(low2);
            sol.abandoned = true;
            return sol;
          }
        }
      }
    }
    t_prev[0] = t[0], t_prev[1] = t[1];
    H_prev[0] = H[0][0], H_prev[1] = H[0][1], H_prev[2] = H[1][1];
    have_prev = true;
    if (!convex && step_inf <= kNoiseSteps * criteria.step_bound(t[0], t[1])) {
      // a stationary point with negative curvature: leave it downhill along that direction
      const double len = kEscape * std::min(width[0], width[1]);
      for (int i = 0; i < 2; ++i) d[i] = neg_dir[i] * len;
    }

    // Armijo backtracking along the projection arc t(α) = clamp(t + α d). The decrease is
    // computed as f(t') - f(t) = ½ (s' - s)·((s' - p) + (s - p)), without the cancellation of two
    // large f for far points. Small convex steps are Newton's local regime: taken as they are.
    bool accepted = false;
    bool vanishes = false;  // the full step changes no parameter: they are as good as they can be
    double tn[2] = {t[0], t[1]};
    SurfaceJet jn;
    double alpha = 1.0;
    const Vec3 r0 = jet.s - p;
    const double local_step = kLocalStep * step_scale;
    const bool expand = convex && !expanded &&
                        step_inf * step_inf * std::max({norm2(jet.suu), norm2(jet.suv), norm2(jet.svv)}) <=
                            kTaylorStep * kTaylorStep * std::min(norm2(jet.su), norm2(jet.sv));
    expanded = false;
    for (int ls = 0; ls < kMaxBacktracks && !accepted; ++ls, alpha *= 0.5) {
      for (int i = 0; i < 2; ++i) tn[i] = std::clamp(t[i] + alpha * d[i], lo[i], hi[i]);
      const double dt0 = tn[0] - t[0], dt1 = tn[1] - t[1];
      if (dt0 == 0.0 && dt1 == 0.0) {
        vanishes = ls == 0;
        break;
      }
      const double slope = g[0] * dt0 + g[1] * dt1;
      Vec3 sn;
      if (ls == 0 && expand && tn[0] == t[0] + d[0] && tn[1] == t[1] + d[1]) {  // d not clipped
        jn.suu = jet.suu, jn.suv = jet.suv, jn.svv = jet.svv;
        jn.su = jet.su + jet.suu * dt0 + jet.suv * dt1;
        jn.sv = jet.sv + jet.suv * dt0 + jet.svv * dt1;
        jn.s = taylor_point(jet, dt0, dt1);
        sn = jn.s;
        expanded = true;
      } else if (ls == 0) {
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
