// The spatial-curve paper's Algorithm 2 (computing the foot point Q, eqs. (10)-(13)) and the method
// `foot_point_march`: Algorithms 1 and 2 run alternately, as in the for-loop of Algorithm 4 but
// until the curve point stops moving.
#pragma once
#include "geometry/implicit_curve.hpp"
#include "geometry/projection_result.hpp"
#include "solvers/curve/iteration_control.hpp"

namespace footpoint::curve {

// Algorithm 2 at the curve point P_I: the tangent line X = t T + P_I (eq. (10)) meets the plane
// through P orthogonal to it at Q0 = t0 T + P_I, t0 = <P - P_I, T> / <T, T> (eq. (11)); Q is the
// point of the segment Q0 P with |Q0 Q| = |P_I Q0| / 2, Q = d (P - Q0) + Q0 with d = d1 / d2,
// d1 = |P_I Q0| / 2, d2 = |Q0 P| (eqs. (12)-(13)). Returns false when T = 0 (singular point).
bool foot_point(const ImplicitEquations& equations, Vec3 p, Vec3 p_i, Vec3& q);

ProjectionResult foot_point_march(const ImplicitEquations& equations, const Box3& box, Vec3 p,
                                  const Options& options);

}  // namespace footpoint::curve
