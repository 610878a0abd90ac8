// The local solve of `auto`: minimise f(t) = ½|s(t) - p|^2 over the closed parameter box by a
// projected Newton method (Bertsekas 1982) with an Armijo line search along the projection arc.
//   gradient  g = (<s - p, s_u>, <s - p, s_v>)            (= -F of eq. (23), hybrid paper)
//   Hessian   H = [E F; F G] + [<s-p, s_uu> <s-p, s_uv>; <s-p, s_uv> <s-p, s_vv>]
// A parameter on its bound with the gradient pushing outwards is held there (the active set), so
// edges become 1-D problems and corners points; the Newton step on the free parameters uses H
// with its eigenvalues replaced by their absolute values where it is not positive definite (a
// saddle, the concave side of the surface, a pole where s_u x s_v = 0), which keeps it a descent
// step of natural length, and a zero gradient at an indefinite H moves along negative curvature.
// Every accepted step decreases f, so the solve cannot end on a maximum or a saddle it did not
// start at, and it never leaves the domain.
//
// Early stop (`auto` passes what it already knows, EarlyStop). At an iterate t with H positive
// definite (smaller eigenvalue λ), gradient g and Newton step δ = -H^{-1} g, let L estimate the
// Lipschitz constant of H: its change since the previous iterate (at the first iterate, since a
// reference point - the centre of the cell the solve starts from), times kLipschitzSafety. Under
// the Kantorovich condition L |δ| <= λ/4, f is strongly convex on the ball |e| <= 2|δ| around t
// (H >= λ/2 there), which holds exactly one stationary point, the basin's minimiser, and
//   min f >= f(t) + ½ <g, δ> - (4/3) L |δ|^3
// (f(t + e) >= f(t) + <g, e> + ½ e^T H e - (L/6)|e|^3, the quadratic model's minimum less the
// cubic remainder on that ball). The solve is abandoned when
//  - a minimiser already found lies in that ball (inside the domain): it is this basin's; or
//  - the bound above is at least ½ (cutoff - tie)^2: the basin holds nothing nearer than the
//    best distance found. `tie` is kTie relative plus the rounding of the distance, so that a
//    copy of the best foot (periodic or folded parametrisations reach one foot from many
//    (u, v)) is abandoned after 2-3 evaluations instead of being solved to the last ulp; the
//    answer's distance is then within that tie of the global minimum.
// On a face of the box (one parameter held on its bound) the same holds for the 1-D problem along
// it, with λ = H_ii of the free parameter, provided the held parameter stays held over the ball:
// its gradient pushes out by more than it can change there, |g_j| > |H_ij| R + L R^2 (R = 2|δ|).
// Then a known minimiser on the same face in the ball is this basin's, and the 1-D lower bound
// applies (for far points the cells along an edge all lead to one edge minimum: ~0.7 repeated
// edge solves per S1 HTTP bench point answered on an edge, before this).
#pragma once
#include <array>
#include <limits>
#include <vector>

#include "geometry/parametric_surface.hpp"
#include "geometry/projection_result.hpp"
#include "solvers/surface/surface_convergence.hpp"

namespace footpoint::surface {

struct LocalSolution {
  double u = 0.0, v = 0.0;
  SurfaceJet jet;         // at (u, v)
  double distance = 0.0;  // |p - s(u, v)|
  Status status = Status::non_finite;
  int iterations = 0;      // accepted steps
  double step_norm = 0.0;  // norm of the last accepted step
  // Stopped early (EarlyStop): (u, v) is the basin's predicted minimiser, `distance` the lower
  // bound on its distance, `jet` the one at the last iterate; status is not meaningful.
  bool abandoned = false;
};

// What the caller knows that can end a solve early (see above).
struct EarlyStop {
  double cutoff = std::numeric_limits<double>::infinity();  // the best distance found so far
  const std::array<double, 2>* minimisers = nullptr;        // minimisers found so far (u, v)
  int minimiser_count = 0;
  // A point near the start and the Hessian of f there (upper triangle), for the first Lipschitz
  // estimate; reference_H[0] = NaN when there is none.
  std::array<double, 2> reference_t{};
  std::array<double, 3> reference_H{std::numeric_limits<double>::quiet_NaN(), 0.0, 0.0};
};

// Default iteration budget of the local solve (Newton from a cell's model minimiser needs 2-4).
inline constexpr int kLocalMaxIterations = 100;

// Starts at (u0, v0) clamped into the box; `start_jet`, if given, is the jet there. With `trace`,
// appends every accepted step (Δu, Δv, 0). With `early`, may stop early with `abandoned` set.
LocalSolution projected_newton(const SurfaceFormulas& formulas, const ParamBox& box, const Vec3& p, double u0,
                               double v0, const ConvergenceCriteria& criteria,
                               std::vector<std::array<double, 3>>* trace = nullptr,
                               const EarlyStop* early = nullptr, const SurfaceJet* start_jet = nullptr);

}  // namespace footpoint::surface
