// parametric/seeding/parametric_curve_cells: the cells a parametric curve's certificate bounds, and
// their hierarchy, against closed forms sampled densely:
//  - a circle (cos t, sin t): c'' = -c, |c'|^2 = 1;
//  - a helix (cos t, sin t, t/5): c'' = (-cos t, -sin t, 0), |c'|^2 = 1.04;
//  - a cubic (t, t^3 - t): c'' = (0, 6t), |c'|^2 = 1 + (3t^2 - 1)^2.
// Every enclosure holds the values at 65 points of its cell, the tangent-line model's error at
// them is within ρ and ρ is within the second-order bound ½ h^2 |c''|max worked out by hand; the
// cells tile the domain at every per_cell-th break; each node's box holds its cells' samples.
// The closed forms are evaluated in doubles: containment is checked to 1e-14 of their size.
#include <doctest/doctest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "geometry/geometry_error.hpp"
#include "parametric/seeding/parametric_curve_cells.hpp"

using namespace footpoint;

namespace parametric_curve_cells_test {

constexpr double kPi = std::numbers::pi;
constexpr double kSlack = 1e-14;

CurveFormulas curve(const std::string& x, const std::string& y, const std::string& z = "") {
  std::vector<formula::NamedFormula> f = {{"x", x}, {"y", y}};
  if (!z.empty()) f.push_back({"z", z});
  return CurveFormulas(formula::Program::compile(f, {"t"}, {}));
}

struct ClosedForm {
  std::function<Vec3(double)> c, d1, d2;
  double d2_max;  // max over the domain of each |c''_k|
};

std::vector<double> uniform(double a, double b, int gaps) {
  std::vector<double> t;
  for (int i = 0; i <= gaps; ++i) t.push_back(a + (b - a) * i / gaps);
  return t;
}

bool within(double x, double mid, double rad, double scale) {
  return std::abs(x - mid) <= rad + kSlack * scale;
}

// Every promise of the cells checked at 65 points of each cell.
void check_cells(const ParametricCurveCells& cells, const ClosedForm& f, int dims) {
  for (const ParametricCurveCell& cell : cells.cells()) {
    CAPTURE(cell.t0);
    REQUIRE(cell.enclosure.bounded);
    REQUIRE(cell.enclosure.smooth);
    REQUIRE(cell.centre_valid);
    const double h = 0.5 * (cell.t1 - cell.t0);
    // the centre's jet and its rounding radii hold the exact c, c' at tc
    const Vec3 cc = f.c(cell.tc()), dc = f.d1(cell.tc());
    for (int k = 0; k < dims; ++k) {
      CHECK(within(cell.centre.c[k], cc[k], cell.c_rad[k], 1.0 + std::abs(cc[k])));
      CHECK(within(cell.centre.d1[k], dc[k], cell.d1_rad[k], 1.0 + std::abs(dc[k])));
    }
    double worst = 0.0;
    for (int i = 0; i <= 64; ++i) {
      const double t = cell.t0 + (cell.t1 - cell.t0) * i / 64;
      const Vec3 c = f.c(t), d1 = f.d1(t), d2 = f.d2(t);
      for (int k = 0; k < dims; ++k) {
        CHECK(within(c[k], cell.enclosure.s_mid[k], cell.enclosure.s_rad[k], 1.0 + std::abs(c[k])));
        CHECK(within(d2[k], cell.enclosure.d2_mid[0][k], cell.enclosure.d2_rad[0][k], 1.0 + std::abs(d2[k])));
      }
      const double speed2 = dot(d1, d1);
      CHECK(speed2 >= cell.enclosure.metric_lo[0] - kSlack * speed2);
      CHECK(speed2 <= cell.enclosure.metric_hi[0] + kSlack * speed2);
      // the tangent-line model's error, |c(t) - c(tc) - c'(tc)(t - tc)|
      worst = std::max(worst, norm(c - cc - dc * (t - cell.tc())));
    }
    CHECK(worst <= cell.rho + kSlack);
    // ρ is the Taylor remainder ½ h^2 |c''| per coordinate, plus rounding: within ½ h^2 sqrt(dims) max|c''_k|
    CHECK(cell.rho <= 0.5 * h * h * std::sqrt(dims) * f.d2_max * (1.0 + 1e-6) + 1e-13);
  }
}

// The hierarchy: nodes before their children, every cell a leaf exactly once, in parameter order,
// every node's box holding the sampled points of the cells below it.
void check_nodes(const ParametricCurveCells& cells, const ClosedForm& f, int dims) {
  const auto& nodes = cells.nodes();
  const std::size_t n = cells.cells().size();
  REQUIRE(n >= 2);
  REQUIRE(!nodes.empty());
  std::vector<std::int32_t> leaves;
  std::function<void(std::int32_t, const std::vector<const ParametricCurveCellNode*>&)> walk =
      [&](std::int32_t index, const std::vector<const ParametricCurveCellNode*>& above) {
        if (index < 0) {
          const ParametricCurveCell& cell = cells.cells()[static_cast<std::size_t>(~index)];
          leaves.push_back(~index);
          for (int i = 0; i <= 16; ++i) {
            const Vec3 c = f.c(cell.t0 + (cell.t1 - cell.t0) * i / 16);
            for (const ParametricCurveCellNode* a : above)
              for (int k = 0; k < dims; ++k) {
                CHECK(c[k] >= a->lo[k] - kSlack);
                CHECK(c[k] <= a->hi[k] + kSlack);
              }
          }
          return;
        }
        REQUIRE(static_cast<std::size_t>(index) < nodes.size());
        const ParametricCurveCellNode& node = nodes[static_cast<std::size_t>(index)];
        std::vector<const ParametricCurveCellNode*> chain = above;
        chain.push_back(&node);
        for (const std::int32_t child : node.child) {
          if (child >= 0) CHECK(child > index);  // a node comes before its children
          walk(child, chain);
        }
      };
  walk(0, {});
  REQUIRE(leaves.size() == n);
  for (std::size_t i = 0; i < n; ++i) CHECK(leaves[i] == static_cast<std::int32_t>(i));
}

const ClosedForm kCircle{[](double t) {
                           return Vec3{std::cos(t), std::sin(t), 0.0};
                         },
                         [](double t) {
                           return Vec3{-std::sin(t), std::cos(t), 0.0};
                         },
                         [](double t) {
                           return Vec3{-std::cos(t), -std::sin(t), 0.0};
                         },
                         1.0};
const ClosedForm kHelix{[](double t) {
                          return Vec3{std::cos(t), std::sin(t), 0.2 * t};
                        },
                        [](double t) {
                          return Vec3{-std::sin(t), std::cos(t), 0.2};
                        },
                        [](double t) {
                          return Vec3{-std::cos(t), -std::sin(t), 0.0};
                        },
                        1.0};
// over [-1.5, 1.5]: |c''_y| = 6|t| <= 9
const ClosedForm kCubic{[](double t) {
                          return Vec3{t, t * t * t - t, 0.0};
                        },
                        [](double t) {
                          return Vec3{1.0, 3.0 * t * t - 1.0, 0.0};
                        },
                        [](double t) {
                          return Vec3{0.0, 6.0 * t, 0.0};
                        },
                        9.0};

TEST_CASE("parametric_curve_cells: a circle's cells tile [0, 2π] at every 4th break and enclose it") {
  CompileBudget budget;
  // 100 gaps: 25 cells; breaks given out of order, repeated and beyond the domain are dropped
  std::vector<double> breaks = uniform(0, 2 * kPi, 100);
  std::reverse(breaks.begin(), breaks.end());
  breaks.push_back(1.0 * 2 * kPi / 100 * 37);
  breaks.push_back(-1.0);
  breaks.push_back(7.0);
  const ParametricCurveCells cells(curve("cos(t)", "sin(t)"), {0, 2 * kPi}, breaks, budget);
  const auto& c = cells.cells();
  REQUIRE(c.size() == 25);
  const std::vector<double> sorted = uniform(0, 2 * kPi, 100);
  for (std::size_t i = 0; i < c.size(); ++i) {
    CHECK(c[i].t0 == sorted[4 * i]);
    CHECK(c[i].t1 == sorted[4 * i + 4]);
  }
  check_cells(cells, kCircle, 2);
  check_nodes(cells, kCircle, 2);
  CHECK(cells.memory_bytes() >= c.size() * sizeof(ParametricCurveCell));
}

TEST_CASE("parametric_curve_cells: a helix and a cubic, any per_cell; the last cell takes the remainder") {
  CompileBudget budget;
  const ParametricCurveCells helix(curve("cos(t)", "sin(t)", "0.2*t"), {0, 4 * kPi}, uniform(0, 4 * kPi, 90),
                                   budget, 3);
  CHECK(helix.cells().size() == 30);
  check_cells(helix, kHelix, 3);
  check_nodes(helix, kHelix, 3);

  // 50 gaps at 4 a cell: 12 cells of 4 and a last one of 2
  const std::vector<double> b = uniform(-1.5, 1.5, 50);
  const ParametricCurveCells cubic(curve("t", "t^3-t"), {-1.5, 1.5}, b, budget);
  REQUIRE(cubic.cells().size() == 13);
  CHECK(cubic.cells().back().t0 == b[48]);
  CHECK(cubic.cells().back().t1 == 1.5);
  check_cells(cubic, kCubic, 2);
  check_nodes(cubic, kCubic, 2);

  // per_cell = 1: a cell per gap
  const ParametricCurveCells fine(curve("t", "t^3-t"), {-1.5, 1.5}, b, budget, 1);
  CHECK(fine.cells().size() == 50);
  check_cells(fine, kCubic, 2);
}

TEST_CASE("parametric_curve_cells: one cell has no hierarchy; no breaks still give the domain's cell") {
  CompileBudget budget;
  const ParametricCurveCells one(curve("cos(t)", "sin(t)"), {0, 0.5}, {}, budget);
  REQUIRE(one.cells().size() == 1);
  CHECK(one.cells()[0].t0 == 0.0);
  CHECK(one.cells()[0].t1 == 0.5);
  CHECK(one.nodes().empty());
  check_cells(one, kCircle, 2);
}

TEST_CASE("parametric_curve_cells: where the formulas are undefined or kinked nothing is claimed") {
  CompileBudget budget;
  // sqrt(t) over [-1, 1]: the cells left of 0 hold no point of the curve's domain of definition
  const ParametricCurveCells root(curve("t", "sqrt(t)"), {-1, 1}, uniform(-1, 1, 40), budget);
  REQUIRE(root.cells().size() == 10);
  for (const ParametricCurveCell& c : root.cells()) {
    CAPTURE(c.t0);
    if (c.t1 <= 0.0) {
      CHECK_FALSE(c.enclosure.bounded);
      CHECK_FALSE(c.centre_valid);
      CHECK(c.rho == std::numeric_limits<double>::infinity());
    } else if (c.t0 > 0.0) {
      CHECK(c.enclosure.bounded);
      CHECK(c.centre_valid);
      CHECK(std::isfinite(c.rho));
    }
  }
  // the hierarchy does not bound unbounded cells: their leaves' boxes are the whole space
  CHECK(root.nodes()[0].lo[1] == -std::numeric_limits<double>::infinity());

  // |t| with the kink inside one cell: that cell has no tangent-line bound, the others have
  const ParametricCurveCells kink(curve("t", "abs(t)"), {-1, 1}, uniform(-1.0, 1.0, 43), budget);
  int unbounded = 0;
  for (const ParametricCurveCell& c : kink.cells()) {
    if (c.t0 < 0.0 && c.t1 > 0.0) {
      CHECK(c.rho == std::numeric_limits<double>::infinity());
      ++unbounded;
    } else {
      // a straight line on each side: only rounding
      CHECK(c.rho <= 1e-14);
    }
  }
  CHECK(unbounded == 1);
}

TEST_CASE("parametric_curve_cells: a past deadline stops the build with compile_timeout") {
  CompileBudget late(CompileBudget::clock::now() - std::chrono::seconds(1));
  // check() reads the clock every 64 cells: 200 cells reach it
  try {
    ParametricCurveCells(curve("cos(t)", "sin(t)"), {0, 2 * kPi}, uniform(0, 2 * kPi, 800), late);
    FAIL("no timeout");
  } catch (const GeometryError& e) {
    CHECK(e.code == "compile_timeout");
  }
}

}  // namespace parametric_curve_cells_test
