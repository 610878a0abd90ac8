#include "solvers/curve/accelerated_correction.hpp"

#include <cmath>

#include "geometry/dense_solve.hpp"
#include "geometry/implicit_curve_differentials.hpp"

namespace footpoint::curve {
namespace {

constexpr double kDivergence = 1e12;

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
  const ImplicitJet j = equations.jet(y);
  const double g2 = norm2(j.grad[i]);
  if (!(g2 > 0.0)) return false;
  z = y - (j.f[i] / g2) * j.grad[i];
  return true;
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
  Landing out;
  out.x = x0;
  const double limit = kDivergence * std::max(1.0, norm(x0) + norm(p));
  double previous = kInfinity;
  for (int n = 0;; ++n) {
    if (n >= control.max_iterations) {
      out.status = Status::max_iterations;
      return out;
    }
    Vec3 y, z, u, dv;
    if (!newton_onto_equation(equations, 0, out.x, y) || !newton_onto_equation(equations, 1, y, z)) {
      out.status = Status::degenerate;
      return out;
    }
    const ImplicitJet jz = equations.jet(z);
    if (!newton_onto_orthogonality(jz, z, p, u) || !correction_vector(jz, u - z, dv)) {
      out.status = Status::degenerate;
      return out;
    }
    const Vec3 x1 = u + dv;
    if (take_paper_step(equations, p, x1, n, limit, previous, control, true, out)) return out;
  }
}

ProjectionResult accelerated(const ImplicitEquations& equations, const Box3& box, Vec3 p,
                             const Options& options) {
  return land_then(equations, box, p, options, "accelerated",
                   [&](const Landing& l, const IterationControl& control) {
                     return accelerate_onto_foot(equations, p, l.x, control);
                   });
}

}  // namespace footpoint::curve
