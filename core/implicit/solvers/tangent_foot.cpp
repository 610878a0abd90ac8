#include "implicit/solvers/tangent_foot.hpp"

#include <cmath>

#include "implicit/solvers/foot_point_march.hpp"

namespace footpoint::curve {

ProjectionResult tangent_foot(const ImplicitEquations& equations, const Box3& box, Vec3 p,
                              const Options& options) {
  std::vector<std::array<double, 3>> trace;
  const IterationControl control = make_control(options, kPaperIterations, &trace);
  IterationControl landing = control;
  landing.trace = nullptr;
  // Eq. (2) is eq. (9) for the embedding f1 = f, f2 = z: its second half-step does nothing.
  const Landing start = land_on_curve(equations, paper_start(p, options, true), landing);
  // Eq. (4): the foot point of p on the tangent line at the curve point y.
  auto tangent_foot_point = [&](Vec3 y, Vec3& q) {
    const ImplicitJet j = equations.jet(y);
    const double g2 = norm2(j.grad[0]);
    if (!(g2 > 0.0)) return false;
    q = p - (dot(p - y, j.grad[0]) / g2) * j.grad[0];
    return true;
  };
  const Landing end = march_on_curve(equations, p, start, control, landing, tangent_foot_point);
  return paper_result(equations, box, p, "tangent_foot", end, control, PaperGoal::foot_of(p),
                      std::move(trace));
}

}  // namespace footpoint::curve
