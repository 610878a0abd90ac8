#include "implicit/solvers/steepest_descent.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

namespace footpoint::curve {
namespace {

// Eq. (9) with the termination test of Algorithm 1: |f1(X)| and |f2(X)| below epsilon (here
// relative, scaled by the gradients, so that the test does not depend on how f is normalised).
struct SteepestDescent {
  const ImplicitEquations& equations;
  double tolerance;
  ImplicitJet jx;  // the jet at the iterate, from stop_before for next

  std::optional<Status> stop_before(Vec3 x) {
    jx = equations.jet(x);
    if (!std::isfinite(jx.f[0]) || !std::isfinite(jx.f[1])) return Status::non_finite;
    const double eps = tolerance * std::max(1.0, norm(x));
    if (std::fabs(jx.f[0]) <= eps * norm(jx.grad[0]) && std::fabs(jx.f[1]) <= eps * norm(jx.grad[1]))
      return Status::converged;
    return std::nullopt;
  }
  bool operator()(Vec3 x, Vec3& x1) const {
    Vec3 y;
    return newton_onto_surface(jx, 0, x, y) && newton_onto_surface(equations.jet(y), 1, y, x1);
  }
};

}  // namespace

Landing land_on_curve(const ImplicitEquations& equations, Vec3 x0, const IterationControl& control) {
  const double limit = kPaperDivergence * std::max(1.0, norm(x0));
  return iterate_paper_map(equations, PaperGoal::on_curve(), x0, limit, control,
                           SteepestDescent{equations, control.step_tolerance, {}});
}

ProjectionResult steepest_descent(const ImplicitEquations& equations, const Box3& box, Vec3 p,
                                  const Options& options) {
  std::vector<std::array<double, 3>> trace;
  const IterationControl control = make_control(options, kPaperIterations, &trace);
  const Landing l = land_on_curve(equations, paper_start(p, options, equations.planar()), control);
  return paper_result(equations, box, p, "steepest_descent", l, control, PaperGoal::on_curve(),
                      std::move(trace));
}

}  // namespace footpoint::curve
