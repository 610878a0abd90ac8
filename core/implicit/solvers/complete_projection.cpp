#include "implicit/solvers/complete_projection.hpp"

#include "implicit/solvers/accelerated_correction.hpp"
#include "implicit/solvers/foot_point_march.hpp"
#include "implicit/solvers/paper_iteration.hpp"
#include "implicit/solvers/steepest_descent.hpp"

namespace footpoint::curve {

// Rounds of Algorithms 2 + 1 in Algorithm 4's for-loop ("an empirical value", Remark 3).
constexpr int kFootPointRounds = 5;

ProjectionResult complete_projection(const ImplicitEquations& equations, const Box3& box, Vec3 p,
                                     const Options& options) {
  std::vector<std::array<double, 3>> trace;
  const IterationControl control = make_control(options, kPaperIterations, &trace);
  // Step 1: Algorithm 1.
  Landing l = land_on_curve(equations, paper_start(p, options, equations.planar()), control);
  // Steps 2-3, five times: Algorithm 2, then Algorithm 1 from the foot point Q.
  for (int i = 0; i < kFootPointRounds && l.status == Status::converged; ++i) {
    Vec3 q;
    if (!foot_point(equations, p, l.x, q)) {
      l.status = Status::degenerate;
      break;
    }
    l = land_on_curve(equations, q, control);
  }
  // Step 4: Algorithm 3.
  if (l.status == Status::converged) l = accelerate_onto_foot(equations, p, l.x, control);
  return paper_result(equations, box, p, "complete", l, control, PaperGoal::foot_of(p), std::move(trace));
}

}  // namespace footpoint::curve
