// The loop shared by the methods of the spatial-curve paper [Curve] on an implicit curve
// (Algorithms 1, 3, 5 and, through them, 4 and the marches of Algorithm 2 and of the planar
// iteration): from a start, X_{n+1} = step(X_n) exactly as printed, until the iterate stops moving
// (the step at the tolerance, or at the rounding floor) and meets the goal's residuals - on the
// curve for Algorithm 1, on the curve and orthogonal (eq. (7)) for the others. The papers' own
// stopping rules test |f_i| against epsilon; ours are relative (iteration_control.hpp), so that
// they do not depend on how the equations are scaled. With options.trace every increment
// X_{n+1} - X_n is recorded. The result at the end is converged only when the foot-point
// conditions hold (paper_result).
#pragma once
#include <array>
#include <optional>
#include <vector>

#include "implicit/geometry/implicit_curve.hpp"
#include "projection/projection_result.hpp"
#include "solvers/iteration_control.hpp"

namespace footpoint::curve {

// Iteration budget of each loop of the paper's algorithms (options.max_iterations overrides it):
// Algorithm 1 alone takes ~2,000 iterations from some of Example 2's test points (its surfaces
// meet at a small angle on the curve's long lobes), and eq. (20) as many again.
inline constexpr int kPaperIterations = 10000;
// Iterates farther than this from the origin (relative to the start) have left any sensible region.
inline constexpr double kPaperDivergence = 1e12;

// The paper's start X0 = P - (0.1, 0.1, 0.1) (planar: P - (0.1, 0.1)), or options.initial.
Vec3 paper_start(Vec3 p, const Options& options, bool planar);

// Where an iteration ended.
struct Landing {
  Vec3 x;
  int iterations = 0;
  double step = 0.0;                  // last increment |X_{n+1} - X_n|
  Status status = Status::converged;  // converged: the goal is met; else why it stopped
};

// What an iteration must reach: the curve (Algorithm 1), or the curve and orthogonality to p - X.
struct PaperGoal {
  bool orthogonal = false;
  Vec3 p;  // the projected point (orthogonal only)
  static PaperGoal on_curve() { return {}; }
  static PaperGoal foot_of(Vec3 p) { return {true, p}; }
};

// One Newton step onto the surface f_i = 0 along its gradient (eqs. (2), (9), (19), (20)):
// x - f_i / |grad f_i|^2 grad f_i, from the jet j at x. False when grad f_i = 0.
bool newton_onto_surface(const ImplicitJet& j, int i, Vec3 x, Vec3& out);

// After a step of length `step` to x (`previous`: the step before): true once the step is at the
// step tolerance or at the rounding floor and x meets the goal's residual tolerance. A loop whose
// steps are that small but whose residuals are not met goes on until its budget is spent: the
// paper's linear iterations contract so slowly on Example 2's lobes that their steps reach the last
// units of X while the orthogonality is still ~1e-11 (they end with max_iterations, honestly).
bool paper_iteration_done(const ImplicitEquations& equations, const PaperGoal& goal, Vec3 x, double step,
                          double& previous, const IterationControl& control);

// Accepts the iterate X_{n+1} = x1 into `out` (records its increment) and says whether the loop
// stops: x1 non-finite, beyond `limit` (diverged), or done (converged); out.status says which.
bool take_paper_step(const ImplicitEquations& equations, const PaperGoal& goal, Vec3 x1, int n, double limit,
                     double& previous, const IterationControl& control, Landing& out);

// The iteration X_{n+1} = step(X_n) from x0 until take_paper_step stops it or the budget is spent.
// `step(x, x1)` sets x1 and returns true, or false where no step is defined (degenerate). It may
// have a member `std::optional<Status> stop_before(Vec3 x)`, a test of the iterate before each step
// (an algorithm's own termination test; a status ends the loop at x).
template <class Step>
Landing iterate_paper_map(const ImplicitEquations& equations, const PaperGoal& goal, Vec3 x0, double limit,
                          const IterationControl& control, Step&& step) {
  Landing out;
  out.x = x0;
  double previous = kInfinity;
  for (int n = 0;; ++n) {
    if constexpr (requires { step.stop_before(x0); }) {
      if (const std::optional<Status> stop = step.stop_before(out.x)) {
        out.status = *stop;
        return out;
      }
    }
    if (n >= control.max_iterations) {
      out.status = Status::max_iterations;
      return out;
    }
    Vec3 x1;
    if (!step(out.x, x1)) {
      out.status = Status::degenerate;
      return out;
    }
    if (take_paper_step(equations, goal, x1, n, limit, previous, control, out)) return out;
  }
}

// The result of a paper method whose loops ended at `end`: converged only when the foot-point
// conditions hold (a method that only lands on the curve, Algorithm 1, reports not_orthogonal
// there; iterates that stopped moving where the residuals are not small are a stall, degenerate),
// outside_domain when the point is not in the box; max_distance applied; the trace attached.
ProjectionResult paper_result(const ImplicitEquations& equations, const Box3& box, Vec3 p, const char* method,
                              const Landing& end, const IterationControl& control, const PaperGoal& goal,
                              std::vector<std::array<double, 3>> trace);

}  // namespace footpoint::curve
