// geometry/midpoint_radius: dot_minus encloses Σ a_i b_i - t for points of its intervals
// (products in long double, exact for doubles' products to 64 bits), keeps exact zeros exact,
// and is about as tight as interval arithmetic rounded outwards product by product.
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <random>

#include "geometry/interval_vec3.hpp"
#include "geometry/midpoint_radius.hpp"

using namespace footpoint;
using formula::Interval;

TEST_CASE("midrad::dot_minus holds every value of its operands' points") {
  std::mt19937_64 rng(41);
  std::uniform_real_distribution<double> u(-5.0, 5.0), w(0.0, 1.0), t01(0.0, 1.0);
  std::uniform_int_distribution<int> kind(0, 5);
  auto interval = [&] {
    switch (kind(rng)) {
      case 0:
        return Interval{0.0, 0.0};  // an exact zero
      case 1: {
        const double x = u(rng);
        return Interval{x, x};  // a point
      }
      case 2: {
        const double x = u(rng) * 1e-3, e = w(rng) * 1e-9;
        return Interval{x, x + e};  // narrow
      }
      default: {
        const double x = u(rng);
        return Interval{x, x + w(rng)};
      }
    }
  };
  for (int n = 0; n < 20000; ++n) {
    IVec3 a, b;
    for (int i = 0; i < 3; ++i) {
      a[i] = interval();
      b[i] = interval();
    }
    const Interval t = interval();
    const Interval g = midrad::dot_minus(a, b, t);
    REQUIRE(g.lo <= g.hi);
    for (int k = 0; k < 20; ++k) {
      auto pick = [&](const Interval& x) { return x.lo + t01(rng) * (x.hi - x.lo); };
      long double exact = -static_cast<long double>(std::fmin(std::fmax(pick(t), t.lo), t.hi));
      for (int i = 0; i < 3; ++i)
        exact += static_cast<long double>(std::fmin(std::fmax(pick(a[i]), a[i].lo), a[i].hi)) *
                 std::fmin(std::fmax(pick(b[i]), b[i].lo), b[i].hi);
      CHECK(g.lo <= exact);
      CHECK(exact <= g.hi);
    }
    // No wider than 1.5 times the outward interval products' enclosure, plus rounding.
    const Interval iv = formula::interval::sub(ivec::dot(a, b), t);
    CHECK(g.hi - g.lo <= 1.5 * (iv.hi - iv.lo) + 1e-12 * (std::abs(iv.lo) + std::abs(iv.hi)) + 1e-250);
  }
  // Exact zeros stay exact: every term with a zero factor, t = 0.
  const IVec3 zero{{{0, 0}, {0, 0}, {0, 0}}}, some{{{1, 2}, {-3, 4}, {5, 5}}};
  const Interval z = midrad::dot_minus(zero, some, Interval{0, 0});
  CHECK(z.lo == 0.0);
  CHECK(z.hi == 0.0);
  // Anything not finite: the whole line.
  const IVec3 wide{{{-INFINITY, INFINITY}, {0, 1}, {0, 1}}};
  const Interval all = midrad::dot_minus(wide, some, Interval{0, 0});
  CHECK(all.lo == -INFINITY);
  CHECK(all.hi == INFINITY);
}
