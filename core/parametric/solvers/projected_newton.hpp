// The local solve of `auto`: minimise f(t) = ½|s(t) - p|^2 over the closed parameter box by a
// projected Newton method (Bertsekas 1982) with an Armijo line search along the projection arc.
//   gradient  g = (<s - p, s_u>, <s - p, s_v>)            (= -F of eq. (23), hybrid paper)
//   Hessian   H = [E F; F G] + [<s-p, s_uu> <s-p, s_uv>; <s-p, s_uv> <s-p, s_vv>]
// A parameter on its bound with the gradient pushing outwards is held there (the active set), so
// edges become 1-D problems and corners points; the Newton step on the free parameters uses H
// with its eigenvalues replaced by their absolute values where it is not positive definite (a
// saddle, the concave side of the surface, a pole where s_u x s_v = 0), which keeps it a descent
// step of natural length, and a zero gradient at an indefinite H moves along negative curvature.
// Every accepted step decreases f, so the solve cannot end on a maximum or a saddle it did not
// start at, and it never leaves the domain.
//
// The parts, a file each: the step (newton_direction.hpp), the early stop with what `auto` already
// knows (basin_early_stop.hpp), Armijo's search along the projection arc (projection_arc_search.hpp).
#pragma once
#include <array>
#include <limits>
#include <vector>

#include "parametric/geometry/parametric_surface.hpp"
#include "parametric/solvers/basin_early_stop.hpp"
#include "parametric/solvers/surface_convergence.hpp"
#include "projection/projection_result.hpp"

namespace footpoint::surface {

struct LocalSolution {
  double u = 0.0, v = 0.0;
  SurfaceJet jet;         // at (u, v)
  double distance = 0.0;  // |p - s(u, v)|
  Status status = Status::non_finite;
  int iterations = 0;      // accepted steps
  double step_norm = 0.0;  // norm of the last accepted step
  // Stopped early (EarlyStop): (u, v) is the basin's predicted minimiser, `distance` the lower
  // bound on its distance, `jet` the one at the last iterate; status is not meaningful.
  bool abandoned = false;
  // Ended on a kink curve of the formulas, stationary there in Clarke's sense
  // (parametric/solvers/kink_minimum.hpp): converged, with location kink.
  bool kink = false;
};

// Default iteration budget of the local solve (Newton from a cell's model minimiser needs 2-4).
inline constexpr int kLocalMaxIterations = 100;

// Starts at (u0, v0) clamped into the box; `start_jet`, if given, is the jet there. With `trace`,
// appends every accepted step (Δu, Δv, 0). With `early`, may stop early with `abandoned` set.
LocalSolution projected_newton(const SurfaceFormulas& formulas, const ParamBox& box, const Vec3& p, double u0,
                               double v0, const ConvergenceCriteria& criteria,
                               std::vector<std::array<double, 3>>* trace = nullptr,
                               const EarlyStop* early = nullptr, const SurfaceJet* start_jet = nullptr);

}  // namespace footpoint::surface
