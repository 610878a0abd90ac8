#include "solvers/curve/tangent_foot.hpp"

#include <cmath>

#include "solvers/curve/steepest_descent.hpp"

namespace footpoint::curve {

ProjectionResult tangent_foot(const ImplicitEquations& equations, const Box3& box, Vec3 p,
                              const Options& options) {
  std::vector<std::array<double, 3>> trace;
  const IterationControl control = make_control(options, kPaperIterations, &trace);
  IterationControl landing = control;
  landing.trace = nullptr;
  // Eq. (2) is eq. (9) for the embedding f1 = f, f2 = z: its second half-step does nothing.
  Landing l = land_on_curve(equations, paper_start(p, options, true), landing);
  Vec3 y = l.x;
  Status status = l.status;
  double step = l.step;
  int rounds = 0;
  double previous = kInfinity;
  while (status == Status::converged) {
    if (rounds >= control.max_iterations) {
      status = Status::max_iterations;
      break;
    }
    const ImplicitJet j = equations.jet(y);
    const double g2 = norm2(j.grad[0]);
    if (!(g2 > 0.0)) {
      status = Status::degenerate;
      break;
    }
    const Vec3 q = p - (dot(p - y, j.grad[0]) / g2) * j.grad[0];  // eq. (4)
    l = land_on_curve(equations, q, landing);
    if (l.status != Status::converged) {
      status = l.status;
      break;
    }
    const Vec3 dy = l.x - y;
    step = norm(dy);
    y = l.x;
    ++rounds;
    control.record(dy.x, dy.y);
    if (paper_iteration_done(equations, p, y, step, previous, control, true)) break;
  }
  ProjectionResult r = paper_result(equations, box, p, y, "tangent_foot", status, rounds, step, control);
  r.trace = std::move(trace);
  return r;
}

}  // namespace footpoint::curve
