#include "implicit/solvers/implicit_curve_summary.hpp"

#include <algorithm>
#include <cmath>

namespace footpoint::curve {
namespace {

// The face of the box that x lies on (within a relative 1e-12), as axis and side (+1 hi, -1 lo);
// axis -1 when x is inside. Planar curves have no z faces.
std::pair<int, int> face_of(const Box3& box, Vec3 x, bool planar) {
  const double slack = 1e-12 * std::max(1.0, norm(x));
  for (int k = 0; k < (planar ? 2 : 3); ++k) {
    if (std::fabs(x[k] - box.lo[k]) <= slack) return {k, -1};
    if (std::fabs(x[k] - box.hi[k]) <= slack) return {k, +1};
  }
  return {-1, 0};
}

}  // namespace

void fill_implicit_residuals(const ImplicitEquations& equations, const Box3& box, Vec3 p, Vec3 x,
                             Summary& summary) {
  fill_implicit_residuals(equations.jet(x), equations.planar(), box, p, x, summary);
}

void fill_implicit_residuals(const ImplicitJet& j, bool planar, const Box3& box, Vec3 p, Vec3 x,
                             Summary& summary) {
  const double n1 = norm(j.grad[0]);
  const double n2 = norm(j.grad[1]);
  summary.equation_residual[0] = n1 > 0.0 ? std::fabs(j.f[0]) / n1 : std::fabs(j.f[0]);
  summary.equation_residual[1] = n2 > 0.0 ? std::fabs(j.f[1]) / n2 : std::fabs(j.f[1]);
  summary.orthogonality = {0.0, 0.0};
  summary.on_boundary = false;

  const Vec3 t = j.tangent();
  const double tn = norm(t);
  if (!(tn > kSingularSine * n1 * n2)) {
    summary.location = Location::singular_point;
    return;
  }
  const Vec3 d = p - x;
  const double denominator = std::max(norm(d), 1e-3 * std::max(1.0, norm(x))) * tn;
  const double along = dot(d, t);  // eq. (7): F(X) = <T, P - X>
  const auto [axis, side] = face_of(box, x, planar);
  if (axis >= 0 && std::fabs(t[axis]) > 1e-12 * tn) {
    // The curve crosses the face: the admissible direction is the tangent pointing into the box.
    // X is a minimum of the distance on the part in the box when that direction does not lead
    // towards p, i.e. <p - X, T_in> <= 0; only the positive part is a residual.
    const Vec3 inward = (t[axis] * side > 0.0) ? -t : t;
    summary.orthogonality[0] = std::max(0.0, dot(d, inward)) / denominator;
    summary.location = Location::box_face;
    summary.on_boundary = true;
    return;
  }
  summary.orthogonality[0] = std::fabs(along) / denominator;
  summary.location = Location::interior;
}

bool implicit_residuals_met(const Summary& summary, Vec3 x, const IterationControl& control,
                            bool with_orthogonality) {
  const double size = std::max(1.0, norm(x));
  const double tol = control.residual_tolerance;
  if (!(summary.equation_residual[0] <= tol * size && summary.equation_residual[1] <= tol * size))
    return false;
  return !with_orthogonality || summary.orthogonality[0] <= tol;
}

bool foot_residuals_met(const ImplicitEquations& equations, Vec3 p, Vec3 x, const IterationControl& control,
                        bool with_orthogonality) {
  const ImplicitJet j = equations.jet(x);
  const double size = std::max(1.0, norm(x));
  const double tol = control.residual_tolerance;
  for (int i = 0; i < 2; ++i)
    if (!(std::fabs(j.f[i]) <= tol * size * norm(j.grad[i]))) return false;
  if (!with_orthogonality) return true;
  const Vec3 t = j.tangent();
  const Vec3 d = p - x;
  return std::fabs(dot(d, t)) <= tol * std::max(norm(d), 1e-3 * size) * norm(t);
}

ProjectionResult implicit_result(const ImplicitEquations& equations, const Box3& box, Vec3 p, Vec3 x,
                                 const char* method) {
  Summary residuals;
  fill_implicit_residuals(equations, box, p, x, residuals);
  return implicit_result(equations.planar(), p, x, method, residuals);
}

ProjectionResult implicit_result(bool planar, Vec3 p, Vec3 x, const char* method, const Summary& residuals) {
  ProjectionResult r;
  r.dim = planar ? 2 : 3;
  r.num_params = 0;
  r.foot = {x.x, x.y, planar ? 0.0 : x.z};
  r.params = {0.0, 0.0};
  r.distance = norm(p - x);
  r.summary = residuals;
  r.summary.method = method;
  return r;
}

}  // namespace footpoint::curve
