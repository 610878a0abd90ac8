// The step of the projected Newton method (parametric/solvers/projected_newton.hpp) at an iterate:
// Newton's step on the free parameters, with H's eigenvalues replaced by their absolute values
// (bounded away from 0) where H is not positive definite - a descent step of natural length at a
// saddle, on the concave side of the surface or at a pole - and the direction of negative
// curvature to leave a stationary saddle by.
#pragma once
#include <array>

#include "parametric/geometry/params.hpp"

namespace footpoint::surface {

// H counts as positive semidefinite when its smallest eigenvalue is >= -this x its largest entry
// (rounding of a singular H); eigenvalues are used at no less than this in absolute value.
inline constexpr double kSemidefinite = 1e-12;

struct NewtonDirection {
  Params<2> step{};                // zero on a held parameter
  Params<2> negative_curvature{};  // a unit direction with e^T H e < 0; zero when convex
  bool convex = true;              // H positive semidefinite on the free parameters
  // Both parameters free and H positive definite (λ1 >= kSemidefinite |H|): step = -H^{-1} g.
  bool definite = false;
  double det = 0.0;  // det H (both free)
};

// g and H of f = ½|s - p|^2 (projected_newton.hpp); `free_[i]` false for a parameter held on its
// bound.
NewtonDirection newton_direction(const double (&H)[2][2], const double (&g)[2], const bool (&free_)[2]);

}  // namespace footpoint::surface
