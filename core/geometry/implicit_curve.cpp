#include "geometry/implicit_curve.hpp"

namespace footpoint {

std::array<double, 2> ImplicitEquations::values(Vec3 x) const {
  std::array<double, 2> f{};
  if (planar_) {
    const double xy[2] = {x.x, x.y};
    program_.values(xy, f.data());
    f[1] = x.z;  // the embedding equation f2 = z
  } else {
    const double xyz[3] = {x.x, x.y, x.z};
    program_.values(xyz, f.data());
  }
  return f;
}

ImplicitJet ImplicitEquations::jet(Vec3 x) const {
  ImplicitJet j;
  if (planar_) {
    const double xy[2] = {x.x, x.y};
    formula::Jet2<2> f[1];
    program_.jets2<2>(xy, f);
    j.f[0] = f[0].v;
    j.grad[0] = {f[0].g[0], f[0].g[1], 0.0};
    j.hess[0][0] = {f[0].h[0][0], f[0].h[0][1], 0.0};
    j.hess[0][1] = {f[0].h[1][0], f[0].h[1][1], 0.0};
    j.f[1] = x.z;
    j.grad[1] = {0.0, 0.0, 1.0};
  } else {
    const double xyz[3] = {x.x, x.y, x.z};
    formula::Jet2<3> f[2];
    program_.jets2<3>(xyz, f);
    for (int i = 0; i < 2; ++i) {
      j.f[i] = f[i].v;
      j.grad[i] = {f[i].g[0], f[i].g[1], f[i].g[2]};
      for (int r = 0; r < 3; ++r) j.hess[i][r] = {f[i].h[r][0], f[i].h[r][1], f[i].h[r][2]};
    }
  }
  return j;
}

bool ImplicitEquations::may_vanish(const Box3& cell) const {
  formula::Interval in[3], out[2];
  for (int k = 0; k < 3; ++k) in[k] = {cell.lo[k], cell.hi[k]};
  program_.intervals(in, out);
  if (out[0].excludes_zero()) return false;
  if (planar_) return !(cell.lo.z > 0.0 || cell.hi.z < 0.0);
  return !out[1].excludes_zero();
}

}  // namespace footpoint
