// parametric/solvers/first_order: the tangent-plane ("H-H-H") iteration, [GSA] eq. (2): the step
// solves the first fundamental form system [E F; F G] Δ = (<p - s, s_u>, <p - s, s_v>). Its step
// on a jet worked out by hand, a degenerate tangent plane refused, and the iteration on a sphere:
// along a great circle its map is θ -> θ - (|p| / R) sin θ, so it converges linearly (rate
// 1 - |p|/R) to p / |p| for |p| < 2R and does not converge beyond.
#include <doctest/doctest.h>

#include <cmath>

#include "paper_method_fixtures.hpp"
#include "parametric/solvers/first_order.hpp"

using footpoint::SurfaceJet;
using footpoint::Vec3;

TEST_CASE("first-order step: the first fundamental form system, by hand") {
  // The paraboloid (u, v, (u^2 + v^2)/2) at (1, 0): E = |s_u|^2 = 2, F = 0, G = 1; p = (0, 1, 2),
  // p - s = (-1, 1, 1.5): right-hand side (0.5, 1), so Δ = (0.25, 1).
  const auto step = footpoint::surface::first_order_step({0, 1, 2}, footpoint::test::paraboloid_jet_at_1_0());
  CHECK(step.failure == footpoint::Status::converged);
  CHECK(step.du == doctest::Approx(0.25).epsilon(1e-15));
  CHECK(step.dv == doctest::Approx(1.0).epsilon(1e-15));
  // A skew parametrisation (s_u = (1, 0, 0), s_v = (1, 1, 0): E = 1, F = 1, G = 2) at the origin
  // towards p = (3, 2, 7): right-hand side (3, 5), Δ = [1 1; 1 2]^{-1} (3, 5) = (1, 2): the
  // tangent-plane point s + Δu s_u + Δv s_v = (3, 2, 0) is p's projection onto the plane z = 0.
  SurfaceJet skew;
  skew.su = {1, 0, 0};
  skew.sv = {1, 1, 0};
  const auto plane = footpoint::surface::first_order_step({3, 2, 7}, skew);
  CHECK(plane.du == doctest::Approx(1.0).epsilon(1e-15));
  CHECK(plane.dv == doctest::Approx(2.0).epsilon(1e-15));
  // Parallel tangents (s_u x s_v = 0): no tangent plane.
  SurfaceJet flat;
  flat.su = {1, 0, 0};
  flat.sv = {2, 0, 0};
  CHECK(footpoint::surface::first_order_step({0, 1, 0}, flat).failure == footpoint::Status::degenerate);
}

TEST_CASE("first-order iteration: linear convergence to a sphere's foot point inside 2R") {
  const auto sphere = footpoint::test::unit_sphere_formulas();
  const footpoint::ParamBox box{-M_PI, M_PI, -M_PI / 2, M_PI / 2};
  const double u = 0.7, v = 0.3;
  const Vec3 direction{std::cos(u) * std::cos(v), std::sin(u) * std::cos(v), std::sin(v)};
  footpoint::Options options;
  options.initial = std::array<double, 3>{u + 0.3, v - 0.2, 0.0};
  // |p| = 1.5: rate |1 - 1.5| = 0.5 per step.
  const auto r = footpoint::surface::project_first_order(sphere, box, 1.5 * direction, options);
  CHECK(r.summary.status == footpoint::Status::converged);
  CHECK(r.params[0] == doctest::Approx(u).epsilon(1e-10));
  CHECK(r.params[1] == doctest::Approx(v).epsilon(1e-10));
  CHECK(r.distance == doctest::Approx(0.5).epsilon(1e-10));
  // Linear, not quadratic: 0.5^k brings 0.3 to 1e-15 in about 50 steps.
  CHECK(r.summary.iterations >= 20);
  // |p| = 0.2 (inside): rate 0.8, still converging, to the same parameters.
  const auto inside = footpoint::surface::project_first_order(sphere, box, 0.2 * direction, options);
  CHECK(inside.summary.status == footpoint::Status::converged);
  CHECK(inside.params[0] == doctest::Approx(u).epsilon(1e-9));
  // |p| = 3: the map's slope at the foot is 1 - 3 = -2, the iterates move away: no convergence.
  const auto outside = footpoint::surface::project_first_order(sphere, box, 3.0 * direction, options);
  CHECK(outside.summary.status != footpoint::Status::converged);
}
