#include "implicit/geometry/implicit_surface.hpp"

namespace footpoint {

double ImplicitSurfaceEquation::value(Vec3 x) const {
  const double xyz[3] = {x.x, x.y, x.z};
  double f = 0.0;
  program_.values(xyz, &f);
  return f;
}

ImplicitSurfaceJet ImplicitSurfaceEquation::jet(Vec3 x) const {
  const double xyz[3] = {x.x, x.y, x.z};
  formula::Jet2<3> f[1];
  program_.jets2<3>(xyz, f);
  ImplicitSurfaceJet j;
  j.f = f[0].v;
  j.grad = {f[0].g[0], f[0].g[1], f[0].g[2]};
  for (int r = 0; r < 3; ++r) j.hess[r] = {f[0].h[r][0], f[0].h[r][1], f[0].h[r][2]};
  return j;
}

Interval ImplicitSurfaceEquation::value_enclosure(const Box3& box) const {
  const IVec3 in = ivec::of_box(box);
  Interval out;
  program_.intervals(in.data(), &out);
  return out;
}

ImplicitSurfaceIntervalJet ImplicitSurfaceEquation::interval_gradient(const Box3& box) const {
  const IVec3 in = ivec::of_box(box);
  formula::IntervalJet1<3> f[1];
  program_.interval_jets1<3>(in.data(), f);
  ImplicitSurfaceIntervalJet j;
  j.f = f[0].v;
  for (int r = 0; r < 3; ++r) {
    j.grad[r] = f[0].g[r];
    for (int c = 0; c < 3; ++c) j.hess[r][c] = formula::interval::entire();
  }
  j.lipschitz = f[0].lipschitz && !f[0].v.partial;
  j.smooth = false;  // no Hessian enclosure here
  return j;
}

ImplicitSurfaceIntervalJet ImplicitSurfaceEquation::interval_jet(const Box3& box) const {
  const IVec3 in = ivec::of_box(box);
  formula::IntervalJet2<3> f[1];
  program_.interval_jets2<3>(in.data(), f);
  ImplicitSurfaceIntervalJet j;
  j.f = f[0].v;
  for (int r = 0; r < 3; ++r) {
    j.grad[r] = f[0].g[r];
    for (int c = 0; c < 3; ++c) j.hess[r][c] = f[0].h[r][c];
  }
  j.lipschitz = f[0].lipschitz && !f[0].v.partial;
  j.smooth = f[0].smooth && !f[0].v.partial;
  return j;
}

}  // namespace footpoint
