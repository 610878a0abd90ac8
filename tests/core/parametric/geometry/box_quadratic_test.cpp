// minimize_on_box (parametric/geometry/box_quadratic.hpp): the exact minimum of a 2-D quadratic over a
// rectangle (for a positive definite one only the edges its minimiser is beyond are tried),
// against a dense grid of the rectangle, for positive definite, indefinite and singular H.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "parametric/geometry/box_quadratic.hpp"

using namespace footpoint;

TEST_CASE("minimize_on_box is the minimum over the rectangle") {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  for (int trial = 0; trial < 3000; ++trial) {
    BoxQuadratic q;
    q.g = {3.0 * U(rng), 3.0 * U(rng)};
    const double a = U(rng), b = U(rng), c = U(rng);
    switch (trial % 3) {
      case 0:
        q.H = {{{a * a + 0.1, a * b}, {a * b, b * b + c * c + 0.1}}};
        break;  // positive definite
      case 1:
        q.H = {{{a, b}, {b, c}}};
        break;  // any
      default:
        q.H = {{{a * a, a * b}, {a * b, b * b}}};
        break;  // singular
    }
    const std::array<double, 2> lo{-std::abs(U(rng)), -std::abs(U(rng))},
        hi{std::abs(U(rng)), std::abs(U(rng))};
    const BoxMinimum m = minimize_on_box(q, lo, hi);
    CHECK(m.delta[0] >= lo[0]);
    CHECK(m.delta[0] <= hi[0]);
    CHECK(m.delta[1] >= lo[1]);
    CHECK(m.delta[1] <= hi[1]);
    CHECK(m.value == doctest::Approx(q.value(m.delta[0], m.delta[1])).epsilon(1e-12));
    double grid_min = std::numeric_limits<double>::infinity();
    constexpr int n = 60;
    for (int i = 0; i <= n; ++i)
      for (int j = 0; j <= n; ++j)
        grid_min =
            std::min(grid_min, q.value(lo[0] + (hi[0] - lo[0]) * i / n, lo[1] + (hi[1] - lo[1]) * j / n));
    CHECK(m.value <= grid_min + 1e-12);
    for (int k = 0; k < 2; ++k) {
      const int side = m.delta[k] <= lo[k] ? -1 : (m.delta[k] >= hi[k] ? 1 : 0);
      CHECK(m.side[k] == side);
    }
  }
}
