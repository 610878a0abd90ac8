// Armijo's backtracking along the projection arc t(α) = clamp(t + α d) onto the parameter box
// (Bertsekas 1982), the line search of the projected Newton method
// (parametric/solvers/projected_newton.hpp): the first α = 1, ½, ¼, ... with sufficient decrease
//   f(t(α)) <= f(t) + kSufficientDecrease <g, t(α) - t>,   f = ½|s - p|^2,
// the decrease computed as f(t') - f(t) = ½ (s' - s)·((s' - p) + (s - p)), without the cancellation
// of two large f for far points. Small convex steps are Newton's local regime, where f changes by
// little more than its rounding: taken as they are.
#pragma once
#include "parametric/geometry/parametric_surface.hpp"
#include "parametric/geometry/params.hpp"

namespace footpoint::surface {

struct ArcStep {
  bool accepted = false;
  bool vanishes = false;  // the full step changes no parameter: they are as good as they can be
  Params<2> t{0.0, 0.0};
  SurfaceJet jet;  // evaluated at t, when accepted
};

// From t (jet there, gradient g) along d, inside [lo, hi]; `step_scale` is the parameters' scale
// (surface_convergence.hpp).
ArcStep search_projection_arc(const SurfaceFormulas& formulas, const Vec3& p, const SurfaceJet& jet,
                              const Params<2>& t, const Params<2>& d, const Params<2>& lo,
                              const Params<2>& hi, const double (&g)[2], bool convex, double step_scale);

}  // namespace footpoint::surface
