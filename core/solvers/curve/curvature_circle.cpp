#include "solvers/curve/curvature_circle.hpp"

#include <cmath>

#include "solvers/curve/iteration_control.hpp"
#include "solvers/curve/parametric_curve_summary.hpp"

namespace footpoint::curve {
namespace {

// |c' x c''| below this fraction of |c'| |c''| counts as zero curvature.
constexpr double kStraight = 1e-12;

// The step dt of eq. (22) at the jet j, or false when c' = 0.
bool circle_step(const CurveJet& j, Vec3 p, double& dt) {
  const double speed2 = norm2(j.d1);
  if (!(speed2 > 0.0)) return false;
  const Vec3 b = cross(j.d1, j.d2);  // binormal direction, |b| = k |c'|^3
  const double b2 = norm2(b);
  if (!(std::sqrt(b2) > kStraight * std::sqrt(speed2) * norm(j.d2))) {
    dt = dot(p - j.c, j.d1) / speed2;  // straight: the tangent foot point
    return true;
  }
  const double speed = std::sqrt(speed2);
  const double k = std::sqrt(b2) / (speed2 * speed);
  const Vec3 normal = cross(b, j.d1) / (std::sqrt(b2) * speed);  // unit principal normal
  const Vec3 m = j.c + normal / k;                               // centre of curvature
  // p moved into the osculating plane (the plane of the circle): for planar curves it is there.
  const Vec3 pp = p - (dot(p - j.c, b) / b2) * b;
  const double to_centre = norm(m - pp);
  if (!(to_centre > 0.0)) {
    dt = dot(p - j.c, j.d1) / speed2;  // p at the centre: every circle point is a foot point
    return true;
  }
  const double w = 1.0 - (1.0 / k) / to_centre;  // eq. (16)
  const Vec3 q = pp + (m - pp) * w;              // eq. (17)
  dt = dot(cross(q - j.c, j.d2), b) / b2;        // eq. (22)
  return true;
}

}  // namespace

ProjectionResult curvature_circle(const CurveFormulas& formulas, const ParamInterval& domain,
                                  const CurveSampleIndex& index, Vec3 p, const Options& options) {
  std::vector<std::array<double, 3>> trace;
  // Linear convergence when p is off the curve (the GSA paper's Remark 2).
  const IterationControl control = make_control(options, 1000, &trace);
  double t = parametric_start(domain, index, p, options);
  Status status = Status::max_iterations;
  double step = 0.0, previous = kInfinity;
  int n = 0;
  while (n < control.max_iterations) {
    double dt = 0.0;
    if (!circle_step(formulas.jet(t), p, dt)) {
      status = Status::degenerate;
      break;
    }
    if (!std::isfinite(dt)) {
      status = Status::non_finite;
      break;
    }
    t += dt;
    ++n;
    step = std::fabs(dt);
    control.record(dt);
    const auto progress = control.progress(step, std::fabs(t), previous);
    if (progress == IterationControl::Progress::converged ||
        (progress == IterationControl::Progress::at_floor &&
         parametric_residual_met(parametric_result(formulas, domain, p, t, "curvature_circle"), control))) {
      status = Status::converged;
      break;
    }
  }
  return finish_parametric_result(formulas, domain, p, t, "curvature_circle", status, n, step, control,
                                  std::move(trace));
}

}  // namespace footpoint::curve
