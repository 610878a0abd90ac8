#include "parametric/solvers/first_order.hpp"

#include <cmath>

namespace footpoint::surface {

PaperStep first_order_step(const Vec3& p, const SurfaceJet& jet) {
  const Vec3 r = p - jet.s;  // <q - s, s_i> = <p - s, s_i>: q - p is normal to the tangent plane
  const double E = dot(jet.su, jet.su), F = dot(jet.su, jet.sv), G = dot(jet.sv, jet.sv);
  const double Su = dot(r, jet.su), Sv = dot(r, jet.sv);
  const double det = E * G - F * F;
  PaperStep step;
  if (!(det > 0.0)) {
    // det <= 0 only when s_u x s_v = 0 (up to rounding): no tangent plane to project onto
    step.failure = std::isnan(det) ? Status::non_finite : Status::degenerate;
    return step;
  }
  // [Hybrid] eq. (5)
  step.du = (G * Su - F * Sv) / det;
  step.dv = -(F * Su - E * Sv) / det;
  return step;
}

namespace {
struct FirstOrder {
  PaperStep step(const Vec3& p, double, double, const SurfaceJet& jet) const {
    return first_order_step(p, jet);
  }
};
}  // namespace

ProjectionResult project_first_order(const SurfaceFormulas& formulas, const ParamBox& box, const Vec3& p,
                                     const Options& options) {
  FirstOrder method;
  return run_paper_iteration("first_order", method, formulas, box, p, options);
}

}  // namespace footpoint::surface
