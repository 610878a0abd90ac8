#include "implicit/solvers/implicit_surface_multiplicity.hpp"

#include <cmath>

#include "implicit/solvers/implicit_surface_lagrange.hpp"

namespace footpoint::surface_implicit {

namespace {

constexpr double kFlat = 1e-8;  // the least eigenvalue against its value 1 at a plane

// The least eigenvalue of the Lagrangian's Hessian I + l H on the tangent plane at x (the
// multiplier l of p - x = l grad f), or NaN where grad f = 0.
double least_tangent_eigenvalue(const ImplicitSurfaceJet& j, Vec3 p, Vec3 x) {
  const double g2 = norm2(j.grad);
  if (!(g2 > 0.0)) return std::nan("");
  const double l = dot(p - x, j.grad) / g2;
  return tangent_form(lagrangian_hessian(j, l), j.grad / std::sqrt(g2)).least_eigenvalue();
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
