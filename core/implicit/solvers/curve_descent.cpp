#include "implicit/solvers/curve_descent.hpp"

#include <cmath>

#include "implicit/geometry/curve_correction.hpp"
#include "implicit/geometry/implicit_curve_differentials.hpp"

namespace footpoint::curve {

LocalMinimum curve_descent(const ImplicitEquations& equations, Vec3 p, Vec3 x0, double max_step,
                           const IterationControl& control) {
  LocalMinimum out;
  out.x = x0;
  double distance2 = norm2(p - x0);
  double previous = kInfinity;
  // The trust region: max_step, or four times the last accepted step when that step had to be
  // halved from its prediction and still decreased the distance beyond rounding (the prediction
  // was wrong, not the rounding too coarse to tell a decrease near the minimum).
  double reach = max_step;
  for (int n = 0; n < control.max_iterations; ++n) {
    const ImplicitJet j = equations.jet(out.x);
    const Vec3 t = unit_tangent(j);
    Vec3 c;
    if (norm2(t) == 0.0 || !curvature_vector(j, c)) return out;  // singular point
    const Vec3 d = out.x - p;
    const double d1 = dot(d, t);
    const double d2 = 1.0 + dot(d, c);
    double ds = d2 > 0.0 ? -d1 / d2 : (d1 > 0.0 ? -reach : reach);
    if (std::fabs(ds) > reach) ds = std::copysign(reach, ds);
    bool moved = false;
    for (int halving = 0; halving < 40; ++halving, ds *= 0.5) {
      Vec3 z;
      int iterations = 0;
      const Vec3 y = out.x + ds * t + (0.5 * ds * ds) * c;
      if (!correct_in_normal_plane(equations, y, t, z, iterations)) continue;
      const double z2 = norm2(p - z);
      if (z2 <= distance2) {
        const Vec3 dx = z - out.x;
        out.step = norm(dx);
        reach = halving > 0 && distance2 - z2 > 1e-14 * distance2 ? std::fmin(max_step, 4.0 * std::fabs(ds))
                                                                  : max_step;
        out.x = z;
        distance2 = z2;
        control.record(dx.x, dx.y, dx.z);
        moved = true;
        break;
      }
    }
    out.iterations = n + 1;
    if (!moved) out.step = 0.0;
    if (!moved || control.stop(out.step, norm(out.x), previous)) {
      const ImplicitJet jx = moved ? equations.jet(out.x) : j;  // not moved: this iteration's
      const Vec3 tx = unit_tangent(jx);
      Vec3 cx;
      if (norm2(tx) > 0.0 && curvature_vector(jx, cx)) out.second_variation = 1.0 + dot(out.x - p, cx);
      out.jet = jx;
      out.converged = true;
      return out;
    }
  }
  return out;
}

}  // namespace footpoint::curve
