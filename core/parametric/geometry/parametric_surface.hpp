// s(u,v) = (x(u,v), y(u,v), z(u,v)) and its exact partial derivatives from the formula tape.
#pragma once
#include "formula/program.hpp"
#include "geometry/vec.hpp"
#include "parametric/geometry/params.hpp"

namespace footpoint {

struct SurfaceJet {
  Vec3 s, su, sv, suu, suv, svv;
};
// All 18 entries finite: as is_finite(Vec3), a sum of 0 x is 0 exactly when they are.
inline bool is_finite(const SurfaceJet& j) {
  const Vec3 zero = 0.0 * j.s + 0.0 * j.su + 0.0 * j.sv + 0.0 * j.suu + 0.0 * j.suv + 0.0 * j.svv;
  return (zero.x + zero.y) + zero.z == 0.0;
}
// s(t + δ) to second order: s + s_u δu + s_v δv + ½ (s_uu δu^2 + 2 s_uv δu δv + s_vv δv^2) (the
// quadratic model of a cell, a Newton model's foot point).
inline Vec3 taylor_point(const SurfaceJet& j, double du, double dv) {
  return j.s + j.su * du + j.sv * dv +
         0.5 * (j.suu * (du * du) + 2.0 * j.suv * (du * dv) + j.svv * (dv * dv));
}
struct SurfaceJet3 : SurfaceJet {
  Vec3 suuu, suuv, suvv, svvv;
};

struct ParamBox {
  double umin, umax, vmin, vmax;
  bool contains(double u, double v) const { return u >= umin && u <= umax && v >= vmin && v <= vmax; }
};

class SurfaceFormulas {
 public:
  explicit SurfaceFormulas(formula::Program program) : program_(std::move(program)) {}
  Vec3 point(double u, double v) const {
    const Params<2> x{u, v};
    double out[3];
    program_.values(x.data(), out);
    return {out[0], out[1], out[2]};
  }
  SurfaceJet jet(double u, double v) const {
    const Params<2> x{u, v};
    formula::Jet2<2> j[3];
    program_.jets2<2>(x.data(), j);
    SurfaceJet r;
    r.s = {j[0].v, j[1].v, j[2].v};
    r.su = {j[0].g[0], j[1].g[0], j[2].g[0]};
    r.sv = {j[0].g[1], j[1].g[1], j[2].g[1]};
    r.suu = {j[0].h[0][0], j[1].h[0][0], j[2].h[0][0]};
    r.suv = {j[0].h[0][1], j[1].h[0][1], j[2].h[0][1]};
    r.svv = {j[0].h[1][1], j[1].h[1][1], j[2].h[1][1]};
    return r;
  }
  SurfaceJet3 jet3(double u, double v) const {
    const Params<2> x{u, v};
    formula::Jet3<2> j[3];
    program_.jets3<2>(x.data(), j);
    SurfaceJet3 r;
    auto pick = [&](auto f) { return Vec3{f(j[0]), f(j[1]), f(j[2])}; };
    r.s = pick([](auto& a) { return a.v; });
    r.su = pick([](auto& a) { return a.g[0]; });
    r.sv = pick([](auto& a) { return a.g[1]; });
    r.suu = pick([](auto& a) { return a.h[0][0]; });
    r.suv = pick([](auto& a) { return a.h[0][1]; });
    r.svv = pick([](auto& a) { return a.h[1][1]; });
    r.suuu = pick([](auto& a) { return a.t[0][0][0]; });
    r.suuv = pick([](auto& a) { return a.t[0][0][1]; });
    r.suvv = pick([](auto& a) { return a.t[0][1][1]; });
    r.svvv = pick([](auto& a) { return a.t[1][1][1]; });
    return r;
  }
  const formula::Program& program() const { return program_; }

 private:
  formula::Program program_;
};

}  // namespace footpoint
