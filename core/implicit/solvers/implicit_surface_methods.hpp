// The literature's local methods for the foot point on an implicit surface f(x, y, z) = 0, from a
// start (options.initial, else p itself), each as published:
//  - lagrange_newton: Newton's method on the Lagrange system p - X = l grad f(X), f(X) = 0
//    ([NW06] Sec. 18.1; implicit/solvers/implicit_surface_lagrange.hpp), unsafeguarded: from p it
//    converges to the stationary point of the distance its basin holds, which may be a saddle or a
//    maximum of the distance, and it ignores the box (outside_domain when it ends outside);
//  - first_order: Hartmann's foot-point iteration for implicit surfaces [Hartmann] (CAGD 16 (1999)
//    355-376, Sec. 5): from the start, Newton steps along the gradient
//        X_{n+1} = X_n - f(X_n) / |grad f(X_n)|^2 grad f(X_n)
//    land on the surface at Y; the foot of p on the tangent plane at Y,
//        Q = p - <p - Y, grad f(Y)> / |grad f(Y)|^2 grad f(Y),
//    is the next start; repeated until the surface points Y stop moving. Linear convergence whose
//    rate is the ratio of the distance to the radius of curvature: it stalls or oscillates where
//    p is beyond a centre of curvature (the tests record where it converges and where not).
// Statuses: converged (the residuals meet the tolerance), max_iterations, diverged, non_finite,
// degenerate (grad f = 0 or a singular Newton system), outside_domain (a foot outside the box),
// beyond_max_distance.
#pragma once
#include "geometry/projection_result.hpp"
#include "implicit/geometry/implicit_surface.hpp"
#include "solvers/iteration_control.hpp"

namespace footpoint::surface_implicit {

// Where Hartmann's iteration from y0 ended: converged when the surface points stopped moving.
struct HartmannEnd {
  Vec3 x;
  int iterations = 0;
  double step = 0.0;
  Status status = Status::max_iterations;
};
HartmannEnd hartmann_iteration(const ImplicitSurfaceEquation& equation, Vec3 p, Vec3 y0,
                               const curve::IterationControl& control);

ProjectionResult lagrange_newton_method(const ImplicitSurfaceEquation& equation, const Box3& box, Vec3 p,
                                        const Options& options);
ProjectionResult first_order_method(const ImplicitSurfaceEquation& equation, const Box3& box, Vec3 p,
                                    const Options& options);

}  // namespace footpoint::surface_implicit
