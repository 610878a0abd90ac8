#include "implicit/solvers/implicit_surface_multiplicity.hpp"

#include <cmath>

namespace footpoint::surface_implicit {

namespace {

constexpr double kFlat = 1e-8;  // the least eigenvalue against its value 1 at a plane

// The least eigenvalue of the Lagrangian's Hessian I + l H on the tangent plane at x, or NaN where
// grad f = 0.
double least_tangent_eigenvalue(const ImplicitSurfaceJet& j, Vec3 p, Vec3 x) {
  const double g2 = norm2(j.grad);
  if (!(g2 > 0.0)) return std::nan("");
  const double l = dot(p - x, j.grad) / g2;
  const Vec3 n = j.grad / std::sqrt(g2);
  const Vec3 helper = std::fabs(n.x) < 0.9 ? Vec3{1.0, 0.0, 0.0} : Vec3{0.0, 1.0, 0.0};
  const Vec3 t1 = cross(n, helper) / norm(cross(n, helper)), t2 = cross(n, t1);
  auto form = [&](Vec3 a, Vec3 b) {
    double s = dot(a, b);
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) s += l * a[r] * j.hess[static_cast<std::size_t>(r)][c] * b[c];
    return s;
  };
  const double a = form(t1, t1), b = form(t1, t2), c = form(t2, t2);
  return 0.5 * (a + c) - std::sqrt(0.25 * (a - c) * (a - c) + b * b);
}

}  // namespace

AnswerMultiplicity implicit_surface_multiplicity(const ImplicitSurfaceEquation& equation, Vec3 p,
                                                 const ProjectionResult& r,
                                                 const std::vector<curve::ReachedFoot>& reached) {
  AnswerMultiplicity m;
  m.computed = true;
  const Vec3 answer{r.foot[0], r.foot[1], r.foot[2]};
  if (r.summary.location == Location::interior && r.distance > 0.0 &&
      std::fabs(least_tangent_eigenvalue(equation.jet(answer), p, answer)) <= kFlat) {
    m.kind = Multiplicity::continuum;
    return m;
  }
  return curve::tied_feet(r, p, reached);
}

}  // namespace footpoint::surface_implicit
