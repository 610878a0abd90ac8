#include "implicit/solvers/simplified_projection.hpp"

#include <algorithm>
#include <cmath>

#include "implicit/solvers/accelerated_correction.hpp"
#include "implicit/solvers/paper_iteration.hpp"
#include "implicit/solvers/steepest_descent.hpp"

namespace footpoint::curve {

ProjectionResult simplified_projection(const ImplicitEquations& equations, const Box3& box, Vec3 p,
                                       const Options& options) {
  std::vector<std::array<double, 3>> trace;
  const IterationControl control = make_control(options, kPaperIterations, &trace);
  // Step 1: Algorithm 1.
  Landing l = land_on_curve(equations, paper_start(p, options, equations.planar()), control);
  if (l.status == Status::converged) {
    // Step 2: eq. (20), eq. (19) without the correction vector.
    auto eq20 = [&](Vec3 x, Vec3& x1) {
      Vec3 y, z;
      return newton_onto_equation(equations, 0, x, y) && newton_onto_equation(equations, 1, y, z) &&
             newton_onto_orthogonality(equations.jet(z), z, p, x1);
    };
    const double limit = kPaperDivergence * std::max(1.0, norm(l.x) + norm(p));
    l = iterate_paper_map(equations, PaperGoal::foot_of(p), l.x, limit, control, eq20);
  }
  return paper_result(equations, box, p, "simplified", l, control, PaperGoal::foot_of(p), std::move(trace));
}

}  // namespace footpoint::curve
