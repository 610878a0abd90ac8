// Shared by the tests of the papers' surface methods in this folder: a jet worked out by hand and a
// surface whose foot points are known in closed form.
#pragma once
#include "formula/program.hpp"
#include "parametric/geometry/parametric_surface.hpp"

namespace footpoint::test {

// The jet of the paraboloid (u, v, (u^2 + v^2)/2) at (1, 0): s = (1, 0, 1/2), s_u = (1, 0, 1),
// s_v = (0, 1, 0), s_uu = s_vv = (0, 0, 1), s_uv = 0.
inline SurfaceJet paraboloid_jet_at_1_0() {
  SurfaceJet j;
  j.s = {1, 0, 0.5};
  j.su = {1, 0, 1};
  j.sv = {0, 1, 0};
  j.suu = {0, 0, 1};
  j.suv = {0, 0, 0};
  j.svv = {0, 0, 1};
  return j;
}

// The unit sphere (cos u cos v, sin u cos v, sin v): the foot point of p != 0 is p / |p|, at
// u = atan2(p_y, p_x), v = asin(p_z / |p|).
inline SurfaceFormulas unit_sphere_formulas() {
  return SurfaceFormulas(formula::Program::compile(
      {{"x", "cos(u)*cos(v)"}, {"y", "sin(u)*cos(v)"}, {"z", "sin(v)"}}, {"u", "v"}, {}));
}

}  // namespace footpoint::test
