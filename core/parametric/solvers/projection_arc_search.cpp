#include "parametric/solvers/projection_arc_search.hpp"

#include <algorithm>
#include <cmath>

#include "parametric/solvers/surface_paper_iteration.hpp"

namespace footpoint::surface {

namespace {
// Armijo's sufficient decrease: f(t + Δ) <= f(t) + c <g, Δ>.
constexpr double kSufficientDecrease = 1e-4;
constexpr int kMaxBacktracks = 60;
// Convex steps at most this x the parameter scale are taken without the decrease test (Newton's
// local regime, where f changes by little more than its rounding).
constexpr double kLocalStep = 1e-6;
}  // namespace

ArcStep search_projection_arc(const SurfaceFormulas& formulas, const Vec3& p, const SurfaceJet& jet,
                              const Params<2>& t, const Params<2>& d, const Params<2>& lo,
                              const Params<2>& hi, const double (&g)[2], bool convex, double step_scale) {
  ArcStep a;
  Params<2>& tn = a.t;
  SurfaceJet& jn = a.jet;
  tn[0] = t[0];
  tn[1] = t[1];
  double alpha = 1.0;
  const Vec3 r0 = jet.s - p;
  const double local_step = kLocalStep * step_scale;
  for (int ls = 0; ls < kMaxBacktracks && !a.accepted; ++ls, alpha *= 0.5) {
    for (int i = 0; i < 2; ++i) tn[i] = std::clamp(t[i] + alpha * d[i], lo[i], hi[i]);
    const double dt0 = tn[0] - t[0], dt1 = tn[1] - t[1];
    if (dt0 == 0.0 && dt1 == 0.0) {
      a.vanishes = ls == 0;
      break;
    }
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
