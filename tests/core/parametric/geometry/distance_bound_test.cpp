// The distance bounds (parametric/geometry/distance_bound.hpp) over parameter boxes of surfaces and curves,
// against dense sampling of the same boxes: every lower bound is at most the least sampled value
// (the true minimum lies between the two); the Hessian bound is at most the smallest eigenvalue
// of the point Hessian anywhere sampled; and the bound from the minimiser itself, where the box
// is convex for f, is the minimum to a few ulps (the certificate of a foot point).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>

#include "parametric/geometry/distance_bound.hpp"
#include "parametric/geometry/parametric_curve.hpp"
#include "parametric/geometry/parametric_surface.hpp"

using namespace footpoint;

namespace {

struct SurfaceCase {
  const char *x, *y, *z;
  double lo, hi;
};

const SurfaceCase kSurfaces[] = {
    {"u+v", "sin(u)+2*cos(v)", "sin(u+v)", -3, 3},
    {"u^4*v^3+u*v+u", "u^3+v^3", "u+v", -2, 2},
    {"(3+cos(v))*cos(u)", "(3+cos(v))*sin(u)", "sin(v)", 0, 6.283185307179586},
    {"u", "v", "exp(-40*(u-0.3)^2)*cos(3*v)", -1, 1},
};

double f_at(const SurfaceFormulas& s, const Vec3& p, double u, double v) {
  return 0.5 * norm2(s.point(u, v) - p);
}

// the smaller eigenvalue of the Hessian of f at (u, v)
double lambda_at(const SurfaceFormulas& s, const Vec3& p, double u, double v) {
  const SurfaceJet j = s.jet(u, v);
  const Vec3 r = j.s - p;
  const double a = dot(j.su, j.su) + dot(r, j.suu), b = dot(j.su, j.sv) + dot(r, j.suv),
               c = dot(j.sv, j.sv) + dot(r, j.svv);
  return 0.5 * (a + c) - std::sqrt(0.25 * (a - c) * (a - c) + b * b);
}

}  // namespace

TEST_CASE("distance bounds over surface boxes hold against dense sampling") {
  std::mt19937_64 rng(3);
  int checked = 0, tight = 0;
  for (const SurfaceCase& c : kSurfaces) {
    INFO(std::string(c.z));
    const SurfaceFormulas s(formula::Program::compile({{"x", c.x}, {"y", c.y}, {"z", c.z}}, {"u", "v"}, {}));
    std::uniform_real_distribution<double> U(c.lo, c.hi), unit(0.0, 1.0), P(-4.0, 4.0);
    for (int trial = 0; trial < 200; ++trial) {
      const double w = (c.hi - c.lo) * std::pow(10.0, -3.0 * unit(rng));  // widths 1e-3 .. 1 of the domain
      const double u0 = std::min(U(rng), c.hi - w), v0 = std::min(U(rng), c.hi - w);
      const std::array<double, 2> lo{u0, v0}, hi{u0 + w * unit(rng), v0 + w * unit(rng)};
      // points near the box's image and far from it
      const Vec3 on = s.point(0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]));
      const Vec3 p = trial % 2 ? on + Vec3{P(rng), P(rng), P(rng)} * 0.05 : Vec3{P(rng), P(rng), P(rng)};
      const BoxEnclosure<2> box = enclose_box<2>(s.program(), lo, hi);
      REQUIRE(box.bounded);
      constexpr int K = 40;
      double fmin = INFINITY, lmin = INFINITY;
      std::array<double, 2> argmin{};
      for (int i = 0; i <= K; ++i)
        for (int j = 0; j <= K; ++j) {
          const double u = lo[0] + (hi[0] - lo[0]) * i / K, v = lo[1] + (hi[1] - lo[1]) * j / K;
          const double f = f_at(s, p, u, v);
          if (f < fmin) fmin = f, argmin = {u, v};
          lmin = std::min(lmin, lambda_at(s, p, u, v));
        }
      CHECK(box_distance2_lower(box.s_mid, box.s_rad, p) <= 2.0 * fmin);
      const HessianBounds<2> hessian = hessian_bounds(box, p);
      const double lambda = hessian.smallest_eigenvalue();
      CHECK(lambda <= lmin);
      // from the centre, from a random point, from the sampled minimiser
      for (const std::array<double, 2>& q :
           {std::array<double, 2>{0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1])},
            std::array<double, 2>{lo[0] + (hi[0] - lo[0]) * unit(rng), lo[1] + (hi[1] - lo[1]) * unit(rng)},
            argmin}) {
        const PointEnclosure<2> at = enclose_point<2>(s.program(), q);
        REQUIRE(at.valid);
        const double bound = second_order_lower_bound(enclose_gradient(at, p), q, lo, hi, hessian);
        CHECK(bound <= fmin);
        ++checked;
      }
      if (lambda > 0.0) {
        // polish the minimiser by projected Newton on the box, then the bound from it is the minimum
        std::array<double, 2> t = argmin;
        for (int it = 0; it < 30; ++it) {
          const SurfaceJet j = s.jet(t[0], t[1]);
          const Vec3 r = j.s - p;
          const double g0 = dot(r, j.su), g1 = dot(r, j.sv);
          const double a = dot(j.su, j.su) + dot(r, j.suu), b = dot(j.su, j.sv) + dot(r, j.suv),
                       cc = dot(j.sv, j.sv) + dot(r, j.svv), det = a * cc - b * b;
          t = {std::clamp(t[0] - (cc * g0 - b * g1) / det, lo[0], hi[0]),
               std::clamp(t[1] - (a * g1 - b * g0) / det, lo[1], hi[1])};
        }
        const PointEnclosure<2> at = enclose_point<2>(s.program(), t);
        const double f_t = f_at(s, p, t[0], t[1]);
        const double bound = second_order_lower_bound(enclose_gradient(at, p), t, lo, hi, hessian);
        CHECK(bound <= fmin);
        // interior minima: the gradient vanishes to rounding; edge ones: it points out of the box
        if (f_t > 1e-6 && bound >= f_t * (1.0 - 1e-10)) ++tight;
      }
    }
  }
  CHECK(checked == 4 * 200 * 3);
  MESSAGE("boxes convex for f whose bound from the polished minimiser is within 1e-10: " << tight);
  CHECK(tight > 100);
}

TEST_CASE("distance bounds over curve intervals hold against dense sampling") {
  std::mt19937_64 rng(5);
  const char* curves[][3] = {{"cos(t)", "sin(t)", "t/4"}, {"t^2", "t^3", "0"}, {"sin(3*t)", "cos(5*t)", "t"}};
  for (const auto& c : curves) {
    const CurveFormulas curve(formula::Program::compile({{"x", c[0]}, {"y", c[1]}, {"z", c[2]}}, {"t"}, {}));
    std::uniform_real_distribution<double> T(-2.0, 2.0), unit(0.0, 1.0), P(-3.0, 3.0);
    for (int trial = 0; trial < 300; ++trial) {
      const double w = 2.0 * std::pow(10.0, -3.0 * unit(rng));
      const double t0 = T(rng);
      const std::array<double, 1> lo{t0}, hi{t0 + w};
      const Vec3 p{P(rng), P(rng), P(rng)};
      const BoxEnclosure<1> box = enclose_box<1>(curve.program(), lo, hi);
      double fmin = INFINITY;
      for (int i = 0; i <= 400; ++i) fmin = std::min(fmin, 0.5 * norm2(curve.point(t0 + w * i / 400) - p));
      CHECK(box_distance2_lower(box.s_mid, box.s_rad, p) <= 2.0 * fmin);
      const HessianBounds<1> hessian = hessian_bounds(box, p);
      const std::array<double, 1> q{t0 + w * unit(rng)};
      const double bound = second_order_lower_bound(enclose_gradient(enclose_point<1>(curve.program(), q), p),
                                                    q, lo, hi, hessian);
      CHECK(bound <= fmin);
    }
  }
}

TEST_CASE("the gradient's signs over surface boxes hold against dense sampling") {
  // where gradient_signs claims ∂_i f > 0 (< 0) over a box, every sampled ∂_i f is; and the claim
  // is made on most boxes far from the foot, where the gradient is large against its spread
  std::mt19937_64 rng(7);
  int claims = 0, boxes = 0;
  for (const SurfaceCase& c : kSurfaces) {
    INFO(std::string(c.z));
    const SurfaceFormulas s(formula::Program::compile({{"x", c.x}, {"y", c.y}, {"z", c.z}}, {"u", "v"}, {}));
    std::uniform_real_distribution<double> U(c.lo, c.hi), unit(0.0, 1.0), P(-4.0, 4.0);
    for (int trial = 0; trial < 300; ++trial) {
      const double w = (c.hi - c.lo) * std::pow(10.0, -3.0 * unit(rng));
      const double u0 = std::min(U(rng), c.hi - w), v0 = std::min(U(rng), c.hi - w);
      const std::array<double, 2> lo{u0, v0}, hi{u0 + w, v0 + w};
      const Vec3 p{P(rng), P(rng), P(rng)};
      const PointEnclosure<2> centre = enclose_point<2>(s.program(), {u0 + 0.5 * w, v0 + 0.5 * w});
      const std::array<int, 2> signs = gradient_signs<2>(enclose_box<2>(s.program(), lo, hi), centre, p);
      ++boxes;
      for (int i = 0; i < 2; ++i) {
        if (signs[static_cast<std::size_t>(i)] == 0) continue;
        ++claims;
        constexpr int K = 24;
        for (int a = 0; a <= K; ++a)
          for (int b = 0; b <= K; ++b) {
            const SurfaceJet j = s.jet(lo[0] + w * a / K, lo[1] + w * b / K);
            const double g = dot(i == 0 ? j.su : j.sv, j.s - p);
            CHECK(g * signs[static_cast<std::size_t>(i)] > 0.0);
          }
      }
    }
  }
  MESSAGE("signs claimed: " << claims << " over " << boxes << " boxes");
  CHECK(claims > boxes / 2);
}
