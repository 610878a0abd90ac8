// [Curve] Algorithm 4, the complete algorithm: Algorithm 1 from the start
// (X0 = P - (0.1, 0.1, 0.1)), five rounds of Algorithm 2 (foot point Q) followed by Algorithm 1
// (Q back onto the curve), then Algorithm 3 (eq. (19)) until the iterates stop moving.
// Known limit, Algorithm 3's (implicit/solvers/accelerated_correction.hpp): on a curve that lies
// in a plane its correction is not determined at the foot point, and the iteration ends at its
// budget (max_iterations) near the foot; Algorithm 5 (simplified_projection.hpp) converges there.
#pragma once
#include "implicit/geometry/implicit_curve.hpp"
#include "projection/projection_result.hpp"

namespace footpoint::curve {

ProjectionResult complete_projection(const ImplicitEquations& equations, const Box3& box, Vec3 p,
                                     const Options& options);

}  // namespace footpoint::curve
