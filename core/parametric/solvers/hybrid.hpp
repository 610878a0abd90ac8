// The hybrid second-order algorithm ([Hybrid] Algorithm 1): first-order steps (eq. (5))
// until the Newton map G(t) = t - F'(t)^{-1} F(t) (eq. (24)) is a contraction at the current
// iterate by the paper's test, all four |∂G_i/∂u|, |∂G_i/∂v| < 1/2, then Newton steps (eq. (22))
// to the end. ∂G needs third derivatives of s, taken exactly from the formula tape (jet3).
#pragma once
#include <array>

#include "parametric/geometry/parametric_surface.hpp"
#include "projection/projection_result.hpp"

namespace footpoint::surface {

// ∂G/∂t at a point: d[i][k] = ∂G_i/∂t_k. `ok` is false where F' is singular.
struct NewtonMapDerivative {
  std::array<std::array<double, 2>, 2> d{};
  bool ok = false;
};
// ∂G/∂t_k = F'^{-1} (∂F'/∂t_k) F'^{-1} F (differentiating t - F'^{-1}F; the t and F'^{-1}F'
// terms cancel), with ∂/∂t_k of F'_ij = <p - s, s_ij> - <s_i, s_j>.
NewtonMapDerivative newton_map_derivative(const Vec3& p, const SurfaceJet3& jet);

// Algorithm 1's switching test: every |∂G_i/∂t_k| < 1/2.
bool newton_map_contracts(const NewtonMapDerivative& dG);

ProjectionResult project_hybrid(const SurfaceFormulas& formulas, const ParamBox& box, const Vec3& p,
                                const Options& options);

}  // namespace footpoint::surface
