#include "implicit/solvers/foot_point_march.hpp"

#include <cmath>

namespace footpoint::curve {

bool foot_point(const ImplicitEquations& equations, Vec3 p, Vec3 p_i, Vec3& q) {
  const Vec3 t = equations.jet(p_i).tangent();
  const double tt = norm2(t);
  if (!(tt > 0.0)) return false;
  const Vec3 q0 = p_i + (dot(p - p_i, t) / tt) * t;  // eq. (11)
  const double d1 = 0.5 * norm(q0 - p_i);
  const double d2 = norm(p - q0);
  // eq. (13); when P lies on the tangent line (d2 = 0) the foot point is Q0 itself.
  q = d2 > 0.0 ? q0 + (d1 / d2) * (p - q0) : q0;
  return true;
}

ProjectionResult foot_point_march(const ImplicitEquations& equations, const Box3& box, Vec3 p,
                                  const Options& options) {
  std::vector<std::array<double, 3>> trace;
  // Rounds of Algorithms 2 + 1. The march slows down as it nears the foot point ([Curve] Remark 3:
  // "slower and slower"); from Example 1's test points it is still far from converged after
  // 10,000 rounds, so the default budget stops it early and says so (max_iterations).
  const IterationControl control = make_control(options, 500, &trace);
  IterationControl landing = control;
  landing.max_iterations = iteration_budget(options, kPaperIterations);
  landing.trace = nullptr;
  const Landing start = land_on_curve(equations, paper_start(p, options, equations.planar()), landing);
  const Landing end = march_on_curve(equations, p, start, control, landing,
                                     [&](Vec3 x, Vec3& q) { return foot_point(equations, p, x, q); });
  return paper_result(equations, box, p, "foot_point_march", end, control, PaperGoal::foot_of(p),
                      std::move(trace));
}

}  // namespace footpoint::curve
