// seeding/point_index: the k-d tree's nearest point and its "a point other than s within radius of
// s is nearer to q" query, against a brute-force scan of the same points (random clouds, a grid
// with ties, clustered points), and an index that stays valid where its owner moves it.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <memory>
#include <random>
#include <vector>

#include "seeding/point_index.hpp"

using footpoint::PointIndex;
using footpoint::Vec3;

namespace {

// The least |p - x|^2 over the points (a brute-force scan).
double point_index_least_distance2(const std::vector<Vec3>& points, Vec3 p) {
  double best = INFINITY;
  for (const Vec3& x : points) best = std::min(best, norm2(p - x));
  return best;
}

bool point_index_brute_nearer_within(const std::vector<Vec3>& points, Vec3 s, double radius, Vec3 q,
                                     double distance2) {
  for (const Vec3& t : points) {
    if (t.x == s.x && t.y == s.y && t.z == s.z) continue;
    if (norm2(t - s) <= radius * radius && norm2(q - t) < distance2) return true;
  }
  return false;
}

std::vector<Vec3> point_index_cloud(std::mt19937_64& rng, int count, double spread) {
  std::uniform_real_distribution<double> u(-spread, spread);
  std::vector<Vec3> points;
  for (int i = 0; i < count; ++i) points.push_back({u(rng), u(rng), u(rng)});
  return points;
}

}  // namespace

TEST_CASE("point index: no points, then one") {
  const PointIndex empty(std::vector<Vec3>{});
  double d2 = -1.0;
  CHECK(empty.nearest({1, 2, 3}, d2) == -1);
  CHECK_FALSE(empty.nearer_within({0, 0, 0}, 10.0, {0, 0, 0}, 100.0));
  const PointIndex one(std::vector<Vec3>{{1, 2, 2}});
  CHECK(one.nearest({0, 0, 0}, d2) == 0);
  CHECK(d2 == 9.0);
  // The only point is s itself: no other point can be nearer.
  CHECK_FALSE(one.nearer_within({1, 2, 2}, 5.0, {1, 2, 2}, 1.0));
}

TEST_CASE("point index: the nearest point is the brute force's, on random clouds") {
  std::mt19937_64 rng(20261206);
  for (const int count : {2, 17, 1000, 5000}) {
    const std::vector<Vec3> points = point_index_cloud(rng, count, 3.0);
    const PointIndex index(points);
    std::uniform_real_distribution<double> q(-5.0, 5.0);
    for (int trial = 0; trial < 300; ++trial) {
      const Vec3 p{q(rng), q(rng), q(rng)};
      double d2 = -1.0;
      const std::int32_t i = index.nearest(p, d2);
      REQUIRE(i >= 0);
      REQUIRE(i < count);
      CHECK(d2 == norm2(p - points[static_cast<std::size_t>(i)]));
      CHECK(d2 == point_index_least_distance2(points, p));
    }
  }
}

TEST_CASE("point index: ties on a grid give a nearest point at the least distance") {
  std::vector<Vec3> grid;
  for (int x = 0; x < 6; ++x)
    for (int y = 0; y < 6; ++y)
      for (int z = 0; z < 6; ++z) grid.push_back({double(x), double(y), double(z)});
  const PointIndex index(grid);
  // The centre of a grid cube is equally near to its eight corners: distance2 3/4.
  double d2 = 0.0;
  const std::int32_t i = index.nearest({2.5, 3.5, 1.5}, d2);
  CHECK(d2 == 0.75);
  const Vec3 corner = grid[static_cast<std::size_t>(i)];
  CHECK(std::abs(corner.x - 2.5) == 0.5);
  CHECK(std::abs(corner.y - 3.5) == 0.5);
  CHECK(std::abs(corner.z - 1.5) == 0.5);
  // Far outside: the nearest corner of the grid, (5, 0, 5), at distance2 1 + 4 + 9.
  CHECK(grid[static_cast<std::size_t>(index.nearest({6, -2, 8}, d2))].x == 5.0);
  CHECK(d2 == 14.0);
}

TEST_CASE("point index: nearer_within agrees with the brute force") {
  std::mt19937_64 rng(7);
  const std::vector<Vec3> points = point_index_cloud(rng, 2000, 1.0);
  const PointIndex index(points);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int found = 0, trials = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const Vec3 s = points[static_cast<std::size_t>(trial * 5)];
    const double radius = 0.05 + 0.3 * unit(rng);
    const Vec3 q{2 * unit(rng) - 1, 2 * unit(rng) - 1, 2 * unit(rng) - 1};
    const double distance2 = norm2(q - s) * (0.2 + unit(rng));
    const bool expected = point_index_brute_nearer_within(points, s, radius, q, distance2);
    CHECK(index.nearer_within(s, radius, q, distance2) == expected);
    found += expected ? 1 : 0;
    ++trials;
  }
  // Both answers occur: the queries are not all one way.
  CHECK(found > 20);
  CHECK(found < trials - 20);
}

TEST_CASE("point index: the radius is inclusive and s itself never counts") {
  const std::vector<Vec3> points{{0, 0, 0}, {1, 0, 0}, {0, 3, 0}};
  const PointIndex index(points);
  // (1, 0, 0) is at exactly radius 1 from s = 0 and at distance2 0 < 0.5 from q = (1, 0, 0).
  CHECK(index.nearer_within({0, 0, 0}, 1.0, {1, 0, 0}, 0.5));
  // Just outside the radius it is not seen; (0, 3, 0) is too far as well.
  CHECK_FALSE(index.nearer_within({0, 0, 0}, 0.999, {1, 0, 0}, 0.5));
  // s = q = (1, 0, 0): the point at s is skipped, and the origin is at distance2 1, not < 1.
  CHECK_FALSE(index.nearer_within({1, 0, 0}, 2.0, {1, 0, 0}, 1.0));
  CHECK(index.nearer_within({1, 0, 0}, 2.0, {1, 0, 0}, 1.0000001));
}

TEST_CASE("point index: moved with its owner, it still answers from its own copy") {
  std::vector<Vec3> points{{0, 0, 0}, {10, 0, 0}};
  auto index = std::make_unique<PointIndex>(points);
  points.clear();  // the index keeps a copy
  auto moved = std::move(index);
  double d2 = 0.0;
  CHECK(moved->nearest({9, 0, 0}, d2) == 1);
  CHECK(d2 == 1.0);
  CHECK(moved->memory_bytes() >= 2 * sizeof(Vec3));
}
