// implicit/seeding/implicit_surface_cells: the octree of an implicit surface's box, its samples,
// its box-edge points and singular points, against closed forms:
//  - every point of a torus and of an ellipsoid, sampled densely from their parametrizations, lies
//    in a kept leaf (a leaf holds every point of S: the enclosures that drop cells are rigorous);
//  - the octants a split cell dropped hold no zero of f (f keeps one strict sign on a grid of them);
//  - the samples lie on S, in their leaf's box widened by half its edge, inside the box;
//  - the edge points of planes and a sphere are the closed-form intersections with the box's
//    twelve edges (corners flagged), the singular point of a cone is its apex, a sphere has none;
//  - the cell budget, the deadline and the bound on bytes stop the subdivision as documented;
//  - land_on_surface and octant_of by hand.
#include <doctest/doctest.h>

#include <chrono>
#include <cmath>
#include <string>
#include <vector>

#include "geometry/geometry_error.hpp"
#include "implicit_surface_truths.hpp"

using namespace footpoint;

namespace implicit_surface_cells_test {

constexpr double kPi = 3.141592653589793;

// Whether x lies (within `slack`) in a kept leaf below cell i.
bool in_kept_leaf(const ImplicitSurfaceCells& cells, std::size_t i, Vec3 x, double slack) {
  const ImplicitSurfaceCell& c = cells.cells[i];
  if (!c.box.contains(x, slack)) return false;
  if (c.first_child < 0) return true;
  for (int k = 0; k < c.children; ++k)
    if (in_kept_leaf(cells, static_cast<std::size_t>(c.first_child + k), x, slack)) return true;
  return false;
}

// The ellipsoid x^2/4 + y^2 + 4 z^2 = 1 and the torus of radii 2 and 0.5, each with its
// parametrization.
struct Parametrized {
  const char* equation;
  Box3 box;
  Vec3 (*point)(double u, double v);  // u, v in [0, 1]
};

Vec3 ellipsoid_point(double u, double v) {
  const double th = 2.0 * kPi * u, ph = kPi * (v - 0.5);
  return {2.0 * std::cos(ph) * std::cos(th), std::cos(ph) * std::sin(th), 0.5 * std::sin(ph)};
}

Vec3 torus_point(double u, double v) {
  const double th = 2.0 * kPi * u, ph = 2.0 * kPi * v;
  return {(2.0 + 0.5 * std::cos(ph)) * std::cos(th), (2.0 + 0.5 * std::cos(ph)) * std::sin(th),
          0.5 * std::sin(ph)};
}

const Parametrized kSurfaces[] = {
    {"x^2/4+y^2+4*z^2-1", {{-2.5, -1.3, -0.7}, {2.1, 1.6, 0.9}}, ellipsoid_point},
    {"(x^2+y^2+z^2+3.75)^2-16*(x^2+y^2)", {{-3, -3, -1}, {3, 3, 1}}, torus_point},
};

TEST_CASE("implicit surface cells: every sampled point of an ellipsoid and a torus is in a kept leaf") {
  for (const Parametrized& s : kSurfaces) {
    CAPTURE(std::string(s.equation));
    const ImplicitSurfaceEquation f = test::surface_equation(s.equation);
    const ImplicitSurfaceCells cells = test::surface_cells(f, s.box);
    REQUIRE(!cells.empty());
    // The leaves are the cells of the last level: edges 2^-5 of the box's, diagonal leaf_diagonal.
    std::size_t leaves = 0;
    for (const ImplicitSurfaceCell& c : cells.cells) {
      if (c.first_child >= 0) {
        for (int k = 0; k < c.children; ++k)
          CHECK(c.box.contains(cells.cells[static_cast<std::size_t>(c.first_child + k)].box));
        continue;
      }
      ++leaves;
      CHECK(c.box.diagonal() == doctest::Approx(s.box.diagonal() / 32.0).epsilon(1e-12));
    }
    CHECK(leaves == cells.leaves);
    CHECK(cells.leaf_diagonal == doctest::Approx(s.box.diagonal() / 32.0).epsilon(1e-12));
    // A 400 x 200 grid of the parametrization; the points the box clips away are skipped. The
    // slack is the points' own rounding (their f is not exactly 0).
    int inside = 0, missed = 0;
    for (int i = 0; i < 400; ++i)
      for (int j = 0; j <= 200; ++j) {
        const Vec3 x = s.point(i / 400.0, j / 200.0);
        if (!s.box.contains(x)) continue;
        ++inside;
        if (!in_kept_leaf(cells, 0, x, 1e-12)) ++missed;
      }
    CHECK(inside > 20000);
    CHECK(missed == 0);
  }
}

TEST_CASE("implicit surface cells: the octants a split cell dropped hold no zero") {
  // f keeps one strict sign on a 5 x 5 x 5 grid of every dropped octant: where S crossed a
  // dropped octant, the grid's points on its two sides would show both signs (S is smooth and
  // its pieces in an octant are not smaller than the grid's spacing for these two surfaces).
  for (const Parametrized& s : kSurfaces) {
    CAPTURE(std::string(s.equation));
    const ImplicitSurfaceEquation f = test::surface_equation(s.equation);
    const ImplicitSurfaceCells cells = test::surface_cells(f, s.box);
    int dropped = 0, mixed = 0;
    for (const ImplicitSurfaceCell& c : cells.cells) {
      if (c.first_child < 0) continue;
      for (int octant = 0; octant < 8; ++octant) {
        const Box3 o = octant_of(c.box, octant);
        bool kept = false;
        for (int k = 0; k < c.children; ++k) {
          const Box3& b = cells.cells[static_cast<std::size_t>(c.first_child + k)].box;
          kept = kept || (b.lo.x == o.lo.x && b.lo.y == o.lo.y && b.lo.z == o.lo.z && b.hi.x == o.hi.x &&
                          b.hi.y == o.hi.y && b.hi.z == o.hi.z);
        }
        if (kept) continue;
        ++dropped;
        int positive = 0, negative = 0;
        for (int a = 0; a <= 4; ++a)
          for (int b = 0; b <= 4; ++b)
            for (int d = 0; d <= 4; ++d) {
              const Vec3 x{o.lo.x + (o.hi.x - o.lo.x) * a / 4.0, o.lo.y + (o.hi.y - o.lo.y) * b / 4.0,
                           o.lo.z + (o.hi.z - o.lo.z) * d / 4.0};
              const double v = f.value(x);
              positive += v > 0.0 ? 1 : 0;
              negative += v < 0.0 ? 1 : 0;
            }
        if (positive != 125 && negative != 125) ++mixed;
      }
    }
    CHECK(dropped > 100);
    CHECK(mixed == 0);
  }
  // A sphere the box misses: no cell, one enclosure computed.
  const ImplicitSurfaceEquation sphere = test::surface_equation("x^2+y^2+z^2-1");
  const ImplicitSurfaceCells none = test::surface_cells(sphere, {{2, 2, 2}, {3, 3, 3}});
  CHECK(none.empty());
  CHECK(none.examined == 1);
  CHECK(none.samples.empty());
}

TEST_CASE("implicit surface cells: samples lie on the surface, by their leaf, inside the box") {
  // On the ellipsoid the distance to S is checked through |f| / |grad f| (first order, exact to
  // rounding at a point of S); on the torus against its closed-form distance.
  for (const Parametrized& s : kSurfaces) {
    CAPTURE(std::string(s.equation));
    const ImplicitSurfaceEquation f = test::surface_equation(s.equation);
    const ImplicitSurfaceCells cells = test::surface_cells(f, s.box);
    std::size_t sampled = 0;
    for (const ImplicitSurfaceCell& c : cells.cells) {
      if (c.first_child >= 0 || c.sample < 0) continue;
      ++sampled;
      REQUIRE(static_cast<std::size_t>(c.sample) < cells.samples.size());
      const Vec3 x = cells.samples[static_cast<std::size_t>(c.sample)];
      CHECK(s.box.contains(x));
      CHECK(c.box.contains(x, 0.5 * c.box.max_edge()));
      const ImplicitSurfaceJet j = f.jet(x);
      CHECK(std::fabs(j.f) / norm(j.grad) <= 1e-14);
      if (s.point == torus_point) CHECK(test::torus_distance(2.0, 0.5, x) <= 1e-14);
    }
    CHECK(sampled == cells.samples.size());
    // Most leaves land: those S crosses (Newton from within half a diagonal of S); the others are
    // leaves that the enclosures could not drop although S misses them (the torus' quartic is
    // overestimated), where Newton may land farther than half an edge away (6400 of 7280 leaves
    // of the torus, all of the ellipsoid's).
    CHECK(sampled * 4 >= cells.leaves * 3);
    REQUIRE(cells.sample_index);
  }
}

TEST_CASE("implicit surface cells: the box's edge points and the singular points in closed form") {
  // The plane x + y + z = 3/2 meets the unit cube's edges at their midpoints (two coordinates
  // at bounds a, b in {0, 1} with a + b = 1, the third 1/2): a hexagon, no corner.
  const Box3 cube{{0, 0, 0}, {1, 1, 1}};
  const ImplicitSurfaceCells hexagon = test::surface_cells(test::surface_equation("x+y+z-1.5"), cube);
  REQUIRE(hexagon.edge_points.size() == 6);
  for (const BoxEdgePoint& e : hexagon.edge_points) {
    CHECK(!e.corner);
    int halves = 0, bounds = 0;
    for (int k = 0; k < 3; ++k) {
      halves += std::fabs(e.x[k] - 0.5) <= 1e-15 ? 1 : 0;
      bounds += (e.x[k] == 0.0 || e.x[k] == 1.0) ? 1 : 0;
    }
    CHECK(halves == 1);
    CHECK(bounds == 2);
    CHECK(std::fabs(e.x.x + e.x.y + e.x.z - 1.5) <= 1e-15);
  }
  // The plane x + y + z = 1 passes through three corners, each met by three edges: three corner
  // points, each once.
  const ImplicitSurfaceCells triangle = test::surface_cells(test::surface_equation("x+y+z-1"), cube);
  REQUIRE(triangle.edge_points.size() == 3);
  for (const BoxEdgePoint& e : triangle.edge_points) {
    CHECK(e.corner);
    CHECK(e.x.x + e.x.y + e.x.z == 1.0);
    CHECK(std::max({e.x.x, e.x.y, e.x.z}) == 1.0);
  }
  // The unit sphere in [-0.5, 2] x [-0.3, 2] x [0.2, 2]: along the edge of axis k with the other
  // coordinates (a, b) at bounds, x_k = ±sqrt(1 - a^2 - b^2) where that is in the edge's range.
  const Box3 box{{-0.5, -0.3, 0.2}, {2, 2, 2}};
  std::vector<Vec3> expected;
  for (int k = 0; k < 3; ++k)
    for (int corner = 0; corner < 4; ++corner) {
      const int i = (k + 1) % 3, l = (k + 2) % 3;
      Vec3 x;
      x[i] = (corner & 1) ? box.hi[i] : box.lo[i];
      x[l] = (corner & 2) ? box.hi[l] : box.lo[l];
      const double rest = 1.0 - x[i] * x[i] - x[l] * x[l];
      if (rest < 0.0) continue;
      for (const double root : {-std::sqrt(rest), std::sqrt(rest)}) {
        x[k] = root;
        if (box.lo[k] <= root && root <= box.hi[k]) expected.push_back(x);
      }
    }
  // By hand: (sqrt(0.87), -0.3, 0.2), (-0.5, sqrt(0.71), 0.2), (-0.5, -0.3, sqrt(0.66)).
  REQUIRE(expected.size() == 3);
  const ImplicitSurfaceCells sphere = test::surface_cells(test::surface_equation("x^2+y^2+z^2-1"), box);
  CHECK(sphere.edge_points.size() == expected.size());
  for (const Vec3& x : expected) {
    double nearest = 1e300;
    for (const BoxEdgePoint& e : sphere.edge_points) nearest = std::min(nearest, norm(e.x - x));
    CHECK(nearest <= 1e-14);
  }
  CHECK(sphere.singular_points.empty());  // grad f = 0 only at the centre, where f = -1
  // The cone (x - 0.1)^2 + (y + 0.2)^2 = (z - 0.3)^2: f = 0 and grad f = 0 at its apex alone.
  const ImplicitSurfaceCells cone =
      test::surface_cells(test::surface_equation("(x-0.1)^2+(y+0.2)^2-(z-0.3)^2"), {{-1, -1, -1}, {1, 1, 1}});
  REQUIRE(cone.singular_points.size() == 1);
  CHECK(norm(cone.singular_points[0] - Vec3{0.1, -0.2, 0.3}) <= 1e-14);
}

TEST_CASE("implicit surface cells: the cell budget, the deadline and the bound on bytes") {
  const ImplicitSurfaceEquation torus = test::surface_equation("(x^2+y^2+z^2+3.75)^2-16*(x^2+y^2)");
  const Box3 box{{-3, -3, -1}, {3, 3, 1}};
  const ImplicitSurfaceCells full = test::surface_cells(torus, box);
  // Each split cell's eight octants are examined, and the box itself.
  std::size_t split = 0;
  for (const ImplicitSurfaceCell& c : full.cells) split += c.first_child >= 0 ? 1 : 0;
  CHECK(full.examined >= 1 + 8 * split);
  auto code_of = [&](std::size_t max_cells, CompileBudget& budget) {
    ImplicitSurfaceCellSettings settings;
    settings.max_cells = max_cells;
    try {
      subdivide_surface(torus, box, budget, settings);
    } catch (const GeometryError& e) {
      return e.code;
    }
    return std::string("none");
  };
  // The budget counts exactly the cells examined: one fewer refuses the surface.
  CompileBudget unbounded;
  CHECK(code_of(full.examined, unbounded) == "none");
  CHECK(code_of(full.examined - 1, unbounded) == "geometry_too_complex");
  CHECK(code_of(100, unbounded) == "geometry_too_complex");
  // Fewer levels: a coarser tree, the same surface covered, fewer cells.
  ImplicitSurfaceCellSettings coarse;
  coarse.levels = 3;
  const ImplicitSurfaceCells three = test::surface_cells(torus, box, coarse);
  CHECK(three.leaf_diagonal == doctest::Approx(box.diagonal() / 8.0).epsilon(1e-12));
  CHECK(three.examined < full.examined);
  // A deadline already past: compile_timeout (the budget reads the clock every 64 checks).
  CompileBudget late(CompileBudget::clock::now() - std::chrono::seconds(1));
  CHECK(code_of(30000, late) == "compile_timeout");
  // A bound on bytes below one cell per leaf: geometry_too_large.
  CompileBudget small(CompileBudget::clock::time_point::max(), 10 * sizeof(ImplicitSurfaceCell));
  CHECK(code_of(30000, small) == "geometry_too_large");
  // What grow() counted is a lower bound of the structure's memory.
  CompileBudget counted;
  const ImplicitSurfaceCells again = subdivide_surface(torus, box, counted);
  CHECK(counted.grown() > 0);
  CHECK(counted.grown() <= again.memory_bytes());
}

TEST_CASE("implicit surface cells: land_on_surface and octant_of by hand") {
  // On the unit sphere a Newton step along the gradient, x - (|x|^2 - 1) / (4 |x|^2) 2x, keeps x on
  // its ray: it lands at x / |x|.
  const ImplicitSurfaceEquation sphere = test::surface_equation("x^2+y^2+z^2-1");
  for (const Vec3 x0 : {Vec3{0.3, -0.2, 0.1}, Vec3{3.0, 4.0, -12.0}, Vec3{1.0, 0.0, 0.0}}) {
    Vec3 x = x0;
    CHECK(land_on_surface(sphere, x));
    CHECK(norm(x - x0 / norm(x0)) <= 1e-15);
  }
  Vec3 centre{0.0, 0.0, 0.0};
  CHECK(!land_on_surface(sphere, centre));  // grad f = 0
  Vec3 far{300.0, 0.0, 0.0};
  CHECK(!land_on_surface(sphere, far, 2));  // two halvings of |x| do not settle from 300
  // octant_of: bit k selects the upper half along axis k.
  const Box3 b{{0, -2, 4}, {2, 2, 8}};
  const Box3 o5 = octant_of(b, 5);  // upper x, lower y, upper z
  CHECK(o5.lo.x == 1.0);
  CHECK(o5.hi.x == 2.0);
  CHECK(o5.lo.y == -2.0);
  CHECK(o5.hi.y == 0.0);
  CHECK(o5.lo.z == 6.0);
  CHECK(o5.hi.z == 8.0);
  const Box3 o2 = octant_of(b, 2);  // lower x, upper y, lower z
  CHECK(o2.lo.x == 0.0);
  CHECK(o2.hi.x == 1.0);
  CHECK(o2.lo.y == 0.0);
  CHECK(o2.hi.y == 2.0);
  CHECK(o2.lo.z == 4.0);
  CHECK(o2.hi.z == 6.0);
}

}  // namespace implicit_surface_cells_test
