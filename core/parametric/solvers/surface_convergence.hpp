// When a surface projection counts as converged, shared by every surface method. The tolerance
// and the budget are read from the Options as for every method (solvers/iteration_control.hpp,
// which says why the curves' stopping rule is another).
//
// Both conditions are required (numerical honesty):
//  - the parameters have settled: the last increment |Δt|∞ <= tol x max(domain scale, |u|, |v|)
//    (so the default 1e-15 means a few ulps of the parameters), and
//  - the orthogonality conditions F_i = <p - s, s_i> = 0 ([Hybrid] eq. (23), [GSA]
//    eq. (31)) hold: |F_i| / (|p - s| |s_i|) <= max(tol, floor), where
//    floor = 16 eps (|p| + |s|) / |p - s| is the rounding of computing p - s itself. A residual at
//    the floor ends the iteration whatever the step (it cannot get better).
// Formulas evaluated with large cancellation (sin of a large argument, high-degree polynomials)
// can hold the residual above that floor while the steps are down to rounding: when the step
// test has passed three times in a row with the residual still above it but below
// kStalledResidual, the iteration has stalled at the formulas' rounding level and counts as
// converged (the summary still reports the residuals as they are).
#pragma once
#include <array>

#include "parametric/geometry/parametric_surface.hpp"
#include "projection/projection_result.hpp"
#include "solvers/iteration_control.hpp"

namespace footpoint::surface {

// Largest relative residual accepted for an iteration stalled at the rounding level: orthogonal
// to half the digits at least, else it is no stationary point at all.
inline constexpr double kStalledResidual = 1e-8;
inline constexpr int kStalledSteps = 3;

struct ConvergenceCriteria {
  double tolerance = kDefaultTolerance;  // relative step and residual tolerance
  double scale = 1.0;                    // parameter scale of the domain (parameter_scale)
  int max_iterations = 0;
  double step_bound(double u, double v) const { return tolerance * step_scale(u, v); }
  // max(scale, |u|, |v|): what the step is measured against
  double step_scale(double u, double v) const;
};

// Largest |bound| of the domain (at least the domain's width): the parameter scale.
double parameter_scale(const ParamBox& box);

// Resolves Options (0 = the method's default) against the domain.
ConvergenceCriteria convergence_criteria(const Options& options, const ParamBox& box,
                                         int default_max_iterations);

// The orthogonality residuals of a foot point s(t) for the point p.
struct Orthogonality {
  std::array<double, 2> relative{0.0, 0.0};  // |F_i| / (|p-s| |s_i|), 0 where s_i = 0 (a pole)
  double floor = 0.0;                        // the rounding floor of the relative residual
};
Orthogonality orthogonality(const Vec3& p, const Vec3& s, const Vec3& su, const Vec3& sv);
// The same with |p| given (an iteration computes it once).
Orthogonality orthogonality(const Vec3& p, double norm_p, const Vec3& s, const Vec3& su, const Vec3& sv);

// The stopping test of an iteration, fed once per step. `free` masks the residuals that must
// vanish (a parameter held on its bound by the projected Newton method has no such condition).
class ConvergenceTest {
 public:
  explicit ConvergenceTest(const ConvergenceCriteria& criteria) : criteria_(criteria) {}
  // step_inf = |Δt|∞ of the step just taken (or about to be taken) at (u, v).
  bool converged(double step_inf, double u, double v, const Orthogonality& o,
                 std::array<bool, 2> free = {true, true});
  // What converged() concludes, without the residuals, for a step above the step bound and a
  // residual above its floor: not converged, and not stalled either.
  void unsettled() { stalled_ = 0; }

 private:
  const ConvergenceCriteria& criteria_;
  int stalled_ = 0;
};

}  // namespace footpoint::surface
