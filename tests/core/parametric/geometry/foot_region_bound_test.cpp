// The foot region bound (parametric/geometry/foot_region_bound.hpp) against dense sampling: over
// boxes about a foot point z of p (p = s(z) + d n(z), so that z is stationary), about z on an
// edge of the box, and about points z that are not stationary at all, the bound never exceeds
// the least sampled value of f (the true minimum lies below that); where the box is small
// against the surface's bending it is f(z) to rounding (the box is closed from z).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>

#include "parametric/geometry/foot_region_bound.hpp"
#include "parametric/geometry/parametric_curve.hpp"
#include "parametric/geometry/parametric_surface.hpp"

using namespace footpoint;

namespace {

struct FootCase {
  const char *x, *y, *z;
  double lo, hi;
};

const FootCase kFootSurfaces[] = {
    {"u+v", "sin(u)+2*cos(v)", "sin(u+v)", -3, 3},
    {"u^4*v^3+u*v+u", "u^3+v^3", "u+v", -2, 2},
    {"(3+cos(v))*cos(u)", "(3+cos(v))*sin(u)", "sin(v)", 0, 6.283185307179586},
    {"2*sin(v)*cos(u)", "2*sin(v)*sin(u)", "2*cos(v)", 0.3, 2.8},
    {"u", "3*v", "exp(-4*(u-0.3)^2)*cos(3*v)", -1, 1},
};

// The least of f = ½|s - p|² over a grid of the box.
double sampled_f_minimum(const SurfaceFormulas& s, const Vec3& p, const std::array<double, 2>& lo,
                         const std::array<double, 2>& hi) {
  constexpr int K = 48;
  double fmin = INFINITY;
  for (int i = 0; i <= K; ++i)
    for (int j = 0; j <= K; ++j) {
      const double u = lo[0] + (hi[0] - lo[0]) * i / K, v = lo[1] + (hi[1] - lo[1]) * j / K;
      fmin = std::min(fmin, 0.5 * norm2(s.point(u, v) - p));
    }
  return fmin;
}

}  // namespace

TEST_CASE("the foot region bound holds against dense sampling and closes small boxes about a foot") {
  std::mt19937_64 rng(11);
  int finite = 0, closed = 0, trials = 0;
  for (const FootCase& c : kFootSurfaces) {
    INFO(c.x << ", " << c.y << ", " << c.z);
    const SurfaceFormulas s(formula::Program::compile({{"x", c.x}, {"y", c.y}, {"z", c.z}}, {"u", "v"}, {}));
    std::uniform_real_distribution<double> unit(0.0, 1.0), sym(-1.0, 1.0);
    for (int trial = 0; trial < 240; ++trial) {
      const double span = c.hi - c.lo;
      const std::array<double, 2> z{c.lo + span * (0.1 + 0.8 * unit(rng)),
                                    c.lo + span * (0.1 + 0.8 * unit(rng))};
      const SurfaceJet j = s.jet(z[0], z[1]);
      const Vec3 n = cross(j.su, j.sv) / norm(cross(j.su, j.sv));
      const int kind = trial % 3;  // 0: a foot, 1: a foot on the box's edge, 2: any point
      const double d = 0.5 * std::pow(10.0, -3.0 * unit(rng)) * sym(rng);
      const Vec3 p = kind < 2 ? j.s + n * d : j.s + Vec3{sym(rng), sym(rng), sym(rng)} * 0.3;
      const double w = span * std::pow(10.0, -3.5 * unit(rng));  // box widths 3e-4 .. 1 of the domain
      std::array<double, 2> lo{z[0] - w * unit(rng), z[1] - w * unit(rng)};
      std::array<double, 2> hi{lo[0] + w, lo[1] + w};
      if (kind == 1) {  // z on the low u edge
        lo[0] = z[0];
        hi[0] = z[0] + w;
      }
      const BoxEnclosure<2> box = enclose_box<2>(s.program(), lo, hi);
      REQUIRE(box.bounded);
      const PointEnclosure<2> at = enclose_point<2>(s.program(), z);
      REQUIRE(at.valid);
      const GradientEnclosure<2> g = enclose_gradient(at, p);
      const double bound = foot_region_lower_bound<2>(at, g, z, box, lo, hi, p);
      const double fmin = sampled_f_minimum(s, p, lo, hi);
      CHECK(bound <= fmin);
      ++trials;
      if (std::isfinite(bound)) ++finite;
      const double fz = 0.5 * norm2(j.s - p);
      if (kind < 2 && bound >= fz - 1e-12 * (1.0 + fz)) ++closed;
    }
  }
  MESSAGE("boxes with a bound: " << finite << " of " << trials << ", closed from a foot: " << closed);
  CHECK(trials == 5 * 240);
  CHECK(closed > 300);
}

TEST_CASE("the foot region bound gives nothing where the foot is not alone") {
  // p at the centre of a sphere: every point is a foot, f is constant; no box about one of them
  // may be closed by more than rounding below that constant (the bound is -inf or below f(z))
  const SurfaceFormulas s(formula::Program::compile(
      {{"x", "sin(v)*cos(u)"}, {"y", "sin(v)*sin(u)"}, {"z", "cos(v)"}}, {"u", "v"}, {}));
  const std::array<double, 2> z{1.0, 1.2};
  const Vec3 p{0.0, 0.0, 0.0};
  for (double w : {1e-6, 1e-3, 0.1}) {
    const std::array<double, 2> lo{z[0] - w, z[1] - w}, hi{z[0] + w, z[1] + w};
    const PointEnclosure<2> at = enclose_point<2>(s.program(), z);
    const double bound = foot_region_lower_bound<2>(at, enclose_gradient(at, p), z,
                                                    enclose_box<2>(s.program(), lo, hi), lo, hi, p);
    CHECK(bound <= 0.5);
  }
  // beyond the focal distance (p on the concave side, farther than the radius): z is a maximum
  // of the distance along the sphere, never a minimum, and no box about it closes
  const Vec3 beyond = s.point(z[0], z[1]) * -0.5;  // 1.5 from the surface, through the centre
  const std::array<double, 2> lo{z[0] - 1e-4, z[1] - 1e-4}, hi{z[0] + 1e-4, z[1] + 1e-4};
  const PointEnclosure<2> at = enclose_point<2>(s.program(), z);
  CHECK(foot_region_lower_bound<2>(at, enclose_gradient(at, beyond), z, enclose_box<2>(s.program(), lo, hi),
                                   lo, hi, beyond) == -INFINITY);
}

TEST_CASE("the foot region bound over curve intervals") {
  std::mt19937_64 rng(13);
  const char* curves[][3] = {{"cos(t)", "sin(t)", "t/4"}, {"t^2", "t^3", "t"}, {"sin(3*t)", "cos(5*t)", "t"}};
  int closed = 0;
  for (const auto& c : curves) {
    const CurveFormulas curve(formula::Program::compile({{"x", c[0]}, {"y", c[1]}, {"z", c[2]}}, {"t"}, {}));
    std::uniform_real_distribution<double> T(-2.0, 2.0), unit(0.0, 1.0), sym(-1.0, 1.0);
    for (int trial = 0; trial < 200; ++trial) {
      const std::array<double, 1> z{T(rng)};
      const CurveJet j = curve.jet(z[0]);
      // a normal to the curve at z: the tangent's component-wise orthogonal complement
      Vec3 n = cross(j.d1, Vec3{0.3, -0.7, 0.6});
      n = n / norm(n);
      const Vec3 p = j.c + n * (0.3 * std::pow(10.0, -3.0 * unit(rng)) * sym(rng));
      const double w = 2.0 * std::pow(10.0, -3.0 * unit(rng));
      const std::array<double, 1> lo{z[0] - w * unit(rng)}, hi{lo[0] + w};
      const PointEnclosure<1> at = enclose_point<1>(curve.program(), z);
      const double bound = foot_region_lower_bound<1>(at, enclose_gradient(at, p), z,
                                                      enclose_box<1>(curve.program(), lo, hi), lo, hi, p);
      double fmin = INFINITY;
      for (int i = 0; i <= 400; ++i) fmin = std::min(fmin, 0.5 * norm2(curve.point(lo[0] + w * i / 400) - p));
      CHECK(bound <= fmin);
      const double fz = 0.5 * norm2(j.c - p);
      if (bound >= fz - 1e-12 * (1.0 + fz)) ++closed;
    }
  }
  MESSAGE("curve intervals closed from a foot: " << closed << " of 600");
  CHECK(closed > 150);
}

TEST_CASE("the foot region bound over cell-sized boxes where the parametrisation is anisotropic") {
  // Boxes of 2-8 % of the domain about feet where J = [s_u s_v] is far from isometric (the
  // degree-6 polynomial surface of the Open CASCADE comparison, S3, and a sheared paraboloid
  // whose s_u and s_v are 17 degrees apart): the bound pairs each direction's bending with that
  // direction's own reach (foot_region_bound.hpp), so it closes most such boxes from the foot,
  // and never lies above the sampled minimum of f.
  const FootCase anisotropic[] = {
      {"u^6+u^5*v+v^6-u^2*v^3+u*v^4-v^5+u^4+u^3*v+v^4+u^3-u*v^2+v^3+u*v+v^2+1",
       "u^6+2*u^4*v^2-v^6+u^5+u^2*v^3+v^5+u^4-u*v^3+u^3-2*u*v^2+v^3+4*u*v+2*v^2+2*u+2*v+1",
       "u^6+u*v^5+u^4*v+u^2*v^3+u^3*v+2*u^2*v^2+v^4+u^3+2*u*v+u", 0, 2},
      {"u+0.95*v", "0.3*v", "0.5*(u+0.95*v)^2+0.4*v^2", -1, 1},
  };
  std::mt19937_64 rng(5);
  int trials = 0, closed = 0;
  for (const FootCase& c : anisotropic) {
    INFO(c.x << ", " << c.y << ", " << c.z);
    const SurfaceFormulas s(formula::Program::compile({{"x", c.x}, {"y", c.y}, {"z", c.z}}, {"u", "v"}, {}));
    std::uniform_real_distribution<double> unit(0.0, 1.0), sym(-1.0, 1.0);
    for (int trial = 0; trial < 150; ++trial) {
      const double span = c.hi - c.lo;
      const std::array<double, 2> z{c.lo + span * (0.1 + 0.8 * unit(rng)),
                                    c.lo + span * (0.1 + 0.8 * unit(rng))};
      const SurfaceJet j = s.jet(z[0], z[1]);
      const Vec3 n = cross(j.su, j.sv) / norm(cross(j.su, j.sv));
      const Vec3 p = j.s + n * (1e-3 * norm(j.s) * sym(rng));
      const double w = span * (0.02 + 0.06 * unit(rng));
      const std::array<double, 2> lo{z[0] - w * unit(rng), z[1] - w * unit(rng)};
      const std::array<double, 2> hi{lo[0] + w, lo[1] + w};
      const PointEnclosure<2> at = enclose_point<2>(s.program(), z);
      REQUIRE(at.valid);
      const double bound = foot_region_lower_bound<2>(at, enclose_gradient(at, p), z,
                                                      enclose_box<2>(s.program(), lo, hi), lo, hi, p);
      CHECK(bound <= sampled_f_minimum(s, p, lo, hi));
      const double fz = 0.5 * norm2(j.s - p);
      if (bound >= fz - 1e-12 * (1.0 + fz)) ++closed;
      ++trials;
    }
  }
  MESSAGE("cell-sized boxes closed from the foot: " << closed << " of " << trials);
  CHECK(closed >= 250);  // the bound with a² + λ alone (one M, one λ for the box) closes 185
}
