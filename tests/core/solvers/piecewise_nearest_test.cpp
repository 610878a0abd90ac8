// The branch and bound over pieces (core/solvers/piecewise_nearest.hpp) on geometries made of
// straight segments, each piece a compiled parametric curve solved by its own `auto`. The truth
// is the segments' closed form (the nearest point of [a, b] to p is a + clamp(<p - a, b - a> /
// |b - a|^2, 0, 1) (b - a)), the minimum over all of them the brute force. Checked: the answer is
// that minimum, exactly the pieces whose boxes are nearer than it are solved (no more than those
// within the gap), the cutoff never falls below it, the certificate's bound is below it, ties on
// separate pieces are reported with both feet, a foot on two pieces' shared end is one foot, the
// minima under all_minima are merged, max_distance leaves every piece out; the box bound and the
// tree of boxes on their own.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "compile_definition.hpp"
#include "solvers/piecewise_nearest.hpp"

using namespace footpoint;

namespace piecewise_nearest_test {

struct Segment {
  Vec3 a, b;
};

// The closed-form nearest point of the segment to p.
Vec3 nearest_on(const Segment& s, const Vec3& p) {
  const Vec3 d = s.b - s.a;
  const double t = std::clamp(dot(p - s.a, d) / dot(d, d), 0.0, 1.0);
  return s.a + t * d;
}

std::string number(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", x);
  return text;
}

// The segments as compiled parametric curves over t in [0, 1], with their bounding boxes.
struct Pieces {
  std::vector<Segment> segments;
  std::vector<std::shared_ptr<const CompiledGeometry>> curves;
  PieceTree tree;

  explicit Pieces(std::vector<Segment> s) : segments(std::move(s)) {
    std::vector<Box3> boxes;
    for (const Segment& seg : segments) {
      std::vector<formula::NamedFormula> formulas;
      const char* names[3] = {"x", "y", "z"};
      for (int k = 0; k < 3; ++k)
        formulas.push_back(
            {names[k], number(seg.a[k]) + "+t*(" + number(seg.b[k]) + "-(" + number(seg.a[k]) + "))"});
      curves.push_back(
          test::compile_definition(GeometryType::parametric_curve, formulas, {{"t", {0.0, 1.0}}}));
      boxes.push_back({min(seg.a, seg.b), max(seg.a, seg.b)});
    }
    tree = PieceTree(std::move(boxes));
  }

  double brute_force(const Vec3& p) const {
    double best = std::numeric_limits<double>::infinity();
    for (const Segment& s : segments) best = std::min(best, norm(p - nearest_on(s, p)));
    return best;
  }

  // nearest_over_pieces with each piece's `auto`; `solved` records the pieces it asked for and
  // `lowest_cutoff` the least cutoff it passed.
  PiecewiseNearest nearest(const Vec3& p, const Options& options, std::vector<std::size_t>* solved = nullptr,
                           double* lowest_cutoff = nullptr) const {
    return nearest_over_pieces(tree, p, options, [&](std::size_t k, const Options& o, double cutoff) {
      if (solved) solved->push_back(k);
      if (lowest_cutoff) *lowest_cutoff = std::min(*lowest_cutoff, cutoff);
      const std::array<double, 3> at{p.x, p.y, p.z};
      return curves[k]->project(at.data(), "auto", o).value();
    });
  }
};

// A zigzag chain of 12 segments in space, each sharing its ends with its neighbours.
std::vector<Segment> zigzag() {
  std::vector<Segment> s;
  const auto vertex = [](int k) { return Vec3{1.0 * k, (k % 2) * 1.5, 0.5 * (k % 3)}; };
  for (int k = 0; k < 12; ++k) s.push_back({vertex(k), vertex(k + 1)});
  return s;
}

}  // namespace piecewise_nearest_test

TEST_CASE(
    "piecewise nearest: the nearest of the segments, solving exactly the pieces whose boxes are nearer") {
  const piecewise_nearest_test::Pieces pieces(piecewise_nearest_test::zigzag());
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> x(-3.0, 15.0), yz(-3.0, 4.0);
  for (int i = 0; i < 40; ++i) {
    const Vec3 p{x(rng), yz(rng), yz(rng)};
    CAPTURE(p.x);
    CAPTURE(p.y);
    CAPTURE(p.z);
    const double truth = pieces.brute_force(p);
    std::vector<std::size_t> solved;
    double lowest_cutoff = std::numeric_limits<double>::infinity();
    const PiecewiseNearest out = pieces.nearest(p, {}, &solved, &lowest_cutoff);
    const ProjectionResult& r = out.result;
    REQUIRE(r.summary.status == Status::converged);
    CHECK(std::abs(r.distance - truth) <= 1e-12 * (1.0 + truth));
    // The foot is the closed-form foot on the piece named.
    const Vec3 foot = piecewise_nearest_test::nearest_on(pieces.segments[out.piece], p);
    CHECK(std::abs(r.foot[0] - foot.x) + std::abs(r.foot[1] - foot.y) + std::abs(r.foot[2] - foot.z) <=
          1e-12);
    CHECK(out.pieces_solved == static_cast<int>(solved.size()));
    // Best first: every piece whose box is nearer than the answer was solved; none whose box is
    // farther than the answer plus the gap (1e-9 relative at most here) was.
    for (std::size_t k = 0; k < pieces.segments.size(); ++k) {
      CAPTURE(k);
      const double lower = distance_lower_bound(pieces.tree.hull(k), p);
      const bool was_solved = std::count(solved.begin(), solved.end(), k) == 1;
      if (lower < truth * (1 - 1e-6)) CHECK(was_solved);
      if (lower > truth * (1 + 1e-6) + 1e-9) CHECK_FALSE(was_solved);
    }
    // The cutoff is the best so far plus the gap: never below the minimum.
    CHECK(lowest_cutoff >= truth * (1 - 1e-12));
    // The pieces' certificates combined: a rigorous bound below the minimum, met.
    CHECK(r.summary.certificate.computed);
    CHECK(r.summary.certificate.lower_bound <= truth * (1 + 1e-12));
    CHECK(r.summary.certificate.certified);
  }
  // Near the chain's first end: the pieces far along it are left out.
  std::vector<std::size_t> solved;
  const PiecewiseNearest near_start = pieces.nearest({-2.0, 0.0, 0.0}, {}, &solved);
  CHECK(near_start.result.distance == doctest::Approx(2.0).epsilon(1e-12));
  CHECK(near_start.piece == 0);
  CHECK(solved.size() <= 3);
}

TEST_CASE("piecewise nearest: equal distances on two pieces are a tie; a shared end is one foot") {
  // Two parallel segments at y = 1 and y = -1: from the origin both are at distance 1.
  const piecewise_nearest_test::Pieces parallel({{{-1, 1, 0}, {1, 1, 0}}, {{-1, -1, 0}, {1, -1, 0}}});
  const ProjectionResult tie = parallel.nearest({0.0, 0.0, 0.0}, {}).result;
  CHECK(tie.distance == doctest::Approx(1.0).epsilon(1e-12));
  REQUIRE(tie.summary.multiplicity.computed);
  CHECK(tie.summary.multiplicity.kind == Multiplicity::tied);
  REQUIRE(tie.summary.multiplicity.count == 2);
  REQUIRE(tie.summary.multiplicity.feet.size() == 2);
  std::vector<double> ys{tie.summary.multiplicity.feet[0][1], tie.summary.multiplicity.feet[1][1]};
  std::sort(ys.begin(), ys.end());
  CHECK(ys[0] == doctest::Approx(-1.0).epsilon(1e-12));
  CHECK(ys[1] == doctest::Approx(1.0).epsilon(1e-12));
  // Off the middle plane the nearer one alone.
  const ProjectionResult one = parallel.nearest({0.0, 0.25, 0.0}, {}).result;
  CHECK(one.distance == doctest::Approx(0.75).epsilon(1e-12));
  CHECK(one.summary.multiplicity.kind == Multiplicity::unique);

  // An L of two segments meeting at (1, 0, 0): from (2, -1, 0) the corner is nearest on both,
  // at sqrt(2), one foot.
  const piecewise_nearest_test::Pieces corner({{{0, 0, 0}, {1, 0, 0}}, {{1, 0, 0}, {1, 1, 0}}});
  std::vector<std::size_t> solved;
  const ProjectionResult at_corner = corner.nearest({2.0, -1.0, 0.0}, {}, &solved).result;
  CHECK(solved.size() == 2);
  CHECK(at_corner.distance == doctest::Approx(std::sqrt(2.0)).epsilon(1e-12));
  CHECK(at_corner.summary.multiplicity.kind == Multiplicity::unique);
  CHECK(std::abs(at_corner.foot[0] - 1.0) + std::abs(at_corner.foot[1]) <= 1e-12);
}

TEST_CASE("piecewise nearest: all_minima solves every piece and lists a shared minimum once, best first") {
  // A U: (0, 2) -> (0, 0) -> (3, 0) -> (3, 2). From (1, 1): the bottom at distance 1, the left
  // side at 1, the right side at 2; each a minimum of its piece, none at a shared corner.
  const piecewise_nearest_test::Pieces u(
      {{{0, 2, 0}, {0, 0, 0}}, {{0, 0, 0}, {3, 0, 0}}, {{3, 0, 0}, {3, 2, 0}}});
  Options options;
  options.all_minima = true;
  std::vector<std::size_t> solved;
  const ProjectionResult r = u.nearest({1.0, 1.0, 0.0}, options, &solved).result;
  CHECK(solved.size() == 3);
  REQUIRE(r.minima.size() == 3);
  CHECK(r.minima[0].distance == doctest::Approx(1.0).epsilon(1e-12));
  CHECK(r.minima[1].distance == doctest::Approx(1.0).epsilon(1e-12));
  CHECK(r.minima[2].distance == doctest::Approx(2.0).epsilon(1e-12));
  CHECK(r.minima[2].foot[0] == doctest::Approx(3.0).epsilon(1e-12));
  CHECK(r.minima[2].foot[1] == doctest::Approx(1.0).epsilon(1e-12));
  // From (4, -1) the corner (3, 0) is the minimum of the bottom and of the right side: once.
  const ProjectionResult c = u.nearest({4.0, -1.0, 0.0}, options).result;
  const auto at_corner = std::count_if(c.minima.begin(), c.minima.end(), [](const Minimum& m) {
    return std::abs(m.foot[0] - 3.0) + std::abs(m.foot[1]) <= 1e-9;
  });
  CHECK(at_corner == 1);
  CHECK(c.minima.front().distance == doctest::Approx(std::sqrt(2.0)).epsilon(1e-12));
}

TEST_CASE("piecewise nearest: every box beyond max_distance gives beyond_max_distance, nothing solved") {
  const piecewise_nearest_test::Pieces pieces(piecewise_nearest_test::zigzag());
  Options options;
  options.max_distance = 1.5;
  std::vector<std::size_t> solved;
  // (-3, 0, 0) is 3 from the chain's first end, its nearest box corner.
  const PiecewiseNearest out = pieces.nearest({-3.0, 0.0, 0.0}, options, &solved);
  CHECK(solved.empty());
  CHECK(out.pieces_solved == 0);
  CHECK(out.result.summary.status == Status::beyond_max_distance);
  CHECK(std::isnan(out.result.distance));
  // Within reach again.
  options.max_distance = 3.5;
  const PiecewiseNearest near = pieces.nearest({-3.0, 0.0, 0.0}, options);
  CHECK(near.result.summary.status == Status::converged);
  CHECK(near.result.distance == doctest::Approx(3.0).epsilon(1e-12));
}

TEST_CASE("piecewise nearest: the box bound and the tree of boxes") {
  const Box3 box{{0, 0, 0}, {1, 2, 3}};
  CHECK(distance_lower_bound(box, {0.5, 1.0, 1.5}) == 0.0);  // inside
  CHECK(distance_lower_bound(box, {1.0, 2.0, 3.0}) == 0.0);  // on a corner
  // Off a face, an edge, a corner: the Euclidean distance to the box, rounded down by < 1e-14.
  for (const auto& [p, d] : std::vector<std::pair<Vec3, double>>{
           {{4.0, 1.0, 1.0}, 3.0}, {{-3.0, -4.0, 1.0}, 5.0}, {{2.0, 4.0, 5.0}, 3.0}}) {
    const double bound = distance_lower_bound(box, p);
    CHECK(bound <= d);
    CHECK(bound >= d * (1 - 1e-14));
  }
  // The tree: every node's box holds its children's, the leaves hold every piece once, in order_.
  std::vector<Box3> boxes;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> c(-10.0, 10.0), size(0.0, 2.0);
  for (int k = 0; k < 37; ++k) {
    const Vec3 lo{c(rng), c(rng), c(rng)};
    boxes.push_back({lo, lo + Vec3{size(rng), size(rng), size(rng)}});
  }
  const PieceTree tree(boxes);
  CHECK(tree.size() == 37);
  const auto holds = [](const Box3& outer, const Box3& inner) {
    for (int k = 0; k < 3; ++k)
      if (inner.lo[k] < outer.lo[k] || inner.hi[k] > outer.hi[k]) return false;
    return true;
  };
  std::vector<int> seen(boxes.size(), 0);
  for (const PieceTree::Node& node : tree.nodes()) {
    for (std::int32_t i = node.first; i < node.first + node.count; ++i)
      CHECK(holds(node.box, boxes[static_cast<std::size_t>(tree.order()[static_cast<std::size_t>(i)])]));
    if (node.child[0] < 0) {
      for (std::int32_t i = node.first; i < node.first + node.count; ++i)
        ++seen[static_cast<std::size_t>(tree.order()[static_cast<std::size_t>(i)])];
    } else {
      for (const std::int32_t child : node.child)
        CHECK(holds(node.box, tree.nodes()[static_cast<std::size_t>(child)].box));
    }
  }
  for (const int s : seen) CHECK(s == 1);
}
