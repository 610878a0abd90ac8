// The capsules that bound the arcs of proved cells (implicit/seeding/curve_cell_proof: ArcCapsule) and the
// rigorous distance to a segment they are measured with (geometry/segment_distance): the segment
// distance against closed forms and a long double evaluation; every capsule holding its arc,
// against the parametrisations of Viviani's curve and of an ellipse, sampled densely through every
// proved cell of their discovery.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <span>
#include <vector>

#include "geometry/compile_budget.hpp"
#include "geometry/segment_distance.hpp"
#include "implicit/seeding/curve_discovery.hpp"
#include "implicit_fixtures.hpp"

using namespace footpoint;
using namespace footpoint::test;

namespace {

// |p - [a, b]| in long double: the nearest point's parameter clamped to [0, 1].
long double segment_distance_long(Vec3 p, Vec3 a, Vec3 b) {
  long double w[3], v[3], wv = 0, vv = 0;
  for (int k = 0; k < 3; ++k) {
    w[k] = static_cast<long double>(p[k]) - a[k];
    v[k] = static_cast<long double>(b[k]) - a[k];
    wv += w[k] * v[k];
    vv += v[k] * v[k];
  }
  const long double t = vv > 0 ? std::clamp(wv / vv, 0.0L, 1.0L) : 0.0L;
  long double s = 0;
  for (int k = 0; k < 3; ++k) s += (w[k] - t * v[k]) * (w[k] - t * v[k]);
  return std::sqrt(s);
}

// Every point of `curve` (samples of a parametrisation) inside a proved cell lies within the
// radius of one of the cell's capsules, and in the cell's item box of the certificate's tree (the
// part of the cell the capsules reach); returns the median of radius / cell edge.
double check_capsules_hold(const CurveDiscovery& d, const std::vector<Vec3>& curve) {
  std::vector<double> ratios;
  int checked_cells = 0;
  std::vector<Box3> item_box(d.cells.cells.size());
  for (const CellItem& it : d.tree.items())
    if (it.kind == CellItemKind::proved_cell) item_box[static_cast<std::size_t>(it.index)] = it.box;
  for (std::size_t c = 0; c < d.cells.cells.size(); ++c) {
    const ProvedCell& cell = d.cells.cells[c];
    const std::span<const ArcCapsule> capsules = d.cells.arc_capsules(c);
    REQUIRE(static_cast<int>(capsules.size()) * 2 == cell.crossing_count);
    for (const ArcCapsule& capsule : capsules) ratios.push_back(capsule.radius / cell.box.max_edge());
    int inside = 0;
    for (const Vec3& x : curve) {
      if (!cell.box.contains(x)) continue;
      ++inside;
      long double nearest = INFINITY, radius = 0;
      for (const ArcCapsule& capsule : capsules) {
        const long double gap = segment_distance_long(x, capsule.a, capsule.b) - capsule.radius;
        if (gap < nearest) nearest = gap, radius = capsule.radius;
      }
      // The samples are the curve's points to a few ulps of their coordinates.
      INFO("cell [" << cell.box.lo.x << ", " << cell.box.hi.x << "] x [" << cell.box.lo.y << ", "
                    << cell.box.hi.y << "] x [" << cell.box.lo.z << ", " << cell.box.hi.z << "], radius "
                    << double(radius));
      REQUIRE(nearest <= 1e-14L);
      REQUIRE(item_box[c].contains(x, 1e-14));
    }
    for (int k = 0; k < 3; ++k) {
      REQUIRE(item_box[c].lo[k] >= cell.box.lo[k]);
      REQUIRE(item_box[c].hi[k] <= cell.box.hi[k]);
    }
    checked_cells += inside > 0;
  }
  // The samples are dense enough to reach nearly every cell.
  CHECK(checked_cells >= static_cast<int>(0.95 * static_cast<double>(d.cells.cells.size())));
  std::sort(ratios.begin(), ratios.end());
  return ratios[ratios.size() / 2];
}

}  // namespace

TEST_CASE("segment_distance_lower_bound: the nearest point at either end or inside, against closed forms") {
  const Vec3 a{0.0, 0.0, 0.0}, b{4.0, 0.0, 0.0};
  const auto near = [](double lower, double exact) {
    CHECK(lower <= exact);
    CHECK(lower >= exact * (1.0 - 1e-12));
  };
  near(segment_distance_lower_bound({1.0, 3.0, 0.0}, a, b), 3.0);     // the perpendicular's foot
  near(segment_distance_lower_bound({-3.0, 0.0, 4.0}, a, b), 5.0);    // beyond a
  near(segment_distance_lower_bound({7.0, 4.0, 0.0}, a, b), 5.0);     // beyond b
  near(segment_distance_lower_bound({2.0, 2.0, 1.0}, a, a), 3.0);     // a segment of one point
  CHECK(segment_distance_lower_bound({2.0, 0.0, 0.0}, a, b) == 0.0);  // on it
  // A tilted segment far from the origin: (1e6 + s, 1e6 + s, 0), s in [0, 1]; the point lies
  // 1/sqrt(2) off its middle.
  near(segment_distance_lower_bound({1e6 + 1.0, 1e6, 0.0}, {1e6, 1e6, 0.0}, {1e6 + 1.0, 1e6 + 1.0, 0.0}),
       std::sqrt(0.5));
}

TEST_CASE(
    "segment_distance_lower_bound: never above the distance, within 1e-12 of it (random, long double)") {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::uniform_real_distribution<double> scale_exp(-8.0, 8.0);
  for (int n = 0; n < 20000; ++n) {
    const double s = std::pow(10.0, scale_exp(rng));
    const Vec3 a{s * u(rng), s * u(rng), s * u(rng)};
    // Short and long segments, points near the line (ends and middle) and far from it.
    const double len = s * std::pow(10.0, -4.0 * std::fabs(u(rng)));
    const Vec3 b = a + Vec3{len * u(rng), len * u(rng), len * u(rng)};
    const double off = s * std::pow(10.0, -6.0 * std::fabs(u(rng)));
    const double t = 1.5 * u(rng);
    const Vec3 p = a + t * (b - a) + Vec3{off * u(rng), off * u(rng), off * u(rng)};
    const long double exact = segment_distance_long(p, a, b);
    const double lower = segment_distance_lower_bound(p, a, b);
    INFO("a " << a.x << " " << a.y << " " << a.z << ", b " << b.x << " " << b.y << " " << b.z << ", p " << p.x
              << " " << p.y << " " << p.z);
    REQUIRE(static_cast<long double>(lower) <= exact);
    // The allowance is relative to |p - a| and |b - a|, not to the distance.
    const double scale = norm(p - a) + norm(b - a);
    CHECK(static_cast<long double>(lower) >= exact - 1e-12L * scale);
  }
}

TEST_CASE("arc capsules hold their arcs: Viviani's curve, every proved cell") {
  // Sphere |X| = 2 and cylinder (x - 1)^2 + y^2 = 1: X(t) = (1 + cos t, sin t, 2 sin(t / 2)),
  // t in [0, 4 pi), through its double point (2, 0, 0) at t = 0 and 2 pi.
  const ImplicitEquations eq = spatial_equations("x^2+y^2+z^2-4", "(x-1)^2+y^2-1");
  CompileBudget budget;
  const CurveDiscovery d = discover_implicit_curve(eq, {{-3.0, -3.0, -3.0}, {3.0, 3.0, 3.0}}, budget);
  REQUIRE(d.cells.cells.size() > 100);
  REQUIRE(d.cells.capsules.size() * 2 == d.cells.crossings.size());
  REQUIRE(d.cells.capsule_begin.size() == d.cells.cells.size() + 1);
  std::vector<Vec3> curve;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    const double t = 4.0 * M_PI * (i + 0.5) / n;
    curve.push_back({1.0 + std::cos(t), std::sin(t), 2.0 * std::sin(0.5 * t)});
  }
  // Most are far thinner than their cells: what makes them worth testing before the cells'
  // enclosures (near the double point, where T is small, they are not).
  const double median = check_capsules_hold(d, curve);
  MESSAGE("median radius / cell edge " << median);
  CHECK(median < 0.05);
}

TEST_CASE("arc capsules hold their arcs: an ellipse, every proved cell") {
  // x^2 / 4 + y^2 = 1: (2 cos t, sin t).
  const ImplicitEquations eq = planar_equations("x^2/4+y^2-1");
  CompileBudget budget;
  const CurveDiscovery d = discover_implicit_curve(eq, {{-3.0, -2.0, 0.0}, {3.0, 2.0, 0.0}}, budget);
  REQUIRE(d.cells.cells.size() > 20);
  std::vector<Vec3> curve;
  const int n = 100000;
  for (int i = 0; i < n; ++i) {
    const double t = 2.0 * M_PI * (i + 0.5) / n;
    curve.push_back({2.0 * std::cos(t), std::sin(t), 0.0});
  }
  const double median = check_capsules_hold(d, curve);
  MESSAGE("median radius / cell edge " << median);
  CHECK(median < 0.05);
}
