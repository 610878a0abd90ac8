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
//  - hu_wallner: Hu and Wallner's second-order iteration [HuWallner] (CAGD 22 (2005) 251-260), the
//    step of its surfaces' case carried to f = 0. From the surface point X with unit normal
//    n = grad f / |grad f|: (1) the foot of p on the tangent plane gives the direction t of the
//    tangent part of p - X; (2) the normal curvature along t, kn = -<t, H t> / |grad f| (H the
//    Hessian of f: the second fundamental form of a level set, [Hartmann]); (3) the
//    curvature circle of the normal section along t, centre m = X + n / kn, radius 1 / |kn|, lies
//    in the plane of X, n and t, which holds p; (4) the foot of p on that circle,
//    q = m + (p - m) / (|kn| |p - m|), the same point as the segment from p to m meets the normal
//    curvature sphere ([GSA] eqs. (11)-(17)); (5) the next surface point is q moved onto f = 0
//    (Newton along the gradient, as above): the paper's step (5) turns q into parameter increments
//    of s(u, v) by the surface's second-order Taylor expansion, and an implicit surface has no
//    parameters, so its point itself is taken, within O(|q - X|^3) of the normal section.
//    Stopped, as the paper's iteration is, when the surface points stop moving. The circle agrees
//    with the normal section to second order: the iteration converges quadratically where p lies
//    in the normal section of its foot along the direction the iteration takes (spheres, planes
//    of symmetry, p on the surface: the inversion problem), and in one step on a sphere; elsewhere
//    the plane of the normal section misses the foot by a multiple of the error, and the rate is
//    linear with a factor proportional to the distance times the difference of the principal
//    curvatures (the tests measure both). The paper's own text was not at hand: the steps follow
//    its description in [GSA] (Sec. 3 and eqs. (11)-(17)) and its abstract.
// Statuses: converged (the residuals meet the tolerance), max_iterations, diverged, non_finite,
// degenerate (grad f = 0 or a singular Newton system), outside_domain (a foot outside the box),
// beyond_max_distance.
#pragma once
#include "implicit/geometry/implicit_surface.hpp"
#include "projection/projection_result.hpp"
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
// Hu and Wallner's iteration from y0 (landed on the surface first).
HartmannEnd hu_wallner_iteration(const ImplicitSurfaceEquation& equation, Vec3 p, Vec3 y0,
                                 const curve::IterationControl& control);
// Steps (1)-(4) at the surface point x with its jet: q, the foot of p on the curvature circle of the
// normal section toward p (x itself where p is on the normal line); false where grad f = 0 or p
// is the circle's centre.
bool curvature_circle_foot(const ImplicitSurfaceJet& j, Vec3 x, Vec3 p, Vec3& q);

ProjectionResult lagrange_newton_method(const ImplicitSurfaceEquation& equation, const Box3& box, Vec3 p,
                                        const Options& options);
ProjectionResult first_order_method(const ImplicitSurfaceEquation& equation, const Box3& box, Vec3 p,
                                    const Options& options);
ProjectionResult hu_wallner_method(const ImplicitSurfaceEquation& equation, const Box3& box, Vec3 p,
                                   const Options& options);

}  // namespace footpoint::surface_implicit
