// The spatial-curve paper's Algorithm 1: Newton's steepest gradient descent, eq. (9),
//   Y_n     = X_n - f1(X_n) / <grad f1(X_n), grad f1(X_n)> grad f1(X_n),
//   X_{n+1} = Y_n - f2(Y_n) / <grad f2(Y_n), grad f2(Y_n)> grad f2(Y_n),
// alternating Newton steps onto f1 = 0 and f2 = 0 until the point lies on both. (The printed
// "/ grad f" is a typo for the product with grad f: a vector cannot divide.) It lands on the curve
// near its start; it does not look for the foot point.
#pragma once
#include "geometry/implicit_curve.hpp"
#include "geometry/projection_result.hpp"
#include "solvers/curve/iteration_control.hpp"

namespace footpoint::curve {

// Iteration budget of each loop of the paper's algorithms (options.max_iterations overrides it):
// Algorithm 1 alone takes ~2,000 iterations from some of Example 2's test points (its surfaces
// meet at a small angle on the curve's long lobes), and eq. (20) as many again.
inline constexpr int kPaperIterations = 10000;

// The paper's start X0 = P - (0.1, 0.1, 0.1) (planar: P - (0.1, 0.1)), or options.initial.
Vec3 paper_start(Vec3 p, const Options& options, bool planar);

struct Landing {
  Vec3 x;
  int iterations = 0;
  double step = 0.0;                  // last increment |X_{n+1} - X_n|
  Status status = Status::converged;  // converged: landed; else why it stopped
};

// Algorithm 1 from x0: iterate eq. (9) until |f1|, |f2| (scaled by |grad f_i|) are below the step
// tolerance or the step stops moving. Records each increment when control.trace is set.
Landing land_on_curve(const ImplicitEquations& equations, Vec3 x0, const IterationControl& control);

// The method `steepest_descent`: Algorithm 1 from the paper's start (or options.initial).
// Converged when the point is on the curve; it is not, in general, orthogonal.
ProjectionResult steepest_descent(const ImplicitEquations& equations, const Box3& box, Vec3 p,
                                  const Options& options);

// Shared by the paper's loops: stop after a step of length `step` to x once the step is at the
// step tolerance or at the rounding floor, and x meets the residual tolerance. A loop whose steps
// are that small but whose residuals are not met goes on until its budget is spent: the paper's
// linear iterations contract so slowly on Example 2's lobes that their steps reach the last units
// of X while the orthogonality is still ~1e-11 (they end with max_iterations, honestly).
bool paper_iteration_done(const ImplicitEquations& equations, Vec3 p, Vec3 x, double step, double& previous,
                          const IterationControl& control, bool with_orthogonality);

// Shared by the paper's loops: accept the iterate X_{n+1} = x1 (record its increment) and say
// whether the loop stops: x1 non-finite, beyond `limit` (diverged) or done by paper_iteration_done
// (converged); `out.status` then says which.
bool take_paper_step(const ImplicitEquations& equations, Vec3 p, Vec3 x1, int n, double limit,
                     double& previous, const IterationControl& control, bool with_orthogonality,
                     Landing& out);

// Shared by the paper's methods: the result at x after a loop that ended with `status`
// (converged only if the residuals meet the tolerance; outside_domain when x is not in the box).
ProjectionResult paper_result(const ImplicitEquations& equations, const Box3& box, Vec3 p, Vec3 x,
                              const char* method, Status status, int iterations, double step,
                              const IterationControl& control, bool with_orthogonality = true);

// Shared by the paper's methods: Algorithm 1 from the paper's start (or options.initial), then
// `refine` (Landing refine(Landing landed, const IterationControl&)) when the landing converged,
// and the result at the end with the trace of every increment.
template <class Refine>
ProjectionResult land_then(const ImplicitEquations& equations, const Box3& box, Vec3 p,
                           const Options& options, const char* method, Refine&& refine,
                           bool with_orthogonality = true) {
  std::vector<std::array<double, 3>> trace;
  const IterationControl control = make_control(options, kPaperIterations, &trace);
  Landing l = land_on_curve(equations, paper_start(p, options, equations.planar()), control);
  if (l.status == Status::converged) l = refine(l, control);
  ProjectionResult r = paper_result(equations, box, p, l.x, method, l.status, l.iterations, l.step, control,
                                    with_orthogonality);
  r.trace = std::move(trace);
  return r;
}

}  // namespace footpoint::curve
