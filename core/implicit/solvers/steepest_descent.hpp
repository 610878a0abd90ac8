// [Curve] Algorithm 1: Newton's steepest gradient descent, eq. (9),
//   Y_n     = X_n - f1(X_n) / <grad f1(X_n), grad f1(X_n)> grad f1(X_n),
//   X_{n+1} = Y_n - f2(Y_n) / <grad f2(Y_n), grad f2(Y_n)> grad f2(Y_n),
// alternating Newton steps onto f1 = 0 and f2 = 0 until the point lies on both. (The printed
// "/ grad f" is a typo for the product with grad f: a vector cannot divide.) It lands on the curve
// near its start; it does not look for the foot point.
#pragma once
#include "implicit/geometry/implicit_curve.hpp"
#include "implicit/solvers/paper_iteration.hpp"
#include "projection/projection_result.hpp"
#include "solvers/iteration_control.hpp"

namespace footpoint::curve {

// Algorithm 1 from x0: iterate eq. (9) until |f1|, |f2| (scaled by |grad f_i|) are below the step
// tolerance or the step stops moving on the curve. Records each increment when control.trace is set.
Landing land_on_curve(const ImplicitEquations& equations, Vec3 x0, const IterationControl& control);

// The method `steepest_descent`: Algorithm 1 from the paper's start (or options.initial).
// Converged when the point is on the curve and happens to be orthogonal; not_orthogonal when it
// is only on the curve.
ProjectionResult steepest_descent(const ImplicitEquations& equations, const Box3& box, Vec3 p,
                                  const Options& options);

}  // namespace footpoint::curve
