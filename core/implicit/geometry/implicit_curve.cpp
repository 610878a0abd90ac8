#include "implicit/geometry/implicit_curve.hpp"

#include <tuple>

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

std::array<Interval, 2> ImplicitEquations::value_enclosure(const Box3& box) const {
  formula::Interval in[3];
  std::array<Interval, 2> out{};
  for (int k = 0; k < 3; ++k) in[k] = {box.lo[k], box.hi[k]};
  program_.intervals(in, out.data());
  if (planar_) out[1] = {box.lo.z, box.hi.z};
  return out;
}

bool ImplicitEquations::may_vanish(const Box3& cell) const {
  const std::array<Interval, 2> f = value_enclosure(cell);
  return !f[0].excludes_zero() && !f[1].excludes_zero();
}

namespace {

// Copies formula i's enclosures (n variables) into j; without Hessians (IntervalJet1) they are
// left holding the whole line.
template <class Jet>
void copy_jet(ImplicitIntervalJet& j, int i, const Jet& f, int n) {
  j.f[i] = f.v;
  for (int r = 0; r < n; ++r) {
    j.grad[i][r] = f.g[r];
    for (int c = 0; c < 3; ++c) {
      if constexpr (requires { f.h; })
        j.hess[i][r][c] = c < n ? f.h[r][c] : Interval{0.0, 0.0};
      else
        j.hess[i][r][c] = formula::interval::entire();
    }
  }
  j.lipschitz = j.lipschitz && f.lipschitz && !f.v.partial;
  j.smooth = j.smooth && f.smooth && !f.v.partial;
}

// The interval [m - r, m + r] of a ball, one rounding of each end covered by one step outwards.
Interval of_ball(const formula::Ball& b) { return formula::interval::outward(b.mid - b.rad, b.mid + b.rad); }

// Copies formula i's ball jet (n variables) into j, as copy_jet.
template <int N>
void copy_jet(ImplicitIntervalJet& j, int i, const formula::BallJet1<N>& f, int n) {
  j.f[i] = of_ball(f.v);
  for (int r = 0; r < n; ++r) {
    j.grad[i][r] = of_ball(f.g[r]);
    for (int c = 0; c < 3; ++c) j.hess[i][r][c] = formula::interval::entire();
  }
  j.lipschitz = j.lipschitz && f.defined;
  j.smooth = j.smooth && f.defined && f.differentiable;
}

// The enclosures from jets evaluated at the inputs (x, y, z): interval jets over a box, or ball
// jets at a point; planar curves' f2 = z, with z's own enclosure.
template <template <int> class Jet, class Input, class Evaluate>
ImplicitIntervalJet enclose(const std::array<Input, 3>& in, Interval z, bool planar, Evaluate&& evaluate) {
  ImplicitIntervalJet j;
  if (planar) {
    Jet<2> f[1];
    evaluate(in.data(), f);
    copy_jet(j, 0, f[0], 2);
    j.f[1] = z;
    j.grad[1][2] = {1.0, 1.0};
  } else {
    Jet<3> f[2];
    evaluate(in.data(), f);
    copy_jet(j, 0, f[0], 3);
    copy_jet(j, 1, f[1], 3);
  }
  j.smooth = j.smooth && j.lipschitz;
  return j;
}

std::array<Interval, 3> inputs(const Box3& box) {
  return {{{box.lo.x, box.hi.x}, {box.lo.y, box.hi.y}, {box.lo.z, box.hi.z}}};
}

}  // namespace

ImplicitIntervalJet ImplicitEquations::point_gradient(Vec3 x) const {
  return enclose<formula::BallJet1>(
      std::array<double, 3>{x.x, x.y, x.z}, {x.z, x.z}, planar_,
      [&](const double* in, auto* f) { program_.ball_jets1<std::tuple_size_v<decltype(f->g)>>(in, f); });
}

bool ImplicitEquations::accurate_values(Vec3 x, std::array<Interval, 2>& f) const {
  const double xyz[3] = {x.x, x.y, x.z};
  formula::Ball b[2];
  if (!program_.accurate_values(xyz, b)) return false;
  f[0] = of_ball(b[0]);
  f[1] = planar_ ? Interval{x.z, x.z} : of_ball(b[1]);
  return true;
}

ImplicitIntervalJet ImplicitEquations::interval_jet(const Box3& box) const {
  return enclose<formula::IntervalJet2>(inputs(box), {box.lo.z, box.hi.z}, planar_,
                                        [&](const formula::Interval* in, auto* f) {
                                          program_.interval_jets2<std::tuple_size_v<decltype(f->g)>>(in, f);
                                        });
}

ImplicitIntervalJet ImplicitEquations::interval_gradient(const Box3& box) const {
  return enclose<formula::IntervalJet1>(inputs(box), {box.lo.z, box.hi.z}, planar_,
                                        [&](const formula::Interval* in, auto* f) {
                                          program_.interval_jets1<std::tuple_size_v<decltype(f->g)>>(in, f);
                                        });
}

}  // namespace footpoint
