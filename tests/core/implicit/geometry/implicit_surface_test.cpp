// implicit/geometry/implicit_surface: the equation of an implicit surface, its exact jet and its
// enclosures over boxes, on the unit sphere f = x^2 + y^2 + z^2 - 1 where all are known in closed
// form: f(1, 2, 3) = 13, grad f = 2x, Hessian 2I; over a box the range of f is that of |x|^2 - 1
// (nearest and farthest corners or faces), and every enclosure must hold the values at points of the
// box; a box the sphere does not meet is refused, one it crosses kept.
#include <doctest/doctest.h>

#include <random>

#include "implicit/geometry/implicit_surface.hpp"

using namespace footpoint;

namespace {

ImplicitSurfaceEquation unit_sphere_equation() {
  return ImplicitSurfaceEquation(formula::Program::compile({{"f", "x^2+y^2+z^2-1"}}, {"x", "y", "z"}, {}));
}

bool surface_interval_holds(const Interval& i, double x) { return i.lo <= x && x <= i.hi; }

}  // namespace

TEST_CASE("implicit surface: the value and exact jet of the sphere's equation") {
  const ImplicitSurfaceEquation sphere = unit_sphere_equation();
  CHECK(sphere.value({1, 2, 3}) == 13.0);
  CHECK(sphere.value({0.6, 0.8, 0}) == doctest::Approx(0.0).scale(1.0).epsilon(1e-15));
  const ImplicitSurfaceJet j = sphere.jet({1, 2, 3});
  CHECK(j.f == 13.0);
  CHECK(j.grad.x == 2.0);
  CHECK(j.grad.y == 4.0);
  CHECK(j.grad.z == 6.0);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) CHECK(j.hess[static_cast<std::size_t>(r)][c] == (r == c ? 2.0 : 0.0));
}

TEST_CASE("implicit surface: enclosures over boxes hold the values, gradients and Hessians") {
  const ImplicitSurfaceEquation sphere = unit_sphere_equation();
  // Over [0.5, 1] x [0, 0.5] x [-1, 0] the range of |x|^2 - 1 is [0.25 - 1, 1 + 0.25 + 1 - 1].
  const Box3 box{{0.5, 0, -1}, {1, 0.5, 0}};
  const Interval f = sphere.value_enclosure(box);
  CHECK(f.lo <= -0.75);
  CHECK(f.hi >= 1.25);
  CHECK(sphere.may_vanish(box));
  const ImplicitSurfaceIntervalJet g = sphere.interval_gradient(box);
  const ImplicitSurfaceIntervalJet h = sphere.interval_jet(box);
  std::mt19937_64 rng(33);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    const Vec3 x{0.5 + 0.5 * unit(rng), 0.5 * unit(rng), -unit(rng)};
    const ImplicitSurfaceJet j = sphere.jet(x);
    CHECK(surface_interval_holds(f, j.f));
    CHECK(surface_interval_holds(g.f, j.f));
    for (int k = 0; k < 3; ++k) {
      CHECK(surface_interval_holds(g.grad[static_cast<std::size_t>(k)], j.grad[k]));
      CHECK(surface_interval_holds(h.grad[static_cast<std::size_t>(k)], j.grad[k]));
      for (int c = 0; c < 3; ++c)
        CHECK(surface_interval_holds(h.hess[static_cast<std::size_t>(k)][static_cast<std::size_t>(c)],
                                     j.hess[static_cast<std::size_t>(k)][c]));
    }
  }
  // The gradient 2x over the box is [1, 2] x [0, 1] x [-2, 0], enclosed with outward rounding only
  // (a linear term loses nothing else).
  CHECK(g.grad[0].lo <= 1.0);
  CHECK(g.grad[0].lo >= 1.0 - 1e-15);
  CHECK(g.grad[0].hi >= 2.0);
  CHECK(g.grad[0].hi <= 2.0 + 1e-15);
  CHECK(g.grad[2].lo <= -2.0);
  CHECK(g.grad[2].lo >= -2.0 - 1e-15);
  CHECK(g.grad[2].hi >= 0.0);
  CHECK(g.grad[2].hi <= 1e-15);
  CHECK(g.lipschitz);
  CHECK(h.smooth);
}

TEST_CASE("implicit surface: a box the sphere does not meet is refused, a point box encloses f") {
  const ImplicitSurfaceEquation sphere = unit_sphere_equation();
  CHECK_FALSE(sphere.may_vanish({{2, 2, 2}, {3, 3, 3}}));                 // f >= 11 there
  CHECK_FALSE(sphere.may_vanish({{-0.1, -0.1, -0.1}, {0.1, 0.1, 0.1}}));  // f <= -0.97
  CHECK(sphere.may_vanish({{0.9, -0.1, -0.1}, {1.1, 0.1, 0.1}}));         // holds (1, 0, 0)
  const Interval at = sphere.value_enclosure({{1, 2, 3}, {1, 2, 3}});
  CHECK(at.lo <= 13.0);
  CHECK(at.hi >= 13.0);
  CHECK(at.hi - at.lo <= 16 * 0x1p-52 * 13);  // a few units of rounding
}
