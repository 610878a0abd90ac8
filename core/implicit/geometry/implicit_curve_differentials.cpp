#include "implicit/geometry/implicit_curve_differentials.hpp"

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

bool critical_point_step(const ImplicitJet& j, Vec3 x, Vec3 p, const std::array<double, 2>& f, Vec3& step) {
  const OrthogonalityFunction o = orthogonality_function(j, x, p);
  Matrix<3> a{};
  for (int c = 0; c < 3; ++c) {
    a[0][c] = j.grad[0][c];
    a[1][c] = j.grad[1][c];
    a[2][c] = o.gradient[c];
  }
  Vector<3> b{-f[0], -f[1], -o.value};
  if (!dense_solve<3>(a, b)) return false;
  step = {b[0], b[1], b[2]};
  return true;
}

}  // namespace footpoint::curve
