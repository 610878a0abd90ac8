// parametric/solvers/newton: plain Newton on the orthogonality conditions F = (<p - s, s_u>,
// <p - s, s_v>) ([Hybrid] eqs. (22)-(24)). Its system and step on a jet worked out by hand (the
// paraboloid z = (u^2 + v^2)/2), a singular F' refused, and the method converging quadratically to
// a sphere's foot point, which is p / |p| in closed form.
#include <doctest/doctest.h>

#include <cmath>

#include "paper_method_fixtures.hpp"
#include "parametric/solvers/newton.hpp"

using footpoint::SurfaceJet;
using footpoint::Vec3;

TEST_CASE("surface newton: the orthogonality system and its step, by hand") {
  // p - s = (-1, 0, 1.5): F = (-1 + 1.5, 0) = (0.5, 0); F'_11 = <p - s, s_uu> - |s_u|^2 = 1.5 - 2,
  // F'_12 = F'_21 = 0 - 0, F'_22 = 1.5 - 1. The step -F'^{-1} F = (-(0.5 / -0.5), 0) = (1, 0).
  const Vec3 p{0, 0, 2};
  const auto sys = footpoint::surface::orthogonality_system(p, footpoint::test::paraboloid_jet_at_1_0());
  CHECK(sys.F1 == 0.5);
  CHECK(sys.F2 == 0.0);
  CHECK(sys.J11 == -0.5);
  CHECK(sys.J12 == 0.0);
  CHECK(sys.J21 == 0.0);
  CHECK(sys.J22 == 0.5);
  CHECK(sys.det() == -0.25);
  const auto step = footpoint::surface::newton_step(p, footpoint::test::paraboloid_jet_at_1_0());
  CHECK(step.failure == footpoint::Status::converged);
  CHECK(step.du == 1.0);
  CHECK(step.dv == 0.0);
  // Off the axis, p = (0, 1, 2): F = (0.5, 1), F' = [-0.5 0; 0 0.5] (s_uv = 0, s_u . s_v = 0), so
  // the step is (1, -2).
  const auto off = footpoint::surface::newton_step({0, 1, 2}, footpoint::test::paraboloid_jet_at_1_0());
  CHECK(off.du == 1.0);
  CHECK(off.dv == -2.0);
}

TEST_CASE("surface newton: a singular F' is degenerate, a NaN non-finite") {
  // p - s = (-1, 0, 2.5): F'_11 = 2.5 - 2 = 0.5, F'_22 = 2.5 - 1 = 1.5; with p = (0, 0, 1.5):
  // F'_11 = 1 - 2 = -1, F'_22 = 0: det 0.
  const auto singular =
      footpoint::surface::newton_step({0, 0, 1.5}, footpoint::test::paraboloid_jet_at_1_0());
  CHECK(singular.failure == footpoint::Status::degenerate);
  const auto nan = footpoint::surface::newton_step({NAN, 0, 2}, footpoint::test::paraboloid_jet_at_1_0());
  CHECK(nan.failure == footpoint::Status::non_finite);
}

TEST_CASE("surface newton: converges to the sphere's foot point p / |p|") {
  const auto sphere = footpoint::test::unit_sphere_formulas();
  const footpoint::ParamBox box{-M_PI, M_PI, -M_PI / 2, M_PI / 2};
  const Vec3 p{2, 1, 0.5};
  const double u = std::atan2(1.0, 2.0), v = std::asin(0.5 / std::sqrt(5.25));
  footpoint::Options options;
  options.initial = std::array<double, 3>{u + 0.2, v - 0.15, 0.0};
  const auto r = footpoint::surface::project_newton(sphere, box, p, options);
  CHECK(r.summary.status == footpoint::Status::converged);
  CHECK(r.params[0] == doctest::Approx(u).epsilon(1e-12));
  CHECK(r.params[1] == doctest::Approx(v).epsilon(1e-12));
  CHECK(r.distance == doctest::Approx(std::sqrt(5.25) - 1.0).epsilon(1e-12));
  for (int k = 0; k < 3; ++k) {
    const double expected = (k == 0 ? 2.0 : k == 1 ? 1.0 : 0.5) / std::sqrt(5.25);
    CHECK(r.foot[static_cast<std::size_t>(k)] == doctest::Approx(expected).epsilon(1e-12));
  }
  // Quadratic convergence: a handful of steps, not the first-order method's dozens.
  CHECK(r.summary.iterations <= 8);
  // Newton finds any stationary point: from near the antipode it converges to the farthest point,
  // -p / |p| (parameters u - π, -v), at distance |p| + 1.
  options.initial = std::array<double, 3>{u - M_PI + 0.1, -v + 0.1, 0.0};
  const auto far = footpoint::surface::project_newton(sphere, box, p, options);
  CHECK(far.summary.status == footpoint::Status::converged);
  CHECK(far.distance == doctest::Approx(std::sqrt(5.25) + 1.0).epsilon(1e-12));
}
