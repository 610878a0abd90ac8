// parametric/geometry/closure_sampling: what the closure checks share, from its documented values:
// the 34 parameters of an edge (its ends and lo + (k + α)/32 (hi - lo), α = (3 - √5)/2), the
// tolerance 256 ε scale, the declared limit max(tolerance, 1e-6 size), the extent of points added,
// the rigorous bounds of a norm (against the exact √(3^2 + 4^2 + 12^2) = 13 and long double) and of
// a difference, and three-digit formatting.
#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "parametric/geometry/closure_sampling.hpp"

namespace cs = footpoint::closure_sampling;

TEST_CASE("closure sampling: the edge's parameters, the tolerance and the declared limit") {
  const auto t = cs::samples(-1.0, 3.0);
  REQUIRE(t.size() == 34);
  CHECK(t.front() == -1.0);
  CHECK(t.back() == 3.0);
  const double alpha = (3 - std::sqrt(5.0)) / 2;
  for (int k = 0; k < 32; ++k) {
    CHECK(t[static_cast<std::size_t>(k) + 1] ==
          doctest::Approx(-1.0 + 4.0 * (k + alpha) / 32).epsilon(1e-15));
    CHECK(t[static_cast<std::size_t>(k) + 1] > t[static_cast<std::size_t>(k)]);
  }
  CHECK(cs::rounding_tolerance(1.0) == 256 * 0x1p-52);
  CHECK(cs::rounding_tolerance(1e6) == 256 * 0x1p-52 * 1e6);
  CHECK(cs::declared_limit(1e-12, 2.0) == 2e-6);
  CHECK(cs::declared_limit(1e-3, 2.0) == 1e-3);
}

TEST_CASE("closure sampling: the extent of the points added") {
  cs::Extent e;
  CHECK(e.size() == 0.0);
  e.add({1, -2, 0.5});
  CHECK(e.size() == 0.0);
  e.add({4, 2, 0.5});
  e.add({2, 0, -11.5});
  CHECK(e.magnitude == 11.5);
  CHECK(e.lo.x == 1.0);
  CHECK(e.hi.y == 2.0);
  CHECK(e.size() == 13.0);  // the box [1, 4] x [-2, 2] x [-11.5, 0.5]: √(9 + 16 + 144)
}

TEST_CASE("closure sampling: rigorous bounds of a norm and a difference") {
  const double b = cs::norm_bound(3, 4, 12);
  CHECK(b >= 13.0);
  CHECK(b <= 13.0 * (1 + 40 * 0x1p-52));
  CHECK(cs::norm_bound(0, 0, 0) == 0.0);
  CHECK(std::isnan(cs::norm_bound(NAN, 1, 1)));
  // Far beyond the squares' range (1e200^2 overflows) and far below it (1e-200^2 underflows).
  CHECK(cs::norm_bound(3e200, 4e200, 0) >= 5e200);
  CHECK(cs::norm_bound(3e200, 4e200, 0) <= 5e200 * (1 + 40 * 0x1p-52));
  CHECK(cs::norm_bound(3e-200, 4e-200, 0) >= 5e-200);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0.0, 10.0);
  for (int trial = 0; trial < 1000; ++trial) {
    const double x = u(rng), y = u(rng), z = u(rng);
    const long double exact = std::sqrt(static_cast<long double>(x) * x + static_cast<long double>(y) * y +
                                        static_cast<long double>(z) * z);
    CHECK(static_cast<long double>(cs::norm_bound(x, y, z)) >= exact);
  }
  CHECK(cs::difference_bound(1.0, 1.0) == 0.0);
  CHECK(cs::difference_bound(1.0, 0.25) > 0.75);
  // The bound holds the exact difference of the two doubles (exact in long double's 64 bits).
  const long double exact_difference = static_cast<long double>(0.3) - static_cast<long double>(0.1);
  CHECK(static_cast<long double>(cs::difference_bound(0.1, 0.3)) >= exact_difference);
  CHECK(cs::format(1234.5678) == "1.23e+03");
  CHECK(cs::format(0.000123456) == "0.000123");
}
