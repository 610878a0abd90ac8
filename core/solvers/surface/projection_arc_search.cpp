#include "solvers/surface/projection_arc_search.hpp"

#include <algorithm>
#include <cmath>

#include "solvers/surface/paper_iteration.hpp"

namespace footpoint::surface {

namespace {
// Armijo's sufficient decrease: f(t + Δ) <= f(t) + c <g, Δ>.
constexpr double kSufficientDecrease = 1e-4;
constexpr int kMaxBacktracks = 60;
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
}  // namespace

ArcStep search_projection_arc(const SurfaceFormulas& formulas, const Vec3& p, const SurfaceJet& jet,
                              const double (&t)[2], const double (&d)[2], const double (&lo)[2],
                              const double (&hi)[2], const double (&g)[2], bool convex, double step_inf,
                              double step_scale, bool may_expand) {
  ArcStep a;
  double* tn = a.t;
  SurfaceJet& jn = a.jet;
  tn[0] = t[0];
  tn[1] = t[1];
  double alpha = 1.0;
  const Vec3 r0 = jet.s - p;
  const double local_step = kLocalStep * step_scale;
  const bool expand = convex && may_expand &&
                      step_inf * step_inf * std::max({norm2(jet.suu), norm2(jet.suv), norm2(jet.svv)}) <=
                          kTaylorStep * kTaylorStep * std::min(norm2(jet.su), norm2(jet.sv));
  for (int ls = 0; ls < kMaxBacktracks && !a.accepted; ++ls, alpha *= 0.5) {
    for (int i = 0; i < 2; ++i) tn[i] = std::clamp(t[i] + alpha * d[i], lo[i], hi[i]);
    const double dt0 = tn[0] - t[0], dt1 = tn[1] - t[1];
    if (dt0 == 0.0 && dt1 == 0.0) {
      a.vanishes = ls == 0;
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
      a.expanded = true;
    } else if (ls == 0) {
      jn = formulas.jet(tn[0], tn[1]);
      sn = jn.s;
    } else {
      sn = formulas.point(tn[0], tn[1]);
    }
    const double df = 0.5 * dot(sn - jet.s, (sn - p) + r0);
    const bool local = convex && std::max(std::abs(dt0), std::abs(dt1)) <= local_step;
    a.accepted = is_finite(sn) && std::isfinite(df) && (df <= kSufficientDecrease * slope || local);
    if (a.accepted && ls > 0) {
      jn = formulas.jet(tn[0], tn[1]);
      a.accepted = is_finite(jn);
    } else if (a.accepted) {
      a.accepted = is_finite(jn);
    }
  }
  return a;
}

}  // namespace footpoint::surface
