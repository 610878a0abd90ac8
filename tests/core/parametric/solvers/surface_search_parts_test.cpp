// The small pieces `auto` builds its search from, each against a plain computation:
//  - SurfaceCells::box_distances2: the four children's squared box distances of a search node (two
//    SSE2 lanes at a time), against the scalar formula, with empty slots and unbounded boxes;
//  - the search tree: every cell is a leaf of it exactly once, and every node's child boxes hold
//    the boxes below them; trees of one cell (no node) and of a few cells answer as the full one;
//  - every cell lies within ρ of the rectangle in its tangent plane (the tangent-plane rule's bound).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "surface_fixtures.hpp"

using namespace footpoint;
using namespace footpoint::test;

TEST_CASE("a search node's four box distances are the scalar ones") {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> U(-5.0, 5.0);
  constexpr double inf = std::numeric_limits<double>::infinity();
  for (int trial = 0; trial < 2000; ++trial) {
    SurfaceCellNode node;
    node.children = 2 + trial % 3;
    for (int k = 0; k < SurfaceCellNode::kWidth; ++k) {
      node.child[k] = k;
      for (int c = 0; c < 3; ++c) {
        double x = U(rng), y = U(rng);
        if (x > y) std::swap(x, y);
        if (trial % 7 == 0 && c == 1) x = -inf, y = inf;  // a non-finite enclosure: unbounded
        node.lo[c][k] = k < node.children ? x : inf;      // an empty slot
        node.hi[c][k] = k < node.children ? y : -inf;
      }
    }
    const Vec3 p{2.0 * U(rng), 2.0 * U(rng), 2.0 * U(rng)};
    double d2[SurfaceCellNode::kWidth];
    SurfaceCells::box_distances2(node, p, d2);
    for (int k = 0; k < SurfaceCellNode::kWidth; ++k) {
      if (k >= node.children) {
        CHECK(d2[k] == inf);
        continue;
      }
      double expected = 0.0;
      for (int c = 0; c < 3; ++c) {
        const double below = node.lo[c][k] - p[c], above = p[c] - node.hi[c][k];
        const double d = std::max({below, above, 0.0});
        expected += d * d;
      }
      CHECK(d2[k] == doctest::Approx(expected).epsilon(1e-15));
    }
  }
}

TEST_CASE("the search tree holds every cell once, inside its parents' boxes") {
  const auto g = make_surface("u+v", "sin(u)+2*cos(v)", "sin(u+v)", {-3, 3}, {-3, 3});
  REQUIRE(g);
  const SurfaceCells& cells = g->cells();
  const auto& nodes = cells.nodes();
  REQUIRE(!nodes.empty());
  std::vector<int> seen(cells.cells().size(), 0);
  // each node's child boxes contain the boxes of that child's own children
  for (std::size_t n = 0; n < nodes.size(); ++n) {
    const SurfaceCellNode& node = nodes[n];
    CHECK(node.children >= 2);
    CHECK(node.children <= SurfaceCellNode::kWidth);
    for (int k = 0; k < node.children; ++k) {
      const std::int32_t child = node.child[k];
      if (child < 0) {
        const std::int32_t leaf = ~child;
        ++seen[static_cast<std::size_t>(leaf)];
        continue;
      }
      CHECK(static_cast<std::size_t>(child) > n);  // breadth first: children after their parent
      const SurfaceCellNode& below = nodes[static_cast<std::size_t>(child)];
      for (int j = 0; j < below.children; ++j)
        for (int c = 0; c < 3; ++c) {
          CHECK(below.lo[c][j] >= node.lo[c][k]);
          CHECK(below.hi[c][j] <= node.hi[c][k]);
        }
    }
  }
  CHECK(std::all_of(seen.begin(), seen.end(), [](int s) { return s == 1; }));
  for (int c = 0; c < 3; ++c)
    for (int k = 0; k < nodes[0].children; ++k) {
      CHECK(nodes[0].lo[c][k] >= cells.lo()[c]);
      CHECK(nodes[0].hi[c][k] <= cells.hi()[c]);
    }
}

TEST_CASE("a cell lies within rho of the rectangle in its tangent plane") {
  const auto g = make_surface("u+v", "sin(u)+2*cos(v)", "sin(u+v)", {-3, 3}, {-3, 3});
  REQUIRE(g);
  int framed = 0;
  for (const SurfaceCell& c : g->cells().cells()) {
    if (!c.framed) continue;
    ++framed;
    CHECK(std::abs(norm(c.e1) - 1.0) < 1e-14);
    CHECK(std::abs(dot(c.e1, c.e2)) < 1e-14);
    CHECK(std::abs(dot(c.e1, c.unit_normal)) < 1e-14);
    CHECK(std::abs(dot(c.centre.su, c.unit_normal)) < 1e-12 * norm(c.centre.su));
    CHECK(std::abs(dot(c.centre.sv, c.unit_normal)) < 1e-12 * norm(c.centre.sv));
    constexpr int n = 6;
    double worst = 0.0;
    for (int i = 0; i <= n; ++i)
      for (int j = 0; j <= n; ++j) {
        const Vec3 r =
            g->formulas().point(c.u0 + (c.u1 - c.u0) * i / n, c.v0 + (c.v1 - c.v0) * j / n) - c.centre.s;
        const double out1 = std::max(std::abs(dot(r, c.e1)) - c.half1, 0.0);
        const double out2 = std::max(std::abs(dot(r, c.e2)) - c.half2, 0.0);
        const double h = dot(r, c.unit_normal);
        worst = std::max(worst, std::sqrt(h * h + out1 * out1 + out2 * out2) / c.rho);
      }
    CHECK(worst <= 1.0);
  }
  CHECK(framed == static_cast<int>(g->cells().cells().size()));
}

TEST_CASE("trees of a single cell and of a few cells answer as the full one") {
  const GeometryDefinition def = example1(3);
  const auto full = make_surface("u+v", "sin(u)+2*cos(v)", "sin(u+v)", {-3, 3}, {-3, 3});
  REQUIRE(full);
  for (std::size_t cap : {1, 2, 3, 5}) {
    SurfaceSeedingOptions seeding;
    seeding.max_bytes = cap * SurfaceCells::bytes_per_cell();
    const ParametricSurface g = compile_with(def, seeding);
    CAPTURE(cap);
    CHECK(g.cells().cells().size() == cap);
    CHECK(g.cells().nodes().empty() == (cap == 1));
    for (const std::array<double, 3>& p :
         {std::array<double, 3>{0.3, 0.5, 0.2}, {9.0, -2.0, 1.0}, {-1.0, 2.5, -0.5}}) {
      const ProjectionResult r = project(g, p, "auto");
      CHECK(r.summary.status == Status::converged);
      CHECK(r.distance == doctest::Approx(project(*full, p, "auto").distance).epsilon(1e-12));
    }
  }
}
