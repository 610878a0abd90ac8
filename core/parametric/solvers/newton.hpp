// Plain Newton's method on the orthogonality conditions
//   F(u, v) = (<p - s, s_u>, <p - s, s_v>) = 0,   t_{n+1} = t_n - F'(t_n)^{-1} F(t_n)
// ([Hybrid] eqs. (22)-(24); [GSA] Table 9). Quadratic near a regular zero, but it finds
// any stationary point of the distance, minimum or not.
#pragma once
#include "parametric/geometry/parametric_surface.hpp"
#include "parametric/solvers/surface_paper_iteration.hpp"
#include "projection/projection_result.hpp"

namespace footpoint::surface {

// F and its Jacobian F' at one parameter point.
struct OrthogonalitySystem {
  double F1 = 0.0, F2 = 0.0;                            // eq. (23)
  double J11 = 0.0, J12 = 0.0, J21 = 0.0, J22 = 0.0;    // ∂F_i/∂u, ∂F_i/∂v
  double det() const { return J11 * J22 - J12 * J21; }  // F0 of eq. (24)
};
OrthogonalitySystem orthogonality_system(const Vec3& p, const SurfaceJet& jet);

// One Newton increment -F'^{-1}F; degenerate when F0 = 0.
PaperStep newton_step(const Vec3& p, const SurfaceJet& jet);

ProjectionResult project_newton(const SurfaceFormulas& formulas, const ParamBox& box, const Vec3& p,
                                const Options& options);

}  // namespace footpoint::surface
