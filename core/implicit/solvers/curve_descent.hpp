// A monotone descent of the distance along an implicit curve, `auto`'s fallback when Newton on the
// Lagrange system does not settle on a minimum near its start (e.g. far from a well-conditioned
// minimum). With s the arc length, phi(s) = |X(s) - p|^2 / 2 has
//   phi'  = <X - p, T>,    phi'' = 1 + <X - p, c>
// (T the unit tangent, c the curvature vector of [Curve] eq. (16)). A Newton
// step ds = -phi' / phi'' (or a descent step where phi'' <= 0), at most max_step, and at most four
// times the last accepted step when that one had to be halved and decreased the distance beyond
// rounding (a trust region: toward a cusp phi' does not vanish, the Newton step stays long while
// the arc left shrinks, and each iteration would halve its way down from it again), is predicted
// to X + ds T + ds^2 / 2 c, corrected back onto the curve in the normal plane, and halved until
// the distance decreases.
#pragma once
#include "implicit/geometry/implicit_curve.hpp"
#include "implicit/solvers/lagrange_newton.hpp"
#include "solvers/iteration_control.hpp"

namespace footpoint::curve {

LocalMinimum curve_descent(const ImplicitEquations& equations, Vec3 p, Vec3 x0, double max_step,
                           const IterationControl& control);

}  // namespace footpoint::curve
