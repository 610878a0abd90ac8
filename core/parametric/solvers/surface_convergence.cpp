#include "parametric/solvers/surface_convergence.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace footpoint::surface {

double parameter_scale(const ParamBox& box) {
  return std::max({std::abs(box.umin), std::abs(box.umax), std::abs(box.vmin), std::abs(box.vmax),
                   box.umax - box.umin, box.vmax - box.vmin});
}

double ConvergenceCriteria::step_scale(double u, double v) const {
  return std::max({scale, std::abs(u), std::abs(v)});
}

ConvergenceCriteria convergence_criteria(const Options& options, const ParamBox& box,
                                         int default_max_iterations) {
  ConvergenceCriteria c;
  c.tolerance = step_tolerance(options);
  c.scale = parameter_scale(box);
  c.max_iterations = iteration_budget(options, default_max_iterations);
  return c;
}

Orthogonality orthogonality(const Vec3& p, const Vec3& s, const Vec3& su, const Vec3& sv) {
  return orthogonality(p, norm(p), s, su, sv);
}

Orthogonality orthogonality(const Vec3& p, double norm_p, const Vec3& s, const Vec3& su, const Vec3& sv) {
  constexpr double eps = std::numeric_limits<double>::epsilon();
  const Vec3 r = p - s;
  const double d = norm(r);
  const double noise = 16.0 * eps * (norm_p + norm(s));
  // below the noise level the distance itself is rounding: measure against that level
  const double d_ref = std::max(d, noise);
  Orthogonality o;
  o.floor = d_ref > 0.0 ? noise / d_ref : 0.0;
  const Vec3 tangents[2] = {su, sv};
  for (int i = 0; i < 2; ++i) {
    const double len = norm(tangents[i]);
    // s_i = 0 (a pole) makes F_i = 0 identically
    o.relative[i] = len > 0.0 && d_ref > 0.0 ? std::abs(dot(r, tangents[i])) / (d_ref * len) : 0.0;
    if (std::isnan(len)) o.relative[i] = std::numeric_limits<double>::quiet_NaN();
  }
  return o;
}

bool ConvergenceTest::converged(double step_inf, double u, double v, const Orthogonality& o,
                                std::array<bool, 2> free) {
  double residual = 0.0;
  for (int i = 0; i < 2; ++i)
    if (free[i]) residual = std::isnan(o.relative[i]) ? o.relative[i] : std::max(residual, o.relative[i]);
  if (!(residual == residual)) return false;  // NaN
  if (residual <= o.floor) return true;
  const bool step_ok = step_inf <= criteria_.step_bound(u, v);
  if (step_ok && residual <= std::max(criteria_.tolerance, o.floor)) return true;
  stalled_ = step_ok && residual <= kStalledResidual ? stalled_ + 1 : 0;
  return stalled_ >= kStalledSteps;
}

}  // namespace footpoint::surface
