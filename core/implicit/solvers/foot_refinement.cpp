#include "implicit/solvers/foot_refinement.hpp"

#include <array>
#include <cmath>

#include "implicit/geometry/implicit_curve_differentials.hpp"

namespace footpoint::curve {

namespace {

// max_i |f_i(x)| / |∇f_i(x)| with f from accurate values (mid-points); false where unavailable.
bool accurate_residual(const ImplicitEquations& eq, Vec3 x, const ImplicitJet& j, std::array<double, 2>& f,
                       double& residual) {
  std::array<Interval, 2> enclosure;
  if (!eq.accurate_values(x, enclosure)) return false;
  residual = 0.0;
  for (int i = 0; i < 2; ++i) {
    f[static_cast<std::size_t>(i)] = formula::interval::mid(enclosure[static_cast<std::size_t>(i)]);
    residual = std::fmax(residual, std::abs(f[static_cast<std::size_t>(i)]) / norm(j.grad[i]));
  }
  return std::isfinite(residual);
}

}  // namespace

bool refine_foot(const ImplicitEquations& eq, Vec3 p, Vec3& x) {
  ImplicitJet j = eq.jet(x);
  if (!(j.normals_sine() < kRefineSine)) return false;
  std::array<double, 2> f{};
  double residual = 0.0;
  if (!accurate_residual(eq, x, j, f, residual)) return false;
  bool moved = false;
  for (int n = 0; n < 2 && residual > 0.0; ++n) {
    Vec3 step;
    if (!critical_point_step(j, x, p, f, step)) break;
    const Vec3 next = x + step;
    if (!is_finite(next)) break;
    const ImplicitJet jn = eq.jet(next);
    std::array<double, 2> fn{};
    double rn = 0.0;
    if (!accurate_residual(eq, next, jn, fn, rn) || !(rn < residual)) break;
    x = next;
    j = jn;
    f = fn;
    residual = rn;
    moved = true;
  }
  return moved;
}

}  // namespace footpoint::curve
