#include "solvers/curve/simplified_projection.hpp"

#include <cmath>

#include "solvers/curve/accelerated_correction.hpp"
#include "solvers/curve/steepest_descent.hpp"

namespace footpoint::curve {
namespace {

constexpr double kDivergence = 1e12;

// Iterates eq. (20) from the curve point x0.
Landing iterate_eq20(const ImplicitEquations& equations, Vec3 p, Vec3 x0, const IterationControl& control) {
  Landing out;
  out.x = x0;
  const double limit = kDivergence * std::max(1.0, norm(x0) + norm(p));
  double previous = kInfinity;
  for (int n = 0;; ++n) {
    if (n >= control.max_iterations) {
      out.status = Status::max_iterations;
      return out;
    }
    Vec3 y, z, x1;
    if (!newton_onto_equation(equations, 0, out.x, y) || !newton_onto_equation(equations, 1, y, z) ||
        !newton_onto_orthogonality(equations.jet(z), z, p, x1)) {
      out.status = Status::degenerate;
      return out;
    }
    if (take_paper_step(equations, p, x1, n, limit, previous, control, true, out)) return out;
  }
}

}  // namespace

ProjectionResult simplified_projection(const ImplicitEquations& equations, const Box3& box, Vec3 p,
                                       const Options& options) {
  return land_then(equations, box, p, options, "simplified",
                   [&](const Landing& l, const IterationControl& control) {
                     return iterate_eq20(equations, p, l.x, control);
                   });
}

}  // namespace footpoint::curve
