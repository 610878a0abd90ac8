// parametric/solvers/projection_arc_search: Armijo's backtracking along the projection arc
// t(α) = clamp(t + α d) (Bertsekas 1982). The header's contract, checked against brute force on
// the arc: f = ½|s - p|^2 evaluated at t(α) for α = 1, ½, ¼, ... in long double, the answer being
// the first α with f(t(α)) - f(t) <= 1e-4 <g, t(α) - t> (every α of a case is decided by more than
// rounding: the test requires a margin), or for a convex model the first whose step is within
// 1e-6 x step_scale in each parameter; no step at all when the full step moves no parameter.
// Cases worked out by hand alongside: a plane's Newton step is taken whole; a step onto the box's
// edge is taken clamped; an overshoot on a paraboloid backs off twice; an ascent is refused (or,
// for a convex model, taken once tiny); a step into where the formulas are undefined backs off
// to where they are; a point 1e9 away, where f's rounding is far above the decrease, still
// sees it.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "parametric/solvers/projection_arc_search.hpp"

using namespace footpoint;

namespace projection_arc_search_test {

SurfaceFormulas arc_surface(const std::string& x, const std::string& y, const std::string& z) {
  return SurfaceFormulas(formula::Program::compile({{"x", x}, {"y", y}, {"z", z}}, {"u", "v"}, {}));
}

struct Arc {
  const SurfaceFormulas& f;
  Vec3 p;
  Params<2> t, d, lo, hi;
  bool convex = false;
  double scale = 1.0;

  // g = ∇f(t) = (<s - p, s_u>, <s - p, s_v>)
  void gradient(double (&g)[2]) const {
    const SurfaceJet j = f.jet(t[0], t[1]);
    g[0] = dot(j.s - p, j.su);
    g[1] = dot(j.s - p, j.sv);
  }
  long double half_square(const Params<2>& at) const {
    const Vec3 s = f.point(at[0], at[1]);
    long double sum = 0.0L;
    for (int k = 0; k < 3; ++k)
      sum += (static_cast<long double>(s[k]) - p[k]) * (static_cast<long double>(s[k]) - p[k]);
    return 0.5L * sum;
  }
  // The brute force: the first α = 2^-k that the contract accepts, k < 60.
  surface::ArcStep expected() const {
    double g[2];
    gradient(g);
    surface::ArcStep e;
    const long double f0 = half_square(t);
    for (int k = 0; k < 60; ++k) {
      const double alpha = std::ldexp(1.0, -k);
      const Params<2> tn{std::clamp(t[0] + alpha * d[0], lo[0], hi[0]),
                         std::clamp(t[1] + alpha * d[1], lo[1], hi[1])};
      if (tn == t) {
        e.vanishes = k == 0;
        return e;
      }
      const double slope = g[0] * (tn[0] - t[0]) + g[1] * (tn[1] - t[1]);
      const long double df = half_square(tn) - f0;
      const long double armijo = 1e-4L * slope;
      const bool local = convex && std::max(std::abs(tn[0] - t[0]), std::abs(tn[1] - t[1])) <= 1e-6 * scale;
      const bool finite = std::isfinite(static_cast<double>(df));
      if (finite && !local) {
        // decided by more than rounding (1e-9 relative; long double carries 19 digits)
        REQUIRE(std::abs(df - armijo) > 1e-9L * (std::abs(df) + std::abs(armijo)));
      }
      if (finite && (local || df <= armijo) && is_finite(f.jet(tn[0], tn[1]))) {
        e.accepted = true;
        e.t = tn;
        return e;
      }
    }
    return e;
  }
  surface::ArcStep run() const {
    double g[2];
    gradient(g);
    return surface::search_projection_arc(f, p, f.jet(t[0], t[1]), t, d, lo, hi, g, convex, scale);
  }
};

// The search agrees with the brute force, and an accepted step comes with its jet.
surface::ArcStep check_arc(const Arc& arc) {
  const surface::ArcStep want = arc.expected();
  const surface::ArcStep got = arc.run();
  CHECK(got.accepted == want.accepted);
  CHECK(got.vanishes == want.vanishes);
  if (want.accepted) {
    CHECK(got.t == want.t);
    const SurfaceJet j = arc.f.jet(got.t[0], got.t[1]);
    CHECK(norm(got.jet.s - j.s) == 0.0);
    CHECK(norm(got.jet.su - j.su) == 0.0);
    CHECK(norm(got.jet.sv - j.sv) == 0.0);
  }
  return got;
}

TEST_CASE("projection_arc_search: a plane's Newton step is taken whole; a step out of the box, clamped") {
  const SurfaceFormulas plane = arc_surface("u", "v", "0");
  // f = ½((u - 0.3)^2 + (v - 0.2)^2 + 1): from (0.9, 0.9) the Newton step -g = (-0.6, -0.7) lands
  // on the minimiser
  const surface::ArcStep whole =
      check_arc({plane, {0.3, 0.2, 1.0}, {0.9, 0.9}, {-0.6, -0.7}, {0, 0}, {1, 1}});
  REQUIRE(whole.accepted);
  CHECK(whole.t[0] == doctest::Approx(0.3).epsilon(1e-15));
  CHECK(whole.t[1] == doctest::Approx(0.2).epsilon(1e-15));
  // p = (3, 0.5, 0) beyond u = 1: the step (2.5, 0) is clamped onto the edge u = 1, where
  // f - f(t) = ½(4 - 6.25) = -1.125 <= 1e-4 x (-2.5 x 0.5)
  const surface::ArcStep edge = check_arc({plane, {3.0, 0.5, 0.0}, {0.5, 0.5}, {2.5, 0.0}, {0, 0}, {1, 1}});
  REQUIRE(edge.accepted);
  CHECK(edge.t == Params<2>{1.0, 0.5});
}

TEST_CASE("projection_arc_search: an overshoot backs off to the first α with sufficient decrease") {
  // paraboloid s = (u, v, u^2 + v^2), p = (0, 0, -1), from (1, 1): g = (7, 7), f = 5.5. The step
  // -g is clamped to (-2, -2) for α = 1 and ½ (f = 44.5); α = ¼ gives (-0.75, -0.75), f = 2.82...
  const SurfaceFormulas bowl = arc_surface("u", "v", "u^2+v^2");
  const surface::ArcStep s = check_arc({bowl, {0.0, 0.0, -1.0}, {1.0, 1.0}, {-7.0, -7.0}, {-2, -2}, {2, 2}});
  REQUIRE(s.accepted);
  CHECK(s.t == Params<2>{-0.75, -0.75});
  // a milder overshoot from an asymmetric start, away from the box's edges
  check_arc({bowl, {0.3, -0.2, 0.5}, {1.2, 0.7}, {-3.1, -1.9}, {-5, -5}, {5, 5}});
}

TEST_CASE(
    "projection_arc_search: a step that moves nothing vanishes; an ascent is refused unless tiny and "
    "convex") {
  const SurfaceFormulas plane = arc_surface("u", "v", "0");
  // at the corner (1, 1) with d pointing out of the box in both parameters: nothing moves
  const surface::ArcStep stuck = check_arc({plane, {3.0, 3.0, 0.0}, {1.0, 1.0}, {1.0, 2.0}, {0, 0}, {1, 1}});
  CHECK(stuck.vanishes);
  CHECK_FALSE(stuck.accepted);
  // uphill: f grows along d = +g at every α; backtracking ends when t + α d rounds to t
  const SurfaceFormulas bowl = arc_surface("u", "v", "u^2+v^2");
  const surface::ArcStep up = check_arc({bowl, {0.0, 0.0, -1.0}, {0.5, 0.25}, {1.0, 0.5}, {-2, -2}, {2, 2}});
  CHECK_FALSE(up.accepted);
  CHECK_FALSE(up.vanishes);
  // a convex model's tiny step is taken as it is: the first α with α |d|max <= 1e-6 x step_scale,
  // 2^-20 for scale 1 (2^-20 = 9.5e-7), 2^-17 for scale 8 (7.6e-6)
  for (const auto& scale_and_power : {std::pair{1.0, 20}, std::pair{8.0, 17}}) {
    const double scale = scale_and_power.first;
    const int k = scale_and_power.second;
    CAPTURE(scale);
    const surface::ArcStep tiny =
        check_arc({bowl, {0.0, 0.0, -1.0}, {0.5, 0.25}, {1.0, 0.5}, {-2, -2}, {2, 2}, true, scale});
    REQUIRE(tiny.accepted);
    CHECK(tiny.t == Params<2>{0.5 + std::ldexp(1.0, -k), 0.25 + std::ldexp(0.5, -k)});
  }
}

TEST_CASE("projection_arc_search: a step into undefined formulas backs off to where they are defined") {
  // z = sqrt(1.2 - u) is undefined past u = 1.2; p = (3, 0.5, 0): f = ½((u - 3)^2 + 1.2 - u),
  // g = (-3, 0) at u = 0.5. Along d = (2, 0): u = 2.5 and 1.5 are undefined, u = 1 decreases f
  // from 3.475 to 2.1
  const SurfaceFormulas root = arc_surface("u", "v", "sqrt(1.2-u)");
  const surface::ArcStep s = check_arc({root, {3.0, 0.5, 0.0}, {0.5, 0.5}, {2.0, 0.0}, {0, 0}, {3, 1}});
  REQUIRE(s.accepted);
  CHECK(s.t == Params<2>{1.0, 0.5});
  CHECK(is_finite(s.jet));
}

TEST_CASE("projection_arc_search: the decrease is seen 1e9 away, where f's rounding (64) dwarfs it") {
  // plane, p = (0.3, 0.2, 1e9): f ~ 5e17, and the Newton step decreases it by ½(0.36 + 0.49) = 0.425
  // exactly: f(t') - f(t) as a difference of two doubles would be 0 or ±64
  const SurfaceFormulas plane = arc_surface("u", "v", "0");
  const Vec3 p{0.3, 0.2, 1e9};
  const Params<2> t{0.9, 0.9};
  const SurfaceJet j = plane.jet(t[0], t[1]);
  const double g[2] = {dot(j.s - p, j.su), dot(j.s - p, j.sv)};
  CHECK(g[0] == doctest::Approx(0.6));
  const surface::ArcStep s =
      surface::search_projection_arc(plane, p, j, t, {-g[0], -g[1]}, {0, 0}, {1, 1}, g, false, 1.0);
  REQUIRE(s.accepted);
  CHECK(s.t[0] == doctest::Approx(0.3).epsilon(1e-15));
  CHECK(s.t[1] == doctest::Approx(0.2).epsilon(1e-15));
}

}  // namespace projection_arc_search_test
