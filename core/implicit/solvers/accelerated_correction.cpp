#include "implicit/solvers/accelerated_correction.hpp"

#include <cmath>

#include "geometry/dense_solve.hpp"
#include "implicit/geometry/implicit_curve_differentials.hpp"
#include "implicit/solvers/steepest_descent.hpp"

namespace footpoint::curve {
namespace {

// Minimum-norm dV with <grad f1, dV> = -err1, <grad f2, dV> = -err2: dV = -J^T (J J^T)^{-1} err.
bool minimum_norm_correction(const ImplicitJet& j, Vec3& dv) {
  Matrix<2> g{{{dot(j.grad[0], j.grad[0]), dot(j.grad[0], j.grad[1])},
               {dot(j.grad[1], j.grad[0]), dot(j.grad[1], j.grad[1])}}};
  Vector<2> b{-j.f[0], -j.f[1]};
  if (!dense_solve<2>(g, b)) return false;
  dv = b[0] * j.grad[0] + b[1] * j.grad[1];
  return true;
}

// The correction vector dV of eq. (18) at Z (jet jz) for DV = U - Z. Each row of the system is
// scaled to unit length (which leaves its solution unchanged) so that the test for a singular
// system compares like with like.
bool correction_vector(const ImplicitJet& jz, Vec3 big_dv, Vec3& dv) {
  Vec3 c;
  if (curvature_vector(jz, c)) {
    const Vec3 w = cross(cross(unit_tangent(jz), c), big_dv);
    const double n0 = norm(jz.grad[0]), n1 = norm(jz.grad[1]), nw = norm(w);
    if (nw > 0.0 && std::isfinite(nw)) {
      const Vec3 r0 = jz.grad[0] / n0, r1 = jz.grad[1] / n1, r2 = w / nw;
      Matrix<3> a{{{r0.x, r0.y, r0.z}, {r1.x, r1.y, r1.z}, {r2.x, r2.y, r2.z}}};
      Vector<3> b{-jz.f[0] / n0, -jz.f[1] / n1, 0.0};
      if (dense_solve<3>(a, b)) {
        dv = {b[0], b[1], b[2]};
        return true;
      }
    }
  }
  return minimum_norm_correction(jz, dv);
}

}  // namespace

bool newton_onto_equation(const ImplicitEquations& equations, int i, Vec3 y, Vec3& z) {
  return newton_onto_surface(equations.jet(y), i, y, z);
}

bool newton_onto_orthogonality(const ImplicitJet& jz, Vec3 z, Vec3 p, Vec3& u) {
  const OrthogonalityFunction f = orthogonality_function(jz, z, p);
  const double g2 = norm2(f.gradient);
  if (!(g2 > 0.0)) return false;
  u = z - (f.value / g2) * f.gradient;
  return true;
}

Landing accelerate_onto_foot(const ImplicitEquations& equations, Vec3 p, Vec3 x0,
                             const IterationControl& control) {
  // Eq. (19): Y and Z by the Newton steps onto f1 = 0 and f2 = 0, U by the one onto F = 0, then
  // X_{n+1} = U + dV.
  auto eq19 = [&](Vec3 x, Vec3& x1) {
    Vec3 y, z, u, dv;
    if (!newton_onto_equation(equations, 0, x, y) || !newton_onto_equation(equations, 1, y, z)) return false;
    const ImplicitJet jz = equations.jet(z);
    if (!newton_onto_orthogonality(jz, z, p, u) || !correction_vector(jz, u - z, dv)) return false;
    x1 = u + dv;
    return true;
  };
  const double limit = kPaperDivergence * std::max(1.0, norm(x0) + norm(p));
  return iterate_paper_map(equations, PaperGoal::foot_of(p), x0, limit, control, eq19);
}

ProjectionResult accelerated(const ImplicitEquations& equations, const Box3& box, Vec3 p,
                             const Options& options) {
  std::vector<std::array<double, 3>> trace;
  const IterationControl control = make_control(options, kPaperIterations, &trace);
  // Algorithm 3 starts on the curve: Algorithm 1 from the paper's start first.
  Landing l = land_on_curve(equations, paper_start(p, options, equations.planar()), control);
  if (l.status == Status::converged) l = accelerate_onto_foot(equations, p, l.x, control);
  return paper_result(equations, box, p, "accelerated", l, control, PaperGoal::foot_of(p), std::move(trace));
}

}  // namespace footpoint::curve
