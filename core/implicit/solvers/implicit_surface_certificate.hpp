// The certificate of an answer on an implicit surface S = {f = 0} clipped to the box B: a rigorous
// lower bound L of the distance from p to S ∩ B (projection/certificate.hpp), by branch and bound
// over the compiled octree (implicit/seeding/implicit_surface_cells.hpp):
//  - a cell whose distance from p (geometry/interval_vec3.hpp, distance_lower_bound) is at least
//    the answer's distance less half the gap holds nothing nearer;
//  - a cell (or a piece of a leaf, subdivided per point) whose enclosure of f excludes 0 holds no
//    point of S;
//  - around the foot x*, a box K where the Lagrangian L(x) = |p - x|^2 / 2 + l f(x) is strongly
//    convex: on S, |p - x|^2 / 2 = L(x) for every l, and with M = I + l H(K) (H(K) the interval
//    Hessian of f over K) and m > 0 a Gershgorin lower bound of M's eigenvalues, Taylor's theorem
//    gives for every x in K ∩ B
//        L(x) >= L(x*) + r . (x - x*) + m / 2 |x - x*|^2,   r = x* - p + l grad f(x*),
//    whose minimum over the box K ∩ B - x* is separable by coordinate (a second-order sufficient
//    condition made global on K: [NW06] Theorem 12.6 and its proof; the box faces' multipliers
//    are r's components along the faces x* lies on, of the sign that makes r . (x - x*) >= 0).
//    L(x*) and r are enclosed with interval arithmetic at the point x*. Where I + l H is indefinite
//    at x* (p inside a tube near its core: the normal direction) or its least eigenvalue is well
//    below the tangent form's, the augmented Lagrangian L + c/2 f^2 ([NW06] Sec. 17.3), also
//    |p - x|^2 / 2 on S, whose Hessian adds c (grad f grad f^T + f H), is bounded the same way;
//    the leaves' second-order bounds take the better of the two.
// The leaves' sample points nearer than the answer are reported (nearer), for the search to start
// from them; so are the samples of the leaves that meet the ball of the answer's radius about p
// away from the foot's convex box K (rivals), where a nearer minimum the bound did not settle
// lies; and, once certified, those of the leaves that may hold a point within the gap of the
// answer's distance, where a tie lies (tie_starts, tie_samples).
#pragma once
#include <cstdint>
#include <vector>

#include "implicit/seeding/implicit_surface_cells.hpp"
#include "projection/certificate.hpp"

namespace footpoint::surface_implicit {

struct SurfaceCertificate {
  Certificate certificate;
  // Samples nearer to p than the answer by more than the gap (only when not certified).
  std::vector<Vec3> nearer;
  // Samples of the leaves that meet the ball |x - p| < distance outside K, within the answer's
  // distance plus a leaf diagonal of p.
  std::vector<Vec3> rivals;
  // With a certified answer, where a tie can be: every point of S within the gap of the answer's
  // distance lies in a leaf outside K (the bound there exceeds it away from the foot) that the
  // branch and bound could not show to lie beyond that distance: a piece of it settled by a bound
  // (of its distance or of the Lagrangian) at most that distance, or left at the budget, or the
  // leaf settled whole by its distance, at most that. tie_starts: the samples (indices, ascending)
  // of such leaves (a leaf bounded piece by piece without one: the sample nearest to its centre,
  // as where a foot lies on a face of the box and Newton from the leaf's centre left it) more
  // than two leaf diagonals from the foot; tie_samples, only when tie_starts has any: the samples
  // of all such leaves and of the leaves in K whose box meets the closed ball of that radius
  // about p.
  std::vector<std::int32_t> tie_samples, tie_starts;
};

// The box budget of one certificate (pieces of leaves subdivided for this point).
inline constexpr int kCertificateBoxes = 20000;

// `budget`: the boxes it may bound beyond the compiled cells (kCertificateBoxes by default).
SurfaceCertificate certify_surface_answer(const ImplicitSurfaceEquation& equation,
                                          const ImplicitSurfaceCells& cells, Vec3 p, Vec3 foot,
                                          double distance, int budget = kCertificateBoxes);

}  // namespace footpoint::surface_implicit
