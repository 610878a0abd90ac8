// parametric/solvers/bezier_patch_nearest: a polynomial Bézier patch's nearest point by its own
// branch and bound, against a closed form (a parabolic trough with two feet at the same distance:
// no unique answer may be claimed, and the B-spline `auto` reports the tie) and against the
// parametric engine's certified `auto` on the same pieces (options.trace keeps the B-spline
// surface on the engine's path), an implementation that shares no code with it. A rational patch:
// the Bernstein net of g_L = |A - pW|² - L W² against g_L evaluated from the patch's nets by this
// file's own Bernstein sums, the unit sphere's eight octants against | |p| - 1 |, and a rational
// bicubic (random weights) against the engine's `auto` as above.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <utility>
#include <vector>

#include "compiled/compiled_geometry.hpp"
#include "compiled/geometry_definition.hpp"
#include "parametric/solvers/bezier_patch_nearest.hpp"

using namespace footpoint;

namespace {

// z = x² over x in [-1, 1], y in [0, 1]: x = -1 + 2s has Bézier points -1, 0, 1 and x² the points
// 1, -1, 1 (the Bernstein coefficients of 4s² - 4s + 1); degree 1 in y.
GeometryDefinition trough() {
  GeometryDefinition def;
  def.type = GeometryType::bspline_surface;
  def.bspline.degree = {2, 1};
  def.bspline.knots = {{0, 0, 0, 1, 1, 1}, {0, 0, 1, 1}};
  const double x[3] = {-1.0, 0.0, 1.0}, z[3] = {1.0, -1.0, 1.0};
  for (int i = 0; i < 3; ++i) def.bspline.control_points.push_back({{x[i], 0.0, z[i]}, {x[i], 1.0, z[i]}});
  return def;
}

// A bicubic B-spline of 4 x 4 pieces on [0, 2]², heights a smooth bump plus noise (fixed seed);
// rational: weights drawn from [0.5, 2].
GeometryDefinition bumpy(std::mt19937& rng, bool rational = false) {
  std::uniform_real_distribution<double> noise(-0.1, 0.1);
  GeometryDefinition def;
  def.type = GeometryType::bspline_surface;
  def.bspline.degree = {3, 3};
  const std::vector<double> knots = {0, 0, 0, 0, 0.5, 1, 1.5, 2, 2, 2, 2};
  def.bspline.knots = {knots, knots};
  for (int i = 0; i < 7; ++i) {
    std::vector<std::vector<double>> row;
    for (int j = 0; j < 7; ++j) {
      const double x = i / 3.0, y = j / 3.0;
      row.push_back({x, y, 0.4 * std::sin(2.0 * x) * std::cos(1.5 * y) + noise(rng)});
    }
    def.bspline.control_points.push_back(row);
  }
  std::uniform_real_distribution<double> weight(0.5, 2.0);
  if (rational)
    for (int i = 0; i < 7; ++i) {
      def.bspline.weights.emplace_back();
      for (int j = 0; j < 7; ++j) def.bspline.weights.back().push_back(weight(rng));
    }
  return def;
}

// Σ_k C(n, k) x^k (1 - x)^(n - k) c_k of the coefficients c[k * stride] (the test's own sums).
double bernstein_sum(const double* c, int n, int stride, double x) {
  double sum = 0.0, binomial = 1.0;
  for (int k = 0; k <= n; ++k) {
    sum += binomial * std::pow(x, k) * std::pow(1.0 - x, n - k) * c[k * stride];
    binomial = binomial * (n - k) / (k + 1);
  }
  return sum;
}

// The tensor sum of a net of (n + 1) x (m + 1) coefficients (k along s) at (s, t).
double tensor_sum(const std::vector<double>& c, int n, int m, double s, double t) {
  std::vector<double> rows(static_cast<std::size_t>(n + 1));
  for (int k = 0; k <= n; ++k)
    rows[static_cast<std::size_t>(k)] = bernstein_sum(&c[static_cast<std::size_t>(k * (m + 1))], m, 1, t);
  return bernstein_sum(rows.data(), n, 1, s);
}

// The octant (sx x >= 0, sy y >= 0, sz z >= 0) of the unit sphere as one biquadratic rational
// patch: the quarter circle (1, 0), (1, 1), (0, 1) with weights 1, sqrt(1/2), 1 around the axis
// times the quarter meridian (radius, height) (1, 0), (1, 1), (0, 1) alike; homogeneous points.
BezierPatch octant(double sx, double sy, double sz) {
  const double h = std::sqrt(0.5);
  const double circle[3][2] = {{1, 0}, {1, 1}, {0, 1}}, meridian[3][2] = {{1, 0}, {1, 1}, {0, 1}};
  const double w[3] = {1.0, h, 1.0};
  std::vector<Vec3> net;
  std::vector<double> weights;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const double wij = w[i] * w[j];
      net.push_back(wij * Vec3{sx * circle[i][0] * meridian[j][0], sy * circle[i][1] * meridian[j][0],
                               sz * meridian[j][1]});
      weights.push_back(wij);
    }
  return BezierPatch(2, 2, std::move(net), std::move(weights));
}

}  // namespace

TEST_CASE("g_L's Bernstein net (the product of Bernstein forms) is g_L = |A - pW|² - L W²") {
  std::mt19937 rng(3535);
  std::uniform_real_distribution<double> coord(-1.0, 1.0), weight(0.3, 3.0), unit(0.0, 1.0);
  for (const std::pair<int, int>& degrees :
       {std::pair{2, 2}, std::pair{3, 2}, std::pair{1, 3}, std::pair{3, 3}}) {
    const int p = degrees.first, q = degrees.second;
    for (const bool rational : {false, true}) {
      std::vector<Vec3> net;
      std::vector<double> w, wx, wy, wz, ww;
      for (int k = 0; k < (p + 1) * (q + 1); ++k) {
        const double wk = rational ? weight(rng) : 1.0;
        const Vec3 point{coord(rng), coord(rng), coord(rng)};
        net.push_back(rational ? wk * point : point);
        if (rational) w.push_back(wk);
        wx.push_back(net.back().x);
        wy.push_back(net.back().y);
        wz.push_back(net.back().z);
        ww.push_back(wk);
      }
      const BezierPatch patch(p, q, net, w);
      const Vec3 x{2.0 * coord(rng), 2.0 * coord(rng), 2.0 * coord(rng)};
      const double L = unit(rng);
      const std::vector<double> g = distance_level_net(patch, x, L);
      REQUIRE(g.size() == static_cast<std::size_t>((2 * p + 1) * (2 * q + 1)));
      double least = g[0];
      for (const double c : g) least = std::min(least, c);
      for (int i = 0; i <= 6; ++i)
        for (int j = 0; j <= 6; ++j) {
          const double s = i / 6.0, t = j / 6.0;
          const double W = tensor_sum(ww, p, q, s, t);
          const Vec3 D{tensor_sum(wx, p, q, s, t) - x.x * W, tensor_sum(wy, p, q, s, t) - x.y * W,
                       tensor_sum(wz, p, q, s, t) - x.z * W};
          const double want = dot(D, D) - L * W * W;
          CAPTURE(p);
          CAPTURE(q);
          CAPTURE(rational);
          CHECK(std::abs(tensor_sum(g, 2 * p, 2 * q, s, t) - want) <=
                1e-12 * (1.0 + std::abs(want) + L * W * W));
          // The net's hull holds the polynomial's range.
          CHECK(least <= want + 1e-12);
          // The patch's own jet: S = A / W.
          const SurfaceJet jet = patch.jet(s, t);
          CHECK(std::abs(norm2(jet.s - x) * W * W - L * W * W - want) <= 1e-12 * (1.0 + std::abs(want)));
        }
    }
  }
}

TEST_CASE("the unit sphere's octants as rational patches: proved nearest points at | |p| - 1 |") {
  std::vector<BezierPatch> octants;
  for (const double sx : {-1.0, 1.0})
    for (const double sy : {-1.0, 1.0})
      for (const double sz : {-1.0, 1.0}) octants.push_back(octant(sx, sy, sz));
  std::mt19937 rng(35);
  std::uniform_real_distribution<double> coord(-2.0, 2.0);
  int points = 0, proved_at_foot = 0;
  for (int i = 0; i < 150; ++i) {
    const Vec3 p{coord(rng), coord(rng), coord(rng)};
    const double r = norm(p), want = std::abs(r - 1.0);
    if (r < 0.2) continue;
    ++points;
    CAPTURE(p.x);
    CAPTURE(p.y);
    CAPTURE(p.z);
    double best = std::numeric_limits<double>::infinity(), lower = best;
    bool all = true;
    for (const BezierPatch& o : octants) {
      const PatchNearest n = nearest_on_patch(o, p, 64);
      // The octant holding p / |p|: its points (sx, 0, 0), (0, sy, 0), (0, 0, sz) have p's signs.
      const bool holds = o.point(0).x * p.x > 0.0 && o.point(6).y * p.y > 0.0 && o.point(2).z * p.z > 0.0;
      if (holds) proved_at_foot += n.proved;
      if (!n.proved) {
        all = false;
        continue;
      }
      CHECK(n.lower_bound <= n.distance);
      CHECK(std::abs(n.distance - norm(n.jet.s - p)) <= 1e-15 * (1.0 + r));
      best = std::min(best, n.distance);
      lower = std::min(lower, n.lower_bound);
    }
    if (!all) continue;
    CHECK(std::abs(best - want) <= 1e-12 * (1.0 + r));
    CHECK(lower <= want * (1.0 + 1e-15));  // rigorous: never above the true distance
    CHECK(want - lower <= std::max(1e-9 * want, 1e-13));
  }
  CHECK(points > 120);
  CHECK(proved_at_foot >= points * 95 / 100);
}

TEST_CASE("a parabolic trough's two feet: no unique foot claimed; the B-spline auto finds the tie") {
  // p = (0, y, 1): f(x) = x² + (x² - 1)² is least at x² = 1/2, two feet at distance sqrt(3/4).
  const BezierPatch patch(2, 1, {{-1, 0, 1}, {-1, 1, 1}, {0, 0, -1}, {0, 1, -1}, {1, 0, 1}, {1, 1, 1}});
  const Vec3 p{0.0, 0.5, 1.0};
  const PatchNearest n = nearest_on_patch(patch, p);
  CHECK_FALSE(n.proved);

  const auto g = compile_geometry(trough());
  const double x[3] = {p.x, p.y, p.z};
  const ProjectionResult r = g->project(x, "auto", {}).value();
  CHECK(std::abs(r.distance - std::sqrt(0.75)) <= 1e-12);
  CHECK(r.summary.certificate.certified);
  CHECK(r.summary.multiplicity.kind == Multiplicity::tied);
  CHECK(r.summary.multiplicity.count == 2);
  CHECK(std::abs(std::abs(r.foot[0]) - std::sqrt(0.5)) <= 1e-9);

  // Off the axis the foot is unique, and the patch proves it: the nearer of the two.
  const Vec3 q{0.2, 0.5, 1.0};
  const PatchNearest m = nearest_on_patch(patch, q);
  REQUIRE(m.proved);
  CHECK(m.jet.s.x > 0.0);
  CHECK(m.lower_bound <= m.distance);
  CHECK(m.distance - m.lower_bound <= 1e-9 * m.distance);
}

TEST_CASE("the patches' branch and bound agrees with the engine's certified auto on every piece") {
  for (const bool rational : {false, true}) {
    CAPTURE(rational);
    std::mt19937 rng(35);
    const auto g = compile_geometry(bumpy(rng, rational));
    std::uniform_real_distribution<double> box(-0.8, 2.8), height(-1.2, 1.2);
    Options engine;
    engine.trace = true;  // the pieces' own `auto`, not their patches
    int points = 0, uncertified = 0;
    const int count = rational ? 60 : 150;
    for (int i = 0; i < count; ++i) {
      const double x[3] = {box(rng), box(rng), height(rng)};
      const ProjectionResult fast = g->project(x, "auto", {}).value();
      const ProjectionResult slow = g->project(x, "auto", engine).value();
      CAPTURE(x[0]);
      CAPTURE(x[1]);
      CAPTURE(x[2]);
      // Each lower bound holds for the other's answer.
      CHECK(fast.summary.certificate.lower_bound <= slow.distance * (1.0 + 1e-15));
      CHECK(slow.summary.certificate.lower_bound <= fast.distance * (1.0 + 1e-15));
      CHECK(fast.summary.certificate.certified);
      CHECK(std::abs(fast.distance - slow.distance) <= 1e-12 * (1.0 + slow.distance));
      if (!slow.summary.certificate.certified) {
        ++uncertified;  // the engine's enclosures of a rational piece may not reach the gap
        continue;
      }
      CHECK(fast.summary.multiplicity.kind == slow.summary.multiplicity.kind);
      CHECK(fast.summary.location == slow.summary.location);
      for (int k = 0; k < 3; ++k)
        CHECK(std::abs(fast.foot[k] - slow.foot[k]) <= 1e-9 * (1.0 + slow.distance));
      ++points;
    }
    CHECK(points + uncertified == count);
    CHECK(uncertified <= count / 10);
  }
}

TEST_CASE("an octant's pole: on the sphere's axis the pole is the proved nearest point") {
  for (const double sz : {-1.0, 1.0})
    for (const double z : {0.3, 0.5, 0.9, 1.2, 2.0, 5.0}) {
      const Vec3 p{0.0, 0.0, sz * z};
      CAPTURE(p.z);
      for (const double sx : {-1.0, 1.0})
        for (const double sy : {-1.0, 1.0}) {
          const BezierPatch o = octant(sx, sy, sz);
          CHECK(o.pole(3));  // t = 1: the meridian's end on the axis
          CHECK_FALSE(o.pole(0));
          const PatchNearest n = nearest_on_patch(o, p, 64);
          REQUIRE(n.proved);
          CHECK(n.pole);
          const double want = std::abs(1.0 - z);
          CHECK(std::abs(n.distance - want) <= 1e-15 * (1.0 + z));
          CHECK(n.lower_bound <= want * (1.0 + 1e-15));
          CHECK(want - n.lower_bound <= 1e-9 * want);
        }
    }
}

// A gently curved bicubic patch and points above, below and beside it at up to a few times its
// size: the sub-patches about the foot (the cluster the side points' Taylor forms bound) and those
// over which f is monotone towards the inside (dropped) must leave the nearest point and a bound
// below every point of the patch. The reference: the least distance over a 121 x 121 grid of the
// patch's points by this file's own Bernstein sums (at or above the least distance, within the
// grid's resolution of it).
TEST_CASE("a bicubic patch's nearest point and bound against a dense grid, with and without cutoff") {
  std::mt19937 rng(3535);
  std::uniform_real_distribution<double> bump(-0.08, 0.08);
  std::vector<Vec3> net;
  std::vector<double> xs, ys, zs;
  for (int k = 0; k <= 3; ++k)
    for (int l = 0; l <= 3; ++l) {
      net.push_back({0.5 * k / 3.0, 0.5 * l / 3.0, 0.1 * std::sin(2.0 * k) * std::cos(l) + bump(rng)});
      xs.push_back(net.back().x);
      ys.push_back(net.back().y);
      zs.push_back(net.back().z);
    }
  const BezierPatch patch(3, 3, net);
  std::uniform_real_distribution<double> across(-0.4, 0.9), height(-0.8, 0.8);
  int proved = 0;
  for (int i = 0; i < 40; ++i) {
    const Vec3 p{across(rng), across(rng), height(rng)};
    CAPTURE(p.x);
    CAPTURE(p.y);
    CAPTURE(p.z);
    double grid = std::numeric_limits<double>::infinity();
    for (int a = 0; a <= 120; ++a)
      for (int b = 0; b <= 120; ++b) {
        const double s = a / 120.0, t = b / 120.0;
        const Vec3 x{tensor_sum(xs, 3, 3, s, t), tensor_sum(ys, 3, 3, s, t), tensor_sum(zs, 3, 3, s, t)};
        grid = std::min(grid, norm(x - p));
      }
    const PatchNearest n = nearest_on_patch(patch, p);
    if (!n.proved) continue;  // a tie or a budget the engine's `auto` takes over
    ++proved;
    CHECK(n.lower_bound <= grid * (1.0 + 1e-12));
    CHECK(n.distance <= grid * (1.0 + 1e-12));
    CHECK(n.distance - n.lower_bound <= 1e-9 * n.distance + 1e-15);
    // A cutoff below the grid's least distance: no point within it, proved, or (the grid's
    // resolution above a point next to the patch) the nearest point; above: the nearest point.
    const PatchNearest below = nearest_on_patch(patch, p, 48, 0.9 * grid);
    if (below.proved) {
      CHECK((below.lower_bound > 0.9 * grid ||
             std::abs(below.distance - n.distance) <= 1e-12 * (1.0 + n.distance)));
      CHECK(below.lower_bound <= grid * (1.0 + 1e-12));
    }
    const PatchNearest above = nearest_on_patch(patch, p, 48, 1.1 * grid);
    if (above.proved) {
      CHECK(above.lower_bound <= grid * (1.0 + 1e-12));
      CHECK(std::abs(above.distance - n.distance) <= 1e-12 * (1.0 + n.distance));
    }
  }
  CHECK(proved >= 36);
}
