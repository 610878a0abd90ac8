// The local solve's last step (solvers/surface/projected_newton.cpp, kTaylorStep): a short convex
// Newton step takes the Taylor expansion of the jet instead of evaluating the formulas. The jet
// a solve ends with - its foot point, its tangents, what the answer and its residuals are made
// of - must be the formulas' own at the solve's parameters, to rounding.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <random>

#include "solvers/surface/projected_newton.hpp"
#include "surface_fixtures.hpp"

using namespace footpoint;
using namespace footpoint::test;
using namespace footpoint::surface;

TEST_CASE("a solve ends with the formulas' jet at its parameters, expanded or evaluated") {
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
  };
  constexpr double eps = std::numeric_limits<double>::epsilon();
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (const Surface& surface : surfaces) {
    const ParametricSurface& g = *surface.g;
    const ParamBox box = g.domain();
    const ConvergenceCriteria criteria = convergence_criteria(Options{}, box, kLocalMaxIterations);
    int converged = 0, expanded = 0;
    for (int k = 0; k < 400; ++k) {
      const double u = box.umin + (box.umax - box.umin) * (0.1 + 0.8 * unit(rng));
      const double v = box.vmin + (box.vmax - box.vmin) * (0.1 + 0.8 * unit(rng));
      const SurfaceJet at = g.formulas().jet(u, v);
      const Vec3 n = cross(at.su, at.sv);
      // a point 0.1 off the surface along its normal, solved from a start 1e-2 away
      const Vec3 p = at.s + n * ((unit(rng) - 0.5) * 0.2 / norm(n));
      const LocalSolution sol = projected_newton(g.formulas(), box, p, u + 1e-2 * (unit(rng) - 0.5),
                                                 v + 1e-2 * (unit(rng) - 0.5), criteria);
      if (sol.status != Status::converged) continue;
      ++converged;
      const SurfaceJet fresh = g.formulas().jet(sol.u, sol.v);
      INFO(surface.name << " at (" << sol.u << ", " << sol.v << ")");
      CHECK(norm(sol.jet.s - fresh.s) <= 16 * eps * norm(fresh.s));
      CHECK(norm(sol.jet.su - fresh.su) <= 64 * eps * norm(fresh.su));
      CHECK(norm(sol.jet.sv - fresh.sv) <= 64 * eps * norm(fresh.sv));
      CHECK(sol.distance == doctest::Approx(norm(p - fresh.s)).epsilon(1e-12));
      if (norm2(sol.jet.s - fresh.s) + norm2(sol.jet.su - fresh.su) + norm2(sol.jet.sv - fresh.sv) > 0.0)
        ++expanded;
    }
    INFO(surface.name);
    CHECK(converged >= 300);
    CHECK(expanded > 0);  // the expansion is what this test measures
  }
}

TEST_CASE("a convex Newton step below the parameters' last bit ends a solve as converged") {
  // The [GSA] Example 1 over [-25,25]^2, from a start found by the brute-force sweep: the
  // fourth step (3e-13) is an expanded one, whose jet leaves the residual a hair above its
  // rounding floor; the next Newton step is below the last bit of u = 17.77, which ends the
  // solve as converged, not `degenerate`.
  const auto g = make_surface("u+v", "sin(u)+2*cos(v)", "sin(u+v)", {-25, 25}, {-25, 25});
  const ConvergenceCriteria criteria = convergence_criteria(Options{}, g->domain(), kLocalMaxIterations);
  const Vec3 p{0.29084437405683827, 0.12161836911652069, -0.35682163493964258};
  const LocalSolution sol = projected_newton(g->formulas(), g->domain(), p, 17.8285, -17.8066, criteria);
  CHECK(sol.status == Status::converged);
  CHECK(sol.distance == doctest::Approx(0.45797324179528337).epsilon(1e-14));
  const Orthogonality o = orthogonality(p, sol.jet.s, sol.jet.su, sol.jet.sv);
  CHECK(std::max(o.relative[0], o.relative[1]) <= 2.0 * o.floor);
}
