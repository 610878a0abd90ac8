// The Geometric Strategy Algorithm ([GSA] Algorithm 1, eqs. (3)-(20)): decompose p - s in
// the frame (s_u, s_v, n) (eqs. (3)-(7)), take the normal curvature k_n along the tangent part
// T = α1 s_u + α2 s_v (eqs. (8)-(10)), intersect the segment from p to the centre m of the normal
// curvature sphere with that sphere (eqs. (11)-(17)) and solve the tangent-plane system for that
// point q (eqs. (18)-(20)). k_n = 0 is perturbed to k_n + ε as in §2.2. Written out, the
// increment is the tangent-plane step (α1, α2) of eq. (7) divided by
// Q = sqrt(1 - 2 k_n <p - s, n> + k_n^2 |p - s|^2) (see gsa.cpp): the same map as printed, with
// the terms that vanish identically (C1 = C2 = 0, the normal part of q - p0) not computed.
#pragma once
#include "parametric/geometry/parametric_surface.hpp"
#include "parametric/solvers/surface_paper_iteration.hpp"
#include "projection/projection_result.hpp"

namespace footpoint::surface {

// One increment from the jet at (u, v); degenerate when s_u x s_v = 0 or p is the sphere's centre.
PaperStep gsa_step(const Vec3& p, const SurfaceJet& jet);

ProjectionResult project_gsa(const SurfaceFormulas& formulas, const ParamBox& box, const Vec3& p,
                             const Options& options);

}  // namespace footpoint::surface
