// implicit/geometry/singular_point: Newton on grad f1 = mu grad f2, f2 = 0 refines a start near a singular
// point onto it; the references are the known singular points of Viviani's curve, the lemniscate
// and the cusp.
#include <doctest/doctest.h>

#include <cmath>

#include "implicit/geometry/singular_point.hpp"
#include "implicit_fixtures.hpp"

using namespace footpoint;
using namespace footpoint::test;

TEST_CASE("refine_singular_point: Viviani's double point (2, 0, 0), quadratically") {
  const ImplicitEquations eq = spatial_equations("x^2+y^2+z^2-4", "(x-1)^2+y^2-1");
  Vec3 x{1.98, 0.015, -0.02};
  REQUIRE(curve::refine_singular_point(eq, x));
  CHECK(norm(x - Vec3{2, 0, 0}) <= 1e-14);
}

TEST_CASE("refine_singular_point: planar curves, grad f = 0 on the curve") {
  // The lemniscate (x^2 + y^2)^2 = 2 (x^2 - y^2) crosses itself at the origin.
  Vec3 x{0.03, -0.02, 0.0};
  REQUIRE(curve::refine_singular_point(planar_equations("(x^2+y^2)^2-2*(x^2-y^2)"), x));
  CHECK(norm(x) <= 1e-14);
  // The cusp y^2 = x^3 at the origin: a degenerate point, where Newton converges linearly.
  Vec3 c{0.01, 0.005, 0.0};
  REQUIRE(curve::refine_singular_point(planar_equations("y^2-x^3"), c));
  CHECK(norm(c) <= 1e-7);
}

TEST_CASE("refine_singular_point: a critical point of f off the curve is no singular point") {
  // grad f = 0 at the circle's centre, where f = -1: not on the curve.
  Vec3 x{0.1, 0.05, 0.0};
  CHECK(!curve::refine_singular_point(planar_equations("x^2+y^2-1"), x));
  // A regular curve has none: the circle {|X| = 2} ∩ {z = 1} from a point next to it.
  Vec3 y = circle_point(0.3) + Vec3{0.01, 0.0, 0.0};
  CHECK(!curve::refine_singular_point(circle(), y));
}

TEST_CASE("isolate_singular_point: Krawczyk isolates a node, not a cusp or a tacnode") {
  // Viviani's double point and the lemniscate's crossing are regular zeros of the singular system.
  const ImplicitEquations viviani = spatial_equations("x^2+y^2+z^2-4", "(x-1)^2+y^2-1");
  Vec3 v{1.98, 0.015, -0.02};
  REQUIRE(curve::refine_singular_point(viviani, v));
  const auto box = curve::isolate_singular_point(viviani, v, 1e-3);
  REQUIRE(box.has_value());
  CHECK(box->contains(Vec3{2, 0, 0}));
  CHECK(box->max_edge() <= 2e-3);
  const ImplicitEquations lemniscate = planar_equations("(x^2+y^2)^2-2*(x^2-y^2)");
  const auto crossing = curve::isolate_singular_point(lemniscate, {1e-9, -1e-9, 0.0}, 0.05);
  REQUIRE(crossing.has_value());
  CHECK(crossing->contains(Vec3{0, 0, 0}));
  // The cusp y^2 = x^3 and the tacnode y^2 = x^4: the Hessian of f is singular there.
  CHECK(!curve::isolate_singular_point(planar_equations("y^2-x^3"), {0.0, 0.0, 0.0}, 0.01).has_value());
  CHECK(!curve::isolate_singular_point(planar_equations("y^2-x^4"), {0.0, 0.0, 0.0}, 0.01).has_value());
}
