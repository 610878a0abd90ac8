// The early stop of `auto`'s local solve (parametric/solvers/projected_newton.hpp): what the caller
// knows (EarlyStop) ends a solve after 1-3 Newton steps when Newton's model proves its basin to be
// that of a minimiser already found, or to hold nothing nearer than the best distance so far.
//
// At an iterate t with H positive definite (smaller eigenvalue λ), gradient g and Newton step
// δ = -H^{-1} g, let L estimate the Lipschitz constant of H: its change since the previous iterate
// (at the first iterate, since a reference point - the centre of the cell the solve starts from),
// times kLipschitzSafety. Under the Kantorovich condition L |δ| <= λ/4, f is strongly convex on the
// ball |e| <= 2|δ| around t (H >= λ/2 there), which holds exactly one stationary point, the basin's
// minimiser, and
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
// applies (for far points the cells along an edge all lead to one edge minimum).
#pragma once
#include <array>
#include <limits>

#include "parametric/geometry/parametric_surface.hpp"
#include "parametric/geometry/params.hpp"

namespace footpoint::surface {

// What the caller knows that can end a solve early.
struct EarlyStop {
  double cutoff = std::numeric_limits<double>::infinity();  // the best distance found so far
  const Params<2>* minimisers = nullptr;                    // minimisers found so far (u, v)
  int minimiser_count = 0;
  // A point near the start and the Hessian of f there (upper triangle), for the first Lipschitz
  // estimate; reference_H[0] = NaN when there is none.
  Params<2> reference_t{};
  std::array<double, 3> reference_H{std::numeric_limits<double>::quiet_NaN(), 0.0, 0.0};
};

// The solve's state at the iterate examined: t and the previous iterate, H there and at the
// previous one (upper triangle), g, the residual r = s - p, Newton's step before any cap, which
// parameters are free, and whether H is positive definite on both (newton_direction.hpp).
struct BasinIterate {
  Params<2> t;
  Params<2> t_prev;
  double H[2][2];
  double H_prev[3];
  double g[2];
  Vec3 r;
  Vec3 s;  // the surface point at t
  Params<2> newton_step;
  bool free_[2];
  bool definite;
  double det;
  double norm_p;
};

// Abandoned: the basin's minimiser is a known one (distance +inf) or holds nothing nearer than
// the cutoff (distance: the lower bound); (u, v) is the known or predicted minimiser.
struct BasinVerdict {
  bool abandoned = false;
  double u = 0.0, v = 0.0;
  double distance = 0.0;
};

// The test above at one iterate; a parameter is free when not held on its bound in `box`.
BasinVerdict test_basin(const BasinIterate& it, const ParamBox& box, const EarlyStop& early);

}  // namespace footpoint::surface
