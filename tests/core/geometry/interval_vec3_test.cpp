// geometry/interval_vec3: the box distance bound never exceeds the exact distance (computed in long
// double) and is within a few ulps of it; the interval dot and cross products hold the products of
// points of their operands.
#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "geometry/interval_vec3.hpp"

using namespace footpoint;

TEST_CASE("distance_lower_bound: below the exact distance to the box, and tight") {
  std::mt19937_64 rng(31);
  std::uniform_real_distribution<double> u(-10.0, 10.0), e(0.0, 2.0);
  for (int i = 0; i < 100000; ++i) {
    const Vec3 p{u(rng), u(rng), u(rng)};
    Box3 b;
    for (int k = 0; k < 3; ++k) {
      b.lo[k] = u(rng);
      b.hi[k] = b.lo[k] + e(rng);
    }
    long double s = 0.0L;
    for (int k = 0; k < 3; ++k) {
      long double g = 0.0L;
      if (p[k] < b.lo[k]) g = static_cast<long double>(b.lo[k]) - p[k];
      if (p[k] > b.hi[k]) g = static_cast<long double>(p[k]) - b.hi[k];
      s += g * g;
    }
    const long double exact = std::sqrt(s);
    const double bound = distance_lower_bound(p, b);
    CHECK(static_cast<long double>(bound) <= exact);
    CHECK(static_cast<long double>(bound) >= exact * (1.0L - 1e-14L));
    CHECK(distance2_lower_bound(p, b) <= s);
  }
  // Inside the box: 0.
  CHECK(distance_lower_bound({0.5, 0.5, 0.5}, {{0, 0, 0}, {1, 1, 1}}) == 0.0);
  CHECK(square_upper_bound(0.1) >= 0.1L * 0.1L);
  // A NaN coordinate of the point claims nothing along its axis: the bound is that of the others.
  const double nan = std::nan("");
  CHECK(distance2_lower_bound({nan, 0.5, 0.5}, {{0, 0, 0}, {1, 1, 1}}) == 0.0);
  CHECK(distance2_lower_bound({nan, 3.0, 0.5}, {{0, 0, 0}, {1, 1, 1}}) <= 4.0);
  CHECK(distance2_lower_bound({nan, 3.0, 0.5}, {{0, 0, 0}, {1, 1, 1}}) >= 4.0 * (1.0 - 1e-14));
  CHECK(distance2_lower_bound({nan, nan, nan}, {{0, 0, 0}, {1, 1, 1}}) == 0.0);
}

TEST_CASE("interval dot and cross products hold the products of their points") {
  std::mt19937_64 rng(32);
  std::uniform_real_distribution<double> u(-3.0, 3.0), w(0.0, 1.0), t(0.0, 1.0);
  for (int i = 0; i < 20000; ++i) {
    IVec3 a, b;
    for (int k = 0; k < 3; ++k) {
      a[k].lo = u(rng);
      a[k].hi = a[k].lo + w(rng);
      b[k].lo = u(rng);
      b[k].hi = b[k].lo + w(rng);
    }
    Vec3 x, y;
    for (int k = 0; k < 3; ++k) {
      x[k] = a[k].lo + t(rng) * (a[k].hi - a[k].lo);
      y[k] = b[k].lo + t(rng) * (b[k].hi - b[k].lo);
    }
    const Interval d = ivec::dot(a, b);
    const long double exact = static_cast<long double>(x.x) * y.x + static_cast<long double>(x.y) * y.y +
                              static_cast<long double>(x.z) * y.z;
    CHECK(d.lo <= exact);
    CHECK(exact <= d.hi);
    const IVec3 c = ivec::cross(a, b);
    for (int k = 0; k < 3; ++k) {
      const int i1 = (k + 1) % 3, i2 = (k + 2) % 3;
      const long double ck =
          static_cast<long double>(x[i1]) * y[i2] - static_cast<long double>(x[i2]) * y[i1];
      CHECK(c[k].lo <= ck);
      CHECK(ck <= c[k].hi);
    }
  }
}
