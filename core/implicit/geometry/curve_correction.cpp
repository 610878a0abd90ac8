#include "implicit/geometry/curve_correction.hpp"

#include <cmath>

#include "geometry/dense_solve.hpp"

namespace footpoint::curve {
namespace {

constexpr double kStepTolerance = 1e-14;

}  // namespace

bool newton_onto_curve(const ImplicitEquations& equations, Vec3& x, int max_iterations) {
  for (int n = 0; n < max_iterations; ++n) {
    const ImplicitJet j = equations.jet(x);
    Matrix<2> g{{{dot(j.grad[0], j.grad[0]), dot(j.grad[0], j.grad[1])},
                 {dot(j.grad[1], j.grad[0]), dot(j.grad[1], j.grad[1])}}};
    Vector<2> b{j.f[0], j.f[1]};
    if (!dense_solve<2>(g, b)) return false;
    const Vec3 dx = b[0] * j.grad[0] + b[1] * j.grad[1];
    x -= dx;
    if (!is_finite(x)) return false;
    if (norm(dx) <= kStepTolerance * std::max(1.0, norm(x))) return true;
  }
  return false;
}

bool correct_in_normal_plane(const ImplicitEquations& equations, Vec3 y, Vec3 t, Vec3& z, int& iterations) {
  z = y;
  for (iterations = 1; iterations <= 10; ++iterations) {
    const ImplicitJet j = equations.jet(z);
    Matrix<3> a{
        {{j.grad[0].x, j.grad[0].y, j.grad[0].z}, {j.grad[1].x, j.grad[1].y, j.grad[1].z}, {t.x, t.y, t.z}}};
    Vector<3> b{-j.f[0], -j.f[1], -dot(z - y, t)};
    if (!dense_solve<3>(a, b)) return false;
    const Vec3 dz{b[0], b[1], b[2]};
    z += dz;
    if (!is_finite(z)) return false;
    if (norm(dz) <= kStepTolerance * std::max(1.0, norm(z))) return true;
  }
  return false;
}

bool locate_face_crossing(const ImplicitEquations& equations, const Box3& box, Vec3 inside, Vec3 outside,
                          Vec3& crossing) {
  // The face first crossed by the segment inside -> outside.
  int axis = -1;
  double best = 2.0, value = 0.0;
  for (int k = 0; k < 3; ++k) {
    const double d = outside[k] - inside[k];
    if (outside[k] > box.hi[k] && d > 0.0) {
      const double s = (box.hi[k] - inside[k]) / d;
      if (s < best) best = s, axis = k, value = box.hi[k];
    } else if (outside[k] < box.lo[k] && d < 0.0) {
      const double s = (box.lo[k] - inside[k]) / d;
      if (s < best) best = s, axis = k, value = box.lo[k];
    }
  }
  if (axis < 0) return false;
  const int a = (axis + 1) % 3, b = (axis + 2) % 3;  // the free coordinates
  Vec3 x = inside + best * (outside - inside);
  x[axis] = value;
  for (int n = 0; n < 16; ++n) {
    const ImplicitJet j = equations.jet(x);
    Matrix<2> m{{{j.grad[0][a], j.grad[0][b]}, {j.grad[1][a], j.grad[1][b]}}};
    Vector<2> r{-j.f[0], -j.f[1]};
    if (!dense_solve<2>(m, r)) return false;
    x[a] += r[0];
    x[b] += r[1];
    if (!is_finite(x)) return false;
    if (std::hypot(r[0], r[1]) <= kStepTolerance * std::max(1.0, norm(x))) {
      crossing = x;
      return box.contains(x, 1e-12 * std::max(1.0, norm(x)));
    }
  }
  return false;
}

}  // namespace footpoint::curve
