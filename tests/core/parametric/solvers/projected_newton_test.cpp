// The local solve's answer (parametric/solvers/projected_newton.cpp): the jet a solve ends with - its
// foot point, its tangents, what the answer, its residuals and its certificate are made of - is
// the formulas' own at the solve's parameters, evaluated there, never extrapolated from an earlier
// step (a Taylor expansion is no evaluation where the formulas have a kink: z = |u|).
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <random>

#include "parametric/solvers/projected_newton.hpp"
#include "surface_fixtures.hpp"

using namespace footpoint;
using namespace footpoint::test;
using namespace footpoint::surface;

TEST_CASE("a solve ends with the formulas' jet evaluated at its parameters") {
  struct Surface {
    const char* name;
    std::shared_ptr<const ParametricSurface> g;
  };
  const Surface surfaces[] = {
      {"S1", make_surface("u+v", "sin(u)+2*cos(v)", "sin(u+v)", {-3, 3}, {-3, 3})},
      {"torus",
       make_surface("(2+0.5*cos(v))*cos(u)", "(2+0.5*cos(v))*sin(u)", "0.5*sin(v)", {0, 6.3}, {0, 6.3})},
      // partials changing over a length of 1/20 in the parameters
      {"ripple", make_surface("u", "v", "0.05*sin(20*u)*cos(20*v)", {-1, 1}, {-1, 1})},
      {"S2", make_surface("u^4*v^3+u*v+u", "u^3+v^3", "u+v", {-2, 2}, {-2, 2})},
      // second partials zero on each side of a kink
      {"kink", make_surface("u", "v", "abs(u-0.1)+0.2*v", {-1, 1}, {-1, 1})},
  };
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (const Surface& surface : surfaces) {
    const ParametricSurface& g = *surface.g;
    const ParamBox box = g.domain();
    const ConvergenceCriteria criteria = convergence_criteria(Options{}, box, kLocalMaxIterations);
    int converged = 0;
    for (int k = 0; k < 400; ++k) {
      const double u = box.umin + (box.umax - box.umin) * (0.1 + 0.8 * unit(rng));
      const double v = box.vmin + (box.vmax - box.vmin) * (0.1 + 0.8 * unit(rng));
      const SurfaceJet at = g.formulas().jet(u, v);
      const Vec3 n = cross(at.su, at.sv);
      // a point 0.1 off the surface along its normal, solved from a start 1e-2 away
      const Vec3 p = at.s + n * ((unit(rng) - 0.5) * 0.2 / norm(n));
      const LocalSolution sol = projected_newton(g.formulas(), box, p, u + 1e-2 * (unit(rng) - 0.5),
                                                 v + 1e-2 * (unit(rng) - 0.5), criteria);
      if (!std::isfinite(sol.distance)) continue;
      converged += sol.status == Status::converged;
      const SurfaceJet fresh = g.formulas().jet(sol.u, sol.v);
      INFO(surface.name << " at (" << sol.u << ", " << sol.v << ")");
      CHECK(norm2(sol.jet.s - fresh.s) == 0.0);
      CHECK(norm2(sol.jet.su - fresh.su) == 0.0);
      CHECK(norm2(sol.jet.sv - fresh.sv) == 0.0);
      CHECK(sol.distance == norm(p - fresh.s));
    }
    INFO(surface.name);
    CHECK(converged >= 300);
  }
}

TEST_CASE("auto across a kink of the formulas: the nearest point, never an extrapolated one") {
  // z = |u| from (0, 0.2, -0.5): the nearest point is the kink's (0, 0.2, 0) at 0.5; a Newton step
  // from u < 0 whose jet was extrapolated along the left piece put the foot at z = -0.25, 0.354
  // away, and certified it
  const auto g = make_surface("u", "v", "abs(u)", {-1, 1}, {-1, 1});
  const ProjectionResult r = project(*g, {0, 0.2, -0.5}, "auto");
  const Vec3 foot{r.foot[0], r.foot[1], r.foot[2]};
  CHECK(norm(foot - g->formulas().point(r.params[0], r.params[1])) == 0.0);
  CHECK(r.distance >= 0.5);
  CHECK(r.distance <= 0.5 + 1e-8);
  CHECK(r.summary.certificate.lower_bound <= 0.5);
}

TEST_CASE("a convex Newton step below the parameters' last bit ends a solve as converged") {
  // The [GSA] Example 1 over [-25,25]^2, from a start found by the brute-force sweep: the
  // residual ends a hair above its rounding floor; the next Newton step is below the last bit of
  // u = 17.77, which ends the solve as converged, not `degenerate`.
  const auto g = make_surface("u+v", "sin(u)+2*cos(v)", "sin(u+v)", {-25, 25}, {-25, 25});
  const ConvergenceCriteria criteria = convergence_criteria(Options{}, g->domain(), kLocalMaxIterations);
  const Vec3 p{0.29084437405683827, 0.12161836911652069, -0.35682163493964258};
  const LocalSolution sol = projected_newton(g->formulas(), g->domain(), p, 17.8285, -17.8066, criteria);
  CHECK(sol.status == Status::converged);
  CHECK(sol.distance == doctest::Approx(0.45797324179528337).epsilon(1e-14));
  const Orthogonality o = orthogonality(p, sol.jet.s, sol.jet.su, sol.jet.sv);
  CHECK(std::max(o.relative[0], o.relative[1]) <= 2.0 * o.floor);
}
