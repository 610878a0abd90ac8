// implicit/geometry/implicit_curve_differentials: the tangent, the curvature vector of [Curve] eq. (16) and
// the orthogonality function F of eq. (7) with its gradient, on a circle where all three are known
// in closed form, and at a singular point where they are not defined.
#include <doctest/doctest.h>

#include <cmath>

#include "implicit/geometry/implicit_curve_differentials.hpp"
#include "implicit_fixtures.hpp"

using namespace footpoint;
using namespace footpoint::test;

TEST_CASE("tangent and curvature vector of a circle: unit tangent, c pointing at the centre with |c| = 1/r") {
  const ImplicitEquations eq = circle();
  for (double a : {0.0, 0.7, 2.0, -2.5}) {
    const Vec3 x = circle_point(a);
    const ImplicitJet j = eq.jet(x);
    CAPTURE(a);
    // T = grad f1 x grad f2 = 2 X x e_z = (2y, -2x, 0): the direction of decreasing angle.
    const Vec3 t = curve::unit_tangent(j);
    CHECK(norm(t - Vec3{std::sin(a), -std::cos(a), 0.0}) <= 1e-15);
    Vec3 c;
    REQUIRE(curve::curvature_vector(j, c));
    const Vec3 expected =
        (Vec3{0, 0, 1} - x) / (kCircleRadius * kCircleRadius);  // towards the centre, 1/r long
    CHECK(norm(c - expected) <= 2e-16 * 4);
    CHECK(std::fabs(dot(c, t)) <= 4e-16);  // eq. (15), third row, to a few ulps of |c|
  }
}

TEST_CASE("orthogonality function: F(X) = <T, P - X> and its gradient in closed form") {
  // T = (2y, -2x, 0): F = 2y (px - x) - 2x (py - y) = 2 (y px - x py), grad F = (-2 py, 2 px, 0).
  const ImplicitEquations eq = circle();
  const Vec3 p{3.0, -1.5, 0.25};
  for (const Vec3 x : {Vec3{0.5, 1.25, 1.0}, Vec3{-2.0, 0.75, 0.5}, circle_point(1.0)}) {
    const curve::OrthogonalityFunction f = curve::orthogonality_function(eq.jet(x), x, p);
    CHECK(f.value == doctest::Approx(2.0 * (x.y * p.x - x.x * p.y)).epsilon(1e-15));
    CHECK(norm(f.gradient - Vec3{-2.0 * p.y, 2.0 * p.x, 0.0}) <= 1e-14);
  }
}

TEST_CASE("a planar curve is embedded as f1 = f, f2 = z: T = (f_y, -f_x, 0)") {
  const ImplicitEquations eq = planar_equations("x^2/9+y^2/4-1");
  const Vec3 x{3.0 * std::cos(0.4), 2.0 * std::sin(0.4), 0.0};
  const ImplicitJet j = eq.jet(x);
  CHECK(j.f[1] == 0.0);
  CHECK(norm(j.grad[1] - Vec3{0, 0, 1}) == 0.0);
  CHECK(norm(j.tangent() - Vec3{2.0 * x.y / 4.0, -2.0 * x.x / 9.0, 0.0}) <= 1e-16);
  // The ellipse's curvature vector lies in the plane, normal to T.
  Vec3 c;
  REQUIRE(curve::curvature_vector(j, c));
  CHECK(c.z == 0.0);
  CHECK(std::fabs(dot(c, curve::unit_tangent(j))) <= 4e-16);
  // |c| = a b / (a^2 sin^2 s + b^2 cos^2 s)^{3/2} for x = (a cos s, b sin s).
  const double s = 0.4, a = 3.0, b = 2.0;
  const double k =
      a * b / std::pow(a * a * std::sin(s) * std::sin(s) + b * b * std::cos(s) * std::cos(s), 1.5);
  CHECK(norm(c) == doctest::Approx(k).epsilon(1e-14));
}

TEST_CASE("at a singular point (T = 0) there is no tangent and no curvature vector") {
  // Viviani's curve crosses itself at (2, 0, 0), where the two spheres' normals are parallel.
  const ImplicitEquations eq = spatial_equations("x^2+y^2+z^2-4", "(x-1)^2+y^2-1");
  const ImplicitJet j = eq.jet({2.0, 0.0, 0.0});
  CHECK(norm(j.tangent()) == 0.0);
  CHECK(norm2(curve::unit_tangent(j)) == 0.0);
  Vec3 c;
  CHECK(!curve::curvature_vector(j, c));
}

TEST_CASE("critical_point_step: Newton on (f1, f2, F) converges quadratically to the circle's foot") {
  const ImplicitEquations eq = circle();
  const Vec3 p{2.5, -1.2, 1.7};
  const Vec3 foot = circle_foot(p);
  Vec3 x = foot + Vec3{3e-3, -2e-3, 1e-3};
  double previous = norm(x - foot);
  for (int n = 0; n < 3; ++n) {
    const ImplicitJet j = eq.jet(x);
    Vec3 step;
    REQUIRE(curve::critical_point_step(j, x, p, j.f, step));
    x += step;
    const double error = norm(x - foot);
    CHECK(error <= std::fmax(4.0 * previous * previous, 1e-15));  // quadratic, to rounding
    previous = error;
  }
  CHECK(previous <= 1e-15);
  // At a singular point of the curve G' is singular: no step.
  const ImplicitEquations cone = spatial_equations("x^2+y^2-z^2", "z-x");
  Vec3 step;
  CHECK_FALSE(curve::critical_point_step(cone.jet({0, 0, 0}), {0, 0, 0}, p, {0.0, 0.0}, step));
}
