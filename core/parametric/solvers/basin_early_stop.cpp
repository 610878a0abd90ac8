#include "parametric/solvers/basin_early_stop.hpp"

#include <cmath>
#include <limits>

namespace footpoint::surface {

namespace {
// L is estimated from H's change over the last step, times this; ties within kTie (relative) of
// the cutoff count as not better.
constexpr double kLipschitzSafety = 4.0;
constexpr double kTie = 1e-13;
}  // namespace

BasinVerdict test_basin(const BasinIterate& it, const ParamBox& box, const EarlyStop& early) {
  BasinVerdict verdict;
  const Params<2> lo{box.umin, box.vmin}, hi{box.umax, box.vmax};
  const double(&H)[2][2] = it.H;
  const double a = H[0][0], b = H[0][1], c = H[1][1];
  // on a face (one parameter held on its bound): the free one and the held one
  const bool on_face = it.free_[0] != it.free_[1];
  const int fi = it.free_[0] ? 0 : 1, hj = 1 - fi;
  if (!(it.definite || (on_face && H[fi][fi] > 0.0))) return verdict;
  // the Newton step on the free parameters, and the smaller eigenvalue of H there
  const Params<2>& delta = it.newton_step;
  const double lambda_min =
      it.definite ? it.det / (0.5 * (a + c) + std::sqrt(0.25 * (a - c) * (a - c) + b * b))  // det / λ2
                  : H[fi][fi];
  // the ball around t (or the point t + δ) inside the domain - on a face, along the free
  // parameter (the held one is on its bound)
  auto within = [&](double c0, double c1, double radius) {
    const bool in0 = c0 - radius > lo[0] && c0 + radius < hi[0];
    const bool in1 = c1 - radius > lo[1] && c1 + radius < hi[1];
    return (in0 || !it.free_[0]) && (in1 || !it.free_[1]);
  };
  const double dt0 = it.t[0] - it.t_prev[0], dt1 = it.t[1] - it.t_prev[1];
  const double dH0 = H[0][0] - it.H_prev[0], dH1 = H[0][1] - it.H_prev[1], dH2 = H[1][1] - it.H_prev[2];
  const double dH2n = dH0 * dH0 + 2.0 * dH1 * dH1 + dH2 * dH2, dt2 = dt0 * dt0 + dt1 * dt1;
  const double dn2 = delta[0] * delta[0] + delta[1] * delta[1];
  // the Kantorovich condition L |δ| <= λ/4, in squares: the square roots only when it holds
  if (!(dt2 > 0.0 &&
        kLipschitzSafety * kLipschitzSafety * dH2n * dn2 <= 0.0625 * lambda_min * lambda_min * dt2))
    return verdict;
  const double L = kLipschitzSafety * std::sqrt(dH2n / dt2);
  const double dn = std::sqrt(dn2);
  const double R = 2.0 * dn;  // the ball holding the basin's only stationary point
  // on a face, the held parameter's gradient pushes out of the box over the whole ball (it
  // changes by at most |H_ij| R + L R^2 there), so the solve stays on the face: the 1-D problem
  // along it is the basin's
  const bool held = !on_face || std::abs(it.g[hj]) > std::abs(b) * R + L * R * R;
  // a minimiser already found in the ball (on this face) is this basin's
  if (held && within(it.t[0], it.t[1], R)) {
    for (int i = 0; i < early.minimiser_count; ++i) {
      const double m0 = early.minimisers[i][0], m1 = early.minimisers[i][1];
      if (on_face && (hj == 0 ? m0 : m1) != it.t[hj]) continue;  // not on this face
      const double e0 = m0 - it.t[0], e1 = m1 - it.t[1];
      if (e0 * e0 + e1 * e1 <= R * R) {
        verdict.abandoned = true;
        verdict.u = m0;
        verdict.v = m1;
        verdict.distance = std::numeric_limits<double>::infinity();
        return verdict;
      }
    }
  }
  // the predicted minimiser inside the box (on a face: inside the face), so that the box does
  // not cut the basin off, and the basin's lower bound not below the cutoff (less the tie)
  const bool inside = held && within(it.t[0] + delta[0], it.t[1] + delta[1], 0.0);
  if (inside && early.cutoff < std::numeric_limits<double>::infinity()) {
    // 2 min f >= |r|^2 + <g, δ> - (8/3) L |δ|^3
    const double low2 =
        dot(it.r, it.r) + (it.g[0] * delta[0] + it.g[1] * delta[1]) - (8.0 / 3.0) * L * dn * dn * dn;
    const double tie =
        kTie * early.cutoff + 32.0 * std::numeric_limits<double>::epsilon() * (it.norm_p + norm(it.s));
    if (low2 >= 0.0 && std::sqrt(low2) >= early.cutoff - tie) {
      verdict.abandoned = true;
      verdict.u = it.t[0] + delta[0];
      verdict.v = it.t[1] + delta[1];
      verdict.distance = std::sqrt(low2);
    }
  }
  return verdict;
}

}  // namespace footpoint::surface
