// seeding/curve_sample_index: the k-d tree's nearest sample and its discrete local minima of the
// distance along the curve, against a brute-force scan of the same samples.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "seeding/curve_sample_index.hpp"

using namespace footpoint;

namespace {

// Samples of two closed curves in space, each linked in a loop: a circle and a trefoil-like knot.
CurveSamples two_loops() {
  CurveSamples s;
  auto loop = [&](int n, auto point) {
    const std::int32_t first = static_cast<std::int32_t>(s.size());
    for (int k = 0; k < n; ++k) {
      const std::int32_t i = s.add(point(2.0 * M_PI * k / n));
      if (k > 0) s.link(i - 1, i);
    }
    s.link(static_cast<std::int32_t>(s.size()) - 1, first);
  };
  loop(400, [](double t) { return Vec3{std::cos(t), std::sin(t), 0.0}; });
  loop(900, [](double t) {
    return Vec3{std::sin(t) + 2 * std::sin(2 * t) + 4, std::cos(t) - 2 * std::cos(2 * t), -std::sin(3 * t)};
  });
  return s;
}

double d2(const CurveSamples& s, std::int32_t i, Vec3 p) {
  return norm2(p - s.points[static_cast<std::size_t>(i)]);
}

// The brute force: the discrete local minima within |p - nearest| + margin, nearest first.
std::vector<std::int32_t> local_minima(const CurveSamples& s, Vec3 p, double margin, double& nearest2) {
  nearest2 = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < s.size(); ++i)
    nearest2 = std::min(nearest2, d2(s, static_cast<std::int32_t>(i), p));
  const double r = std::sqrt(nearest2) + margin;
  std::vector<std::int32_t> out;
  for (std::size_t k = 0; k < s.size(); ++k) {
    const auto i = static_cast<std::int32_t>(k);
    const double di = d2(s, i, p);
    if (di > r * r) continue;
    if (s.prev[k] >= 0 && d2(s, s.prev[k], p) < di) continue;
    if (s.next[k] >= 0 && d2(s, s.next[k], p) < di) continue;
    out.push_back(i);
  }
  std::sort(out.begin(), out.end(),
            [&](std::int32_t a, std::int32_t b) { return d2(s, a, p) < d2(s, b, p); });
  return out;
}

}  // namespace

TEST_CASE("nearest: the k-d tree's nearest sample is the brute force's") {
  const CurveSamples s = two_loops();
  const CurveSampleIndex index(s);
  CHECK(&index.samples() == &s);
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-3.0, 8.0);
  for (int k = 0; k < 500; ++k) {
    const Vec3 p{u(rng), u(rng) * 0.5, u(rng) * 0.3};
    double found2 = 0.0;
    const std::int32_t i = index.nearest(p, found2);
    double best2 = 0.0;
    local_minima(s, p, 0.0, best2);
    REQUIRE(i >= 0);
    CHECK(found2 == best2);
    CHECK(d2(s, i, p) == best2);
  }
}

TEST_CASE("nearest_and_local_minima: the brute force's discrete local minima, nearest first") {
  const CurveSamples s = two_loops();
  const CurveSampleIndex index(s);
  std::mt19937_64 rng(12);
  std::uniform_real_distribution<double> u(-3.0, 8.0);
  for (const double margin : {0.0, 0.05, 0.5, std::numeric_limits<double>::infinity()}) {
    for (int k = 0; k < 200; ++k) {
      const Vec3 p{u(rng), u(rng) * 0.5, u(rng) * 0.3};
      SampleCandidates c;
      double nearest2 = 0.0;
      const std::int32_t nearest = index.nearest_and_local_minima(p, margin, c, nearest2);
      double best2 = 0.0;
      const std::vector<std::int32_t> expected = local_minima(s, p, margin, best2);
      CAPTURE(margin);
      CHECK(nearest2 == best2);
      CHECK(d2(s, nearest, p) == best2);
      // At most kMaxSampleCandidates are kept: the nearest ones.
      const std::size_t n = std::min<std::size_t>(expected.size(), kMaxSampleCandidates);
      REQUIRE(static_cast<std::size_t>(c.count) == n);
      for (std::size_t j = 0; j < n; ++j) {
        CHECK(c.items[j].distance2 == d2(s, expected[j], p));
        CHECK(c.items[j].distance2 == d2(s, c.items[j].index, p));
      }
    }
  }
}

TEST_CASE("an index over no samples answers -1") {
  const CurveSamples none;
  const CurveSampleIndex index(none);
  double d = 0.0;
  CHECK(index.nearest({1, 2, 3}, d) == -1);
  SampleCandidates c;
  CHECK(index.nearest_and_local_minima({1, 2, 3}, 1.0, c, d) == -1);
  CHECK(c.count == 0);
}
