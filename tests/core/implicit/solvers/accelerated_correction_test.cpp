// implicit/solvers/accelerated_correction: the Newton steps of [Curve] eqs. (19)-(20) in closed form on
// the circle of implicit_fixtures.hpp, and Algorithm 3 converging from a curve point to the foot point.
#include <doctest/doctest.h>

#include <cmath>

#include "implicit/solvers/accelerated_correction.hpp"
#include "implicit_fixtures.hpp"

using namespace footpoint;
using namespace footpoint::test;

TEST_CASE("newton_onto_equation: Z = Y - f_i / |grad f_i|^2 grad f_i") {
  const ImplicitEquations eq = circle();
  const Vec3 y{1.0, 1.5, 0.5};
  Vec3 z;
  REQUIRE(curve::newton_onto_equation(eq, 0, y, z));
  const double f1 = norm2(y) - 4.0;  // grad f1 = 2y
  CHECK(norm(z - (y - (f1 / (4.0 * norm2(y))) * (2.0 * y))) <= 1e-15);
  REQUIRE(curve::newton_onto_equation(eq, 1, y, z));
  CHECK(norm(z - Vec3{1.0, 1.5, 1.0}) == 0.0);  // f2 = z - 1 is linear: one step lands
  // grad f1 = 0 at the origin: no step.
  CHECK(!curve::newton_onto_equation(eq, 0, {0, 0, 0}, z));
}

TEST_CASE("newton_onto_orthogonality: U = Z - F / |grad F|^2 grad F with F = 2 (y px - x py)") {
  const ImplicitEquations eq = circle();
  const Vec3 p{3.0, -1.5, 0.25}, z{0.5, 1.25, 1.0};
  Vec3 u;
  REQUIRE(curve::newton_onto_orthogonality(eq.jet(z), z, p, u));
  const double f = 2.0 * (z.y * p.x - z.x * p.y);
  const Vec3 g{-2.0 * p.y, 2.0 * p.x, 0.0};
  CHECK(norm(u - (z - (f / norm2(g)) * g)) <= 1e-15 * 4);
}

TEST_CASE("accelerate_onto_foot: Algorithm 3 from points of Viviani's curve to the foot point") {
  // The stationary point of |p - X| on the curve for p = (0.5, 1.5, 1): the Lagrange system solved
  // with mpmath's findroot at 50 digits.
  const ImplicitEquations eq = spatial_equations("x^2+y^2+z^2-4", "(x-1)^2+y^2-1");
  const Vec3 p{0.5, 1.5, 1.0};
  const Vec3 foot{0.88718670641719025, 0.99361620396962064, 1.4918534067278928};
  const curve::IterationControl c = curve::make_control(Options{}, curve::kPaperIterations, nullptr);
  for (double a : {1.0, 2.0}) {
    // Viviani's curve: (1 + cos a, sin a, sqrt(4 - |(x, y)|^2)) on its upper half.
    Vec3 x0{1.0 + std::cos(a), std::sin(a), 0.0};
    x0.z = std::sqrt(4.0 - norm2(x0));
    const curve::Landing l = curve::accelerate_onto_foot(eq, p, x0, c);
    CAPTURE(a);
    CHECK(l.status == Status::converged);
    CHECK(norm(l.x - foot) <= 1e-14);
    CHECK(l.iterations < 100);
  }
}

TEST_CASE("accelerate_onto_foot: on a planar curve eq. (18) is singular at the foot point") {
  // For a curve in a plane, T x c is the plane's normal, so (T x c) x dV lies in the plane,
  // orthogonal to dV = U - Z; at the foot point dV is tangent and that row is the curve's normal in
  // the plane, a combination of grad f1 and grad f2: the correction of eq. (18) is not determined
  // there, and the iteration wanders near the foot point until its budget is spent. Algorithm 5
  // (eq. (20), without the correction) converges from the same point.
  const Vec3 p{3.0, 1.0, 2.0};
  const curve::IterationControl c = curve::make_control(Options{}, 2000, nullptr);
  const curve::Landing l = curve::accelerate_onto_foot(circle(), p, circle_point(0.0), c);
  CHECK(l.status == Status::max_iterations);
  CHECK(norm(l.x - circle_foot(p)) < 0.2);
  CHECK(norm(l.x - circle_foot(p)) > 1e-6);
}
