// The local solve's early stop (parametric/solvers/projected_newton.hpp): a solve is abandoned when
// Newton's model proves its basin to be a known minimiser's, or to hold nothing nearer than the
// cutoff - and not otherwise.
#include <doctest/doctest.h>

#include <cmath>

#include "parametric/solvers/projected_newton.hpp"
#include "surface_fixtures.hpp"

using namespace footpoint;
using namespace footpoint::test;
using namespace footpoint::surface;

namespace {

constexpr double kTwoPi = 6.283185307179586;

// A torus covered twice in u: s(u + 2π, v) = s(u, v), so every foot has two parameter pairs.
std::shared_ptr<const ParametricSurface> double_torus() {
  return make_surface("(2+0.5*cos(v))*cos(u)", "(2+0.5*cos(v))*sin(u)", "0.5*sin(v)", {0, 2 * kTwoPi},
                      {0, kTwoPi});
}

ConvergenceCriteria criteria_for(const ParametricSurface& g) {
  return convergence_criteria(Options{}, g.domain(), kLocalMaxIterations);
}

}  // namespace

TEST_CASE("a copy of the best foot is abandoned against its own distance, solved against a larger cutoff") {
  const auto g = double_torus();
  const Vec3 p{1.3, 1.1, 0.7};
  const ConvergenceCriteria crit = criteria_for(*g);
  const LocalSolution first = projected_newton(g->formulas(), g->domain(), p, 0.8, 1.0, crit);
  REQUIRE(first.status == Status::converged);
  REQUIRE_FALSE(first.abandoned);
  // the same foot from the other copy, started a little off it
  const double u0 = first.u + kTwoPi + 0.05, v0 = first.v - 0.05;
  EarlyStop early;
  early.cutoff = first.distance;
  const LocalSolution copy = projected_newton(g->formulas(), g->domain(), p, u0, v0, crit, nullptr, &early);
  CHECK(copy.abandoned);
  CHECK(copy.iterations <= 3);
  // the predicted minimiser is the copy's, and its bound no more than the tie below the cutoff
  CHECK(copy.u == doctest::Approx(first.u + kTwoPi).epsilon(1e-6));
  CHECK(copy.v == doctest::Approx(first.v).epsilon(1e-6));
  CHECK(copy.distance >= first.distance * (1.0 - 1e-12));

  // a cutoff above the basin's minimum (by more than the tie) must let it be solved
  early.cutoff = first.distance * (1.0 + 1e-9);
  const LocalSolution solved = projected_newton(g->formulas(), g->domain(), p, u0, v0, crit, nullptr, &early);
  CHECK_FALSE(solved.abandoned);
  CHECK(solved.status == Status::converged);
  CHECK(solved.distance == doctest::Approx(first.distance).epsilon(1e-14));
  CHECK(solved.u == doctest::Approx(first.u + kTwoPi).epsilon(1e-13));
}

TEST_CASE("a solve in a known minimiser's basin is abandoned; one in another basin is not") {
  const auto g = double_torus();
  const Vec3 p{1.3, 1.1, 0.7};
  const ConvergenceCriteria crit = criteria_for(*g);
  const LocalSolution first = projected_newton(g->formulas(), g->domain(), p, 0.8, 1.0, crit);
  REQUIRE(first.status == Status::converged);

  const std::array<double, 2> known[1] = {{first.u, first.v}};
  EarlyStop early;  // no cutoff: only the minimiser test
  early.minimisers = known;
  early.minimiser_count = 1;
  const LocalSolution same =
      projected_newton(g->formulas(), g->domain(), p, first.u + 0.1, first.v - 0.1, crit, nullptr, &early);
  CHECK(same.abandoned);
  CHECK(same.u == first.u);
  CHECK(same.v == first.v);
  CHECK_FALSE(std::isfinite(same.distance));  // merged, not bounded

  // the copy's basin is another one: solved to its end
  const LocalSolution other = projected_newton(g->formulas(), g->domain(), p, first.u + kTwoPi + 0.1,
                                               first.v - 0.1, crit, nullptr, &early);
  CHECK_FALSE(other.abandoned);
  CHECK(other.status == Status::converged);
  CHECK(other.u == doctest::Approx(first.u + kTwoPi).epsilon(1e-13));
}

TEST_CASE("a worse local minimum is abandoned against the best distance") {
  // C5 of [Hybrid]: z = cos(u^2 + v^2) on [0,2]^2, p = (4, 5, 6) has several minima
  const auto g = make_surface("u", "v", "cos(u^2+v^2)", {0, 2}, {0, 2});
  const Vec3 p{4, 5, 6};
  const ConvergenceCriteria crit = criteria_for(*g);
  const ProjectionResult best = project(*g, {4, 5, 6}, "auto");
  REQUIRE(best.summary.status == Status::converged);
  Options all;
  all.all_minima = true;
  const ProjectionResult minima = project(*g, {4, 5, 6}, "auto", all);
  REQUIRE(minima.minima.size() >= 2);
  int interior_worse = 0;
  for (const Minimum& m : minima.minima) {
    if (m.location != Location::interior || m.distance <= best.distance * (1.0 + 1e-6)) continue;
    ++interior_worse;
    EarlyStop early;
    early.cutoff = best.distance;
    const LocalSolution s = projected_newton(g->formulas(), g->domain(), p, m.params[0] + 0.01,
                                             m.params[1] - 0.01, crit, nullptr, &early);
    INFO("worse minimum d = " << m.distance << " at (" << m.params[0] << ", " << m.params[1] << ")");
    CHECK(s.abandoned);
    CHECK(s.distance >= best.distance);
    CHECK(s.distance <= m.distance * (1.0 + 1e-6));
  }
  CHECK(interior_worse >= 1);
}

TEST_CASE("the early stop on a face: a known minimiser on the same edge ends a solve along it") {
  // A far point of the HTTP benchmark on S1: its nearest point is on the edge u = 3, and the
  // cells along that edge all start solves there (an early stop that needed the ball inside the
  // domain would let each of them run to convergence).
  const auto g = make_surface("u+v", "sin(u)+2*cos(v)", "sin(u+v)", {-3, 3}, {-3, 3});
  const ConvergenceCriteria criteria = criteria_for(*g);
  const Vec3 p{9.85065, 2.36607, -1.00025};
  const LocalSolution first = projected_newton(g->formulas(), g->domain(), p, 3.0, 1.5, criteria);
  REQUIRE(first.status == Status::converged);
  REQUIRE(first.u == 3.0);
  CHECK(first.v == doctest::Approx(1.75518).epsilon(1e-5));
  const LocalSolution full = projected_newton(g->formulas(), g->domain(), p, 3.0, 2.0625, criteria);
  REQUIRE(full.status == Status::converged);
  CHECK(full.v == doctest::Approx(first.v).epsilon(1e-12));

  const std::array<double, 2> known[1] = {{first.u, first.v}};
  EarlyStop early;
  early.minimisers = known;
  early.minimiser_count = 1;
  const LocalSolution stopped =
      projected_newton(g->formulas(), g->domain(), p, 3.0, 2.0625, criteria, nullptr, &early);
  CHECK(stopped.abandoned);
  CHECK(stopped.u == first.u);
  CHECK(stopped.v == first.v);
  CHECK(stopped.iterations < full.iterations);

  // a minimiser just inside the domain is not on the face: the solve goes on to the edge's own
  const std::array<double, 2> off_face[1] = {{std::nextafter(3.0, 0.0), first.v}};
  early.minimisers = off_face;
  const LocalSolution solved =
      projected_newton(g->formulas(), g->domain(), p, 3.0, 2.0625, criteria, nullptr, &early);
  CHECK_FALSE(solved.abandoned);
  CHECK(solved.status == Status::converged);
  CHECK(solved.v == doctest::Approx(first.v).epsilon(1e-12));
}
