#include "geometry/implicit_curve_differentials.hpp"

#include "geometry/dense_solve.hpp"

namespace footpoint::curve {

Vec3 unit_tangent(const ImplicitJet& j) {
  const Vec3 t = j.tangent();
  const double n = norm(t);
  return n > 0.0 ? t / n : Vec3{};
}

bool curvature_vector(const ImplicitJet& j, Vec3& c) {
  const Vec3 t = unit_tangent(j);
  if (norm2(t) == 0.0) return false;
  // eq. (15) as the linear system W2 c = b.
  Matrix<3> w{
      {{j.grad[0].x, j.grad[0].y, j.grad[0].z}, {j.grad[1].x, j.grad[1].y, j.grad[1].z}, {t.x, t.y, t.z}}};
  Vector<3> b{-dot(t, j.hess[0] * t), -dot(t, j.hess[1] * t), 0.0};
  if (!dense_solve<3>(w, b)) return false;
  c = {b[0], b[1], b[2]};
  return true;
}

OrthogonalityFunction orthogonality_function(const ImplicitJet& j, Vec3 x, Vec3 p) {
  const Vec3 t = j.tangent();
  const Vec3 d = p - x;
  OrthogonalityFunction f;
  f.value = dot(t, d);
  for (int k = 0; k < 3; ++k) {
    // Column k of a symmetric Hessian is its row k.
    const Vec3 dt = cross(j.hess[0][k], j.grad[1]) + cross(j.grad[0], j.hess[1][k]);
    f.gradient[k] = dot(dt, d) - t[k];
  }
  return f;
}

}  // namespace footpoint::curve
