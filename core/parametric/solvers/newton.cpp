#include "parametric/solvers/newton.hpp"

#include <cmath>

namespace footpoint::surface {

OrthogonalitySystem orthogonality_system(const Vec3& p, const SurfaceJet& jet) {
  const Vec3 r = p - jet.s;
  OrthogonalitySystem sys;
  sys.F1 = dot(r, jet.su);
  sys.F2 = dot(r, jet.sv);
  // ∂/∂t_j <p - s, s_i> = <p - s, s_ij> - <s_j, s_i>
  sys.J11 = dot(r, jet.suu) - dot(jet.su, jet.su);
  sys.J12 = dot(r, jet.suv) - dot(jet.su, jet.sv);
  sys.J21 = sys.J12;
  sys.J22 = dot(r, jet.svv) - dot(jet.sv, jet.sv);
  return sys;
}

PaperStep newton_step(const Vec3& p, const SurfaceJet& jet) {
  const OrthogonalitySystem sys = orthogonality_system(p, jet);
  const double F0 = sys.det();
  PaperStep step;
  if (F0 == 0.0 || std::isnan(F0)) {
    step.failure = F0 == 0.0 ? Status::degenerate : Status::non_finite;
    return step;
  }
  // eq. (24): G(t) = t - F'^{-1} F, written out with F0 = det F'
  step.du = -(sys.J22 * sys.F1 - sys.J12 * sys.F2) / F0;
  step.dv = -(sys.J11 * sys.F2 - sys.J21 * sys.F1) / F0;
  return step;
}

namespace {
struct Newton {
  PaperStep step(const Vec3& p, double, double, const SurfaceJet& jet) const { return newton_step(p, jet); }
};
}  // namespace

ProjectionResult project_newton(const SurfaceFormulas& formulas, const ParamBox& box, const Vec3& p,
                                const Options& options) {
  Newton method;
  return run_paper_iteration("newton", method, formulas, box, p, options);
}

}  // namespace footpoint::surface
