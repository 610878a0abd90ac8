#include "parametric/solvers/curvature_circle.hpp"

#include <cmath>

#include "parametric/solvers/parametric_iteration.hpp"

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
  auto circle = [&](const CurveJet& j) {
    ParamStep s;
    if (!circle_step(j, p, s.dt))
      s.failure = Status::degenerate;
    else if (!std::isfinite(s.dt))
      s.failure = Status::non_finite;
    return s;
  };
  // Linear convergence when p is off the curve ([GSA] Remark 2): a larger budget.
  return iterate_parametric("curvature_circle", formulas, domain, index, p, options, 1000,
                            AtFloor::converged_if_orthogonal, circle);
}

}  // namespace footpoint::curve
