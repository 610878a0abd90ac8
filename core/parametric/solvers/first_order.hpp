// The first-order (tangent-plane, "H-H-H") iteration of Hartmann, Hoschek-Lasser and Hu et al.:
// project p onto the tangent plane at s(u_n, v_n) and solve the first fundamental form system
//   [E F; F G] (Δu, Δv)^T = (<p - s, s_u>, <p - s, s_v>)^T
// ([GSA] eq. (2); [Hybrid] eqs. (4)-(5)). Linearly convergent where it converges;
// [Hybrid]'s counterexamples C1-C5 are surfaces where it does not.
#pragma once
#include "parametric/geometry/parametric_surface.hpp"
#include "parametric/solvers/surface_paper_iteration.hpp"
#include "projection/projection_result.hpp"

namespace footpoint::surface {

// One increment from the jet at (u, v); degenerate when EG - F^2 = 0 (s_u x s_v = 0).
PaperStep first_order_step(const Vec3& p, const SurfaceJet& jet);

// Iterates from options.initial (else the domain's centre), unclamped, as published.
ProjectionResult project_first_order(const SurfaceFormulas& formulas, const ParamBox& box, const Vec3& p,
                                     const Options& options);

}  // namespace footpoint::surface
