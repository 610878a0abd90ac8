// Newton's method on the Lagrange (KKT) system of min |p - X|^2 / 2 subject to f(X) = 0 on an
// implicit surface,
//   X - p + l grad f(X) = 0,   f(X) = 0,
// with the 4 x 4 Jacobian [[I + l H, grad f], [grad f^T, 0]] (H the exact Hessian of f), solved
// by Gaussian elimination with partial pivoting (geometry/dense_solve.hpp); and the same on a face
// x_k = c of the box, the system of the spatial curve {f = 0} ∩ {x_k = c} (its second gradient
// e_k, its Hessian 0: implicit/geometry/lagrange_step.hpp's null-space step). Quadratic convergence
// from a nearby surface point ([NW06] Sec. 18.1, Theorem 18.4); the multipliers start at the
// least-squares solution of p - X = l grad f (+ m e_k).
#pragma once
#include <array>
#include <vector>

#include "implicit/geometry/implicit_surface.hpp"
#include "projection/projection_result.hpp"
#include "solvers/iteration_control.hpp"

namespace footpoint::surface_implicit {

struct SurfaceMinimum {
  Vec3 x;
  double multiplier = 0.0;  // l at x
  int iterations = 0;
  double step = 0.0;
  bool converged = false;
};

// From x0; each step is shortened to at most max_step (the cell size of the sample it starts
// from; infinity for no limit), and the solve gives up after 8 shortened steps.
SurfaceMinimum lagrange_newton_interior(const ImplicitSurfaceEquation& equation, Vec3 p, Vec3 x0,
                                        double max_step, const curve::IterationControl& control);

// On the plane x_axis = value (x0 is moved onto it first).
SurfaceMinimum lagrange_newton_face(const ImplicitSurfaceEquation& equation, Vec3 p, Vec3 x0, int axis,
                                    double value, double max_step, const curve::IterationControl& control);

// The Lagrangian's Hessian A = I + l H at a point of the surface, restricted to its tangent plane
// (grad f != 0, n = grad f / |grad f|), in the orthonormal basis t1 = n x e / |n x e| (e the
// axis least aligned with n among x, y), t2 = n x t1: [a11 a12; a12 a22]. Positive semidefinite
// at a local minimum of the distance on the surface ([NW06] Theorem 12.5); singular where p is
// a centre of curvature of the surface.
struct TangentForm {
  double a11 = 0.0, a12 = 0.0, a22 = 0.0;
  double least_eigenvalue() const;
};
// The Lagrangian's Hessian I + l H at the jet.
Mat3 lagrangian_hessian(const ImplicitSurfaceJet& j, double l);
// `a` = I + l H; `n` the unit normal.
TangentForm tangent_form(const Mat3& a, Vec3 n);

// Where x lies in the box: interior, box_face, box_edge or box_corner by how many coordinates
// are at a bound (within `slack`).
Location box_location(const Box3& box, Vec3 x, double slack = 0.0);

// A result at the foot x of p: the distance, |f| / |grad f| (equation_residual[0]), the sine
// between p - x and grad f in the directions x can move in within the box (orthogonality[0]; 0
// when p = x, on an edge, at a corner), the location in the box.
ProjectionResult implicit_surface_result(const ImplicitSurfaceEquation& equation, const Box3& box, Vec3 p,
                                         Vec3 x, const char* method);

}  // namespace footpoint::surface_implicit
