// Moving a point near an implicit curve onto it, by Newton's method with exact Jacobians. Used to
// seed and trace the curve (implicit/seeding/curve_discovery) and by the local solvers of `auto`.
#pragma once
#include "implicit/geometry/implicit_curve.hpp"

namespace footpoint::curve {

// Minimum-norm Gauss-Newton onto f1 = f2 = 0: x <- x - J^T (J J^T)^{-1} f with J the 2 x 3 matrix
// of the gradients (the nearest point of the linearised curve). True when it converged (the last
// step below 1e-14 max(1, |x|)) within max_iterations; x is then on the curve.
bool newton_onto_curve(const ImplicitEquations& equations, Vec3& x, int max_iterations = 16);

// Newton on f1(Z) = f2(Z) = 0, <Z - y, t> = 0: the point of the curve in the plane through y
// orthogonal to t (the corrector of a predictor-corrector walk along t). z starts at y.
bool correct_in_normal_plane(const ImplicitEquations& equations, Vec3 y, Vec3 t, Vec3& z, int& iterations);

// The point where the curve leaves the box between `inside` (in the box) and `outside` (not): the
// face is the first one the segment crosses, and Newton solves f1 = f2 = 0 in the two free
// coordinates. False when that fails or lands outside the face.
bool locate_face_crossing(const ImplicitEquations& equations, const Box3& box, Vec3 inside, Vec3 outside,
                          Vec3& crossing);

}  // namespace footpoint::curve
