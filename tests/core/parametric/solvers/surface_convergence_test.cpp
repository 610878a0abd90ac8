// parametric/solvers/surface_convergence: when a surface method has converged, from its documented
// rule. Both the step (|Δt|∞ <= tol x max(scale, |u|, |v|)) and the orthogonality residuals
// |<p - s, s_i>| / (|p - s| |s_i|) <= max(tol, floor) are required; a residual at the rounding
// floor 16 ε (|p| + |s|) / |p - s| ends the iteration whatever the step; three settled steps with a
// residual under kStalledResidual count as a stall at the formulas' rounding. Values by hand on the
// paraboloid's jet at (1, 0) (tests/core/parametric/solvers/paper_method_fixtures.hpp).
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "paper_method_fixtures.hpp"
#include "parametric/solvers/surface_convergence.hpp"

using namespace footpoint;
using namespace footpoint::surface;

namespace {

Orthogonality convergence_residuals(double r0, double r1, double floor) {
  Orthogonality o;
  o.relative = {r0, r1};
  o.floor = floor;
  return o;
}

// What the test concludes after each of the steps (|Δt|∞ at (0, 0)), the residuals o throughout.
std::vector<bool> convergence_run(ConvergenceTest& test, std::initializer_list<double> steps,
                                  const Orthogonality& o) {
  std::vector<bool> out;
  for (const double step : steps) out.push_back(test.converged(step, 0, 0, o));
  return out;
}

}  // namespace

TEST_CASE("surface convergence: the parameter scale and the criteria read from the options") {
  CHECK(parameter_scale({-3, 5, 0.5, 1}) == 8.0);  // the width of [-3, 5]
  CHECK(parameter_scale({10, 10.5, 20, 20.25}) == 20.25);
  const ConvergenceCriteria defaults = convergence_criteria(Options{}, {-3, 5, 0.5, 1}, 40);
  CHECK(defaults.tolerance == kDefaultTolerance);
  CHECK(defaults.scale == 8.0);
  CHECK(defaults.max_iterations == 40);
  CHECK(defaults.step_scale(2, -1) == 8.0);
  CHECK(defaults.step_scale(2, -11) == 11.0);
  CHECK(defaults.step_bound(0, 0) == 8.0 * kDefaultTolerance);
  Options given;
  given.tolerance = 1e-10;
  given.max_iterations = 7;
  const ConvergenceCriteria c = convergence_criteria(given, {0, 1, 0, 1}, 40);
  CHECK(c.tolerance == 1e-10);
  CHECK(c.max_iterations == 7);
}

TEST_CASE("surface convergence: the orthogonality residuals and their floor, by hand") {
  // p = (0, 0, 2), s = (1, 0, 1/2): p - s = (-1, 0, 3/2), |p - s| = √3.25; <p - s, s_u> = 1/2 with
  // |s_u| = √2; <p - s, s_v> = 0.
  const SurfaceJet j = test::paraboloid_jet_at_1_0();
  const Vec3 p{0, 0, 2};
  const Orthogonality o = orthogonality(p, j.s, j.su, j.sv);
  CHECK(o.relative[0] == doctest::Approx(0.5 / (std::sqrt(3.25) * std::sqrt(2.0))).epsilon(1e-15));
  CHECK(o.relative[1] == 0.0);
  const double eps = std::numeric_limits<double>::epsilon();
  CHECK(o.floor == doctest::Approx(16 * eps * (2 + std::sqrt(1.25)) / std::sqrt(3.25)).epsilon(1e-15));
  // A pole (s_u = 0): F_u vanishes identically, its residual is 0; a NaN tangent gives NaN.
  CHECK(orthogonality(p, j.s, {0, 0, 0}, j.sv).relative[0] == 0.0);
  CHECK(std::isnan(orthogonality(p, j.s, {NAN, 0, 0}, j.sv).relative[0]));
  // p on the surface: the distance is below the rounding and is measured against it (floor 1).
  const Orthogonality on = orthogonality(j.s, j.s, j.su, j.sv);
  CHECK(on.floor == 1.0);
  CHECK(on.relative[0] == 0.0);
}

TEST_CASE("surface convergence: a settled step and a small residual, both required") {
  ConvergenceCriteria criteria;
  criteria.tolerance = 1e-12;
  criteria.scale = 1.0;
  ConvergenceTest test(criteria);
  const double floor = 1e-15;
  // Step settled (1e-13 <= 1e-12), residual small: converged.
  CHECK(test.converged(1e-13, 0.5, 0.5, convergence_residuals(1e-13, 0, floor)));
  // Residual small, step not settled: not yet.
  CHECK_FALSE(test.converged(1e-3, 0.5, 0.5, convergence_residuals(1e-13, 0, floor)));
  // Step settled, residual large (above kStalledResidual): not converged, however often.
  for (int k = 0; k < 5; ++k)
    CHECK_FALSE(test.converged(0.0, 0.5, 0.5, convergence_residuals(1e-6, 0, floor)));
  // The step bound grows with |u|: 1e-9 is settled at u = 2000 (bound 2e-9), not at u = 1.
  CHECK(test.converged(1e-9, 2000, 0, convergence_residuals(1e-13, 0, floor)));
  CHECK_FALSE(test.converged(1e-9, 1, 0, convergence_residuals(1e-13, 0, floor)));
  // A residual at its floor ends the iteration whatever the step.
  CHECK(test.converged(1.0, 0.5, 0.5, convergence_residuals(1e-15, 1e-15, floor)));
  // NaN never converges.
  CHECK_FALSE(test.converged(0.0, 0.5, 0.5, convergence_residuals(NAN, 0, floor)));
}

TEST_CASE("surface convergence: three settled steps above the tolerance are a stall") {
  ConvergenceCriteria criteria;
  criteria.tolerance = 1e-15;
  const Orthogonality stalled = convergence_residuals(1e-10, 0, 1e-16);  // tol < 1e-10 < 1e-8
  ConvergenceTest test(criteria);
  CHECK(convergence_run(test, {0, 0, 0}, stalled) == std::vector<bool>{false, false, true});
  // A step that has not settled starts the count again.
  ConvergenceTest again(criteria);
  CHECK(convergence_run(again, {0, 0, 1, 0, 0, 0}, stalled) ==
        std::vector<bool>{false, false, false, false, false, true});
  // unsettled() resets it the same way.
  ConvergenceTest reset(criteria);
  CHECK(convergence_run(reset, {0, 0}, stalled) == std::vector<bool>{false, false});
  reset.unsettled();
  CHECK(convergence_run(reset, {0, 0, 0}, stalled) == std::vector<bool>{false, false, true});
}

TEST_CASE("surface convergence: a held parameter's residual does not count") {
  ConvergenceCriteria criteria;
  criteria.tolerance = 1e-12;
  ConvergenceTest test(criteria);
  // On a bound the held parameter's F_v need not vanish: only F_u is required.
  const Orthogonality o = convergence_residuals(1e-14, 0.5, 1e-16);
  CHECK_FALSE(test.converged(0.0, 0, 0, o));
  CHECK(test.converged(0.0, 0, 0, o, {true, false}));
  CHECK_FALSE(test.converged(0.0, 0, 0, o, {false, true}));
}
