// parametric/solvers/hybrid: [Hybrid] Algorithm 1 switches from first-order steps to Newton's once
// the Newton map G(t) = t - F'^{-1} F is a contraction (every |∂G_i/∂t_k| < 1/2). ∂G against a
// value worked out by hand on the paraboloid (u, v, (u^2 + v^2)/2) at (1, 0) for p = (0, 0, 2)
// (along v = 0, G(u) = u - F/F' with F = u - u^3/2, so ∂G_u/∂u = F F'' / F'^2 = -6), ∂G = 0 for
// a p on the normal there (F = 0), and the method converging to a sphere's foot p / |p|.
#include <doctest/doctest.h>

#include <cmath>

#include "paper_method_fixtures.hpp"
#include "parametric/solvers/hybrid.hpp"

using namespace footpoint;
using namespace footpoint::surface;

TEST_CASE("hybrid: the Newton map's derivative by hand, and the switching test") {
  SurfaceJet3 jet;
  static_cast<SurfaceJet&>(jet) = test::paraboloid_jet_at_1_0();  // third derivatives 0
  // F = (1/2, 0), F' = diag(-1/2, 1/2), F'^{-1} F = (-1, 0); ∂F'/∂u = [-3 0; 0 -1] and
  // ∂F'/∂v = [0 -1; -1 0] (from ∂/∂t_k (<p - s, s_ij> - <s_i, s_j>) with s_ijk = 0), so
  // ∂G/∂u = F'^{-1} (3, 0) = (-6, 0) and ∂G/∂v = F'^{-1} (0, 1) = (0, 2).
  const NewtonMapDerivative d = newton_map_derivative({0, 0, 2}, jet);
  REQUIRE(d.ok);
  CHECK(d.d[0][0] == doctest::Approx(-6.0).epsilon(1e-15));
  CHECK(d.d[1][0] == doctest::Approx(0.0).scale(1.0));
  CHECK(d.d[0][1] == doctest::Approx(0.0).scale(1.0));
  CHECK(d.d[1][1] == doctest::Approx(2.0).epsilon(1e-15));
  CHECK_FALSE(newton_map_contracts(d));
  // p = s + (-1, 0, 1)/4 on the normal (-1, 0, 1) of s_u x s_v at the same jet: F = 0 exactly,
  // F' = diag(1/4 - 2, 1/4 - 1) is regular, and so ∂G = 0: a contraction.
  const NewtonMapDerivative at_foot = newton_map_derivative({0.75, 0, 0.75}, jet);
  REQUIRE(at_foot.ok);
  for (const auto& row : at_foot.d)
    for (const double x : row) CHECK(x == 0.0);
  CHECK(newton_map_contracts(at_foot));
  // The test is strict: |∂G| = 1/2 does not contract.
  NewtonMapDerivative half;
  half.ok = true;
  half.d = {{{0.5, 0.0}, {0.0, 0.1}}};
  CHECK_FALSE(newton_map_contracts(half));
  half.d[0][0] = 0.4999;
  CHECK(newton_map_contracts(half));
  // A singular F': p = (0, 0, 1.5) gives F'_22 = <p - s, s_vv> - |s_v|^2 = 1 - 1 = 0, so no ∂G.
  SurfaceJet3 singular;
  static_cast<SurfaceJet&>(singular) = test::paraboloid_jet_at_1_0();
  CHECK_FALSE(newton_map_derivative({0, 0, 1.5}, singular).ok);
}

TEST_CASE("hybrid: converges to the sphere's foot point p / |p|") {
  const SurfaceFormulas sphere = test::unit_sphere_formulas();
  const ParamBox box{-M_PI, M_PI, -M_PI / 2, M_PI / 2};
  // |p| < 2: the first-order steps it may begin with converge too (their rate is 1 - |p|).
  const Vec3 p{-0.5, 1, 0.75};
  const double norm_p = std::sqrt(0.25 + 1 + 0.5625);
  const double u = std::atan2(1.0, -0.5), v = std::asin(0.75 / norm_p);
  Options options;
  options.initial = std::array<double, 3>{u - 0.5, v + 0.3, 0.0};
  const ProjectionResult r = project_hybrid(sphere, box, p, options);
  CHECK(r.summary.status == Status::converged);
  CHECK(r.params[0] == doctest::Approx(u).epsilon(1e-12));
  CHECK(r.params[1] == doctest::Approx(v).epsilon(1e-12));
  CHECK(r.distance == doctest::Approx(norm_p - 1).epsilon(1e-12));
}
