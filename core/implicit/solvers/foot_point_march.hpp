// [Curve] Algorithm 2 (computing the foot point Q, eqs. (10)-(13)), the march that alternates a
// foot point with Algorithm 1 back onto the curve, and the method `foot_point_march`: Algorithms 2
// and 1 alternately, as in the for-loop of Algorithm 4 but until the curve point stops moving.
#pragma once
#include "implicit/geometry/implicit_curve.hpp"
#include "implicit/solvers/paper_iteration.hpp"
#include "implicit/solvers/steepest_descent.hpp"
#include "projection/projection_result.hpp"
#include "solvers/iteration_control.hpp"

namespace footpoint::curve {

// Algorithm 2 at the curve point P_I: the tangent line X = t T + P_I (eq. (10)) meets the plane
// through P orthogonal to it at Q0 = t0 T + P_I, t0 = <P - P_I, T> / <T, T> (eq. (11)); Q is the
// point of the segment Q0 P with |Q0 Q| = |P_I Q0| / 2, Q = d (P - Q0) + Q0 with d = d1 / d2,
// d1 = |P_I Q0| / 2, d2 = |Q0 P| (eqs. (12)-(13)). Returns false when T = 0 (singular point).
bool foot_point(const ImplicitEquations& equations, Vec3 p, Vec3 p_i, Vec3& q);

// The march from `start` (where Algorithm 1 landed): rounds of a foot point q of p from the curve
// point x (`foot(x, q)`; false where there is none: degenerate), then Algorithm 1 from q back onto
// the curve (with `landing`), until the curve points stop moving where they are orthogonal
// (paper_iteration_done) or `control`'s budget of rounds is spent. Each round's increment of the
// curve point is recorded; the iterations are the rounds. A landing that fails ends the march at
// the last curve point with the landing's status.
template <class FootPoint>
Landing march_on_curve(const ImplicitEquations& equations, Vec3 p, const Landing& start,
                       const IterationControl& control, const IterationControl& landing, FootPoint&& foot) {
  Landing out{start.x, 0, start.step, start.status};
  const PaperGoal goal = PaperGoal::foot_of(p);
  double previous = kInfinity;
  while (out.status == Status::converged) {
    if (out.iterations >= control.max_iterations) {
      out.status = Status::max_iterations;
      break;
    }
    Vec3 q;
    if (!foot(out.x, q)) {
      out.status = Status::degenerate;
      break;
    }
    const Landing l = land_on_curve(equations, q, landing);
    if (l.status != Status::converged) {
      out.status = l.status;
      break;
    }
    const Vec3 dx = l.x - out.x;
    out.step = norm(dx);
    out.x = l.x;
    ++out.iterations;
    control.record(dx.x, dx.y, dx.z);
    if (paper_iteration_done(equations, goal, out.x, out.step, previous, control)) break;
  }
  return out;
}

ProjectionResult foot_point_march(const ImplicitEquations& equations, const Box3& box, Vec3 p,
                                  const Options& options);

}  // namespace footpoint::curve
