// geometry/box3: the hull holds both boxes and is the least box that does, the intersection holds
// exactly the points in both (empty when they do not meet), against point membership on a grid.
#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "geometry/box3.hpp"

using namespace footpoint;

TEST_CASE("Box3 hull and intersection agree with point membership") {
  std::mt19937_64 rng(5);
  std::uniform_int_distribution<int> u(-4, 4);
  auto box = [&] {
    Box3 b;
    for (int k = 0; k < 3; ++k) {
      const int a = u(rng), c = u(rng);
      b.lo[k] = std::fmin(a, c);
      b.hi[k] = std::fmax(a, c);
    }
    return b;
  };
  for (int i = 0; i < 300; ++i) {
    const Box3 a = box(), b = box();
    const Box3 h = hull(a, b), m = intersection(a, b);
    CHECK(h.contains(a));
    CHECK(h.contains(b));
    // Least: every face of the hull touches one of the boxes.
    for (int k = 0; k < 3; ++k) {
      CHECK((h.lo[k] == a.lo[k] || h.lo[k] == b.lo[k]));
      CHECK((h.hi[k] == a.hi[k] || h.hi[k] == b.hi[k]));
    }
    CHECK(m.empty() == !a.intersects(b));
    // On the half-integer grid, which holds the boxes' faces: in both iff in the intersection.
    for (double x = -4.0; x <= 4.0; x += 0.5)
      for (double y = -4.0; y <= 4.0; y += 0.5)
        for (double z = -4.0; z <= 4.0; z += 0.5) {
          const Vec3 p{x, y, z};
          REQUIRE((a.contains(p) && b.contains(p)) == (!m.empty() && m.contains(p)));
        }
  }
  // A NaN bound makes a box empty; a flat box (a planar curve's z = 0) is not.
  CHECK(Box3{{0, 0, std::nan("")}, {1, 1, 1}}.empty());
  CHECK_FALSE(Box3{{0, 0, 0}, {1, 1, 0}}.empty());
}
