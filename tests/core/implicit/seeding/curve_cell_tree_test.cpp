// implicit/seeding/curve_cell_tree: the bounding volume hierarchy over a subdivision's proved cells,
// unproved boxes and box-face crossings. Checked: one item per proved cell, unproved box and
// crossing on a face of the curve's box; a proved cell's item box lies in the cell and holds every
// point of the curve in the cell (points from the curves' parametrisations), and is thin beside a
// nearly straight arc; the tree's node boxes hold their children's and their items' boxes, its
// leaves hold at most 8 items and share the items out exactly once.
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "closed_form_curves.hpp"
#include "implicit/seeding/curve_cell_tree.hpp"
#include "implicit_fixtures.hpp"

using namespace footpoint;
using namespace footpoint::test;

namespace curve_cell_tree_test {

const Box3 kSpace{{-3, -3, -3}, {3, 3, 3}};

// The node boxes hold their children's boxes and the boxes of the items in their leaves; leaves
// have at most 8 items, and every item is in exactly one leaf. Returns the violations.
int bad_nodes(const CurveCellTree& tree) {
  const auto& nodes = tree.nodes();
  const auto& items = tree.items();
  std::vector<int> seen(items.size(), 0);
  int bad = 0;
  for (const CurveCellTree::Node& n : nodes) {
    if (n.left < 0) {
      bad += n.count < 1 || n.count > 8 || n.right >= 0;
      for (std::int32_t i = n.first; i < n.first + n.count; ++i) {
        ++seen[static_cast<std::size_t>(i)];
        bad += !n.box.contains(items[static_cast<std::size_t>(i)].box);
      }
    } else {
      bad += n.right < 0 || !n.box.contains(nodes[static_cast<std::size_t>(n.left)].box) ||
             !n.box.contains(nodes[static_cast<std::size_t>(n.right)].box);
    }
  }
  for (int s : seen) bad += s != 1;
  return bad;
}

// The points x of the curve in a proved cell that its item box does not hold.
int outside_item(const CurveCells& cells, const CurveCellTree& tree, const std::vector<Vec3>& points) {
  int bad = 0;
  for (const CellItem& item : tree.items()) {
    if (item.kind != CellItemKind::proved_cell) continue;
    const Box3& cell = cells.cells[static_cast<std::size_t>(item.index)].box;
    bad += !cell.contains(item.box);
    for (const Vec3& x : points)
      if (cell.contains(x) && !item.box.contains(x, 1e-12)) ++bad;
  }
  return bad;
}

std::vector<Vec3> curve_points(const ParamCurve& curve, int n) {
  std::vector<Vec3> out;
  for (int i = 0; i < n; ++i) out.push_back(curve.c(curve.t0 + (curve.t1 - curve.t0) * i / n));
  return out;
}

int count(const CurveCellTree& tree, CellItemKind kind) {
  int n = 0;
  for (const CellItem& i : tree.items()) n += i.kind == kind;
  return n;
}

TEST_CASE("CurveCellTree: Viviani's curve, every cell, unproved box and point of the curve held") {
  const ImplicitEquations eq = spatial_equations("x^2+y^2+z^2-4", "(x-1)^2+y^2-1");
  const CurveCells cells = subdivided_cells(eq, kSpace);
  const CurveCellTree tree(cells, kSpace);
  // No crossing on the box's faces: the curve is inside |x|, |y|, |z| <= 2.
  CHECK(tree.items().size() == cells.cells.size() + cells.unproved.size());
  CHECK(count(tree, CellItemKind::proved_cell) == static_cast<int>(cells.cells.size()));
  CHECK(count(tree, CellItemKind::unproved) == static_cast<int>(cells.unproved.size()));
  for (const CellItem& i : tree.items())
    if (i.kind == CellItemKind::unproved) {
      const Box3& u = cells.unproved[static_cast<std::size_t>(i.index)].box;
      CHECK((u.contains(i.box) && i.box.contains(u)));
    }
  CHECK(bad_nodes(tree) == 0);
  CHECK(outside_item(cells, tree, curve_points(viviani_curve(), 2000)) == 0);
  // The root holds the whole curve: the double point, and every point sampled.
  REQUIRE(!tree.nodes().empty());
  CHECK(tree.nodes()[0].box.contains(Vec3{2, 0, 0}, 1e-12));
}

TEST_CASE("CurveCellTree: a circle clipped by its box, its two face crossings are items") {
  // x <= 0.5 cuts x^2 + y^2 = 1 at (0.5, +-sqrt 0.75).
  const Box3 box{{-2, -2, 0}, {0.5, 2, 0}};
  const CurveCells cells = subdivided_cells(planar_equations("x^2+y^2-1"), box);
  const CurveCellTree tree(cells, box);
  REQUIRE(count(tree, CellItemKind::box_face) == 2);
  for (const CellItem& i : tree.items())
    if (i.kind == CellItemKind::box_face) {
      const Vec3 x = cells.crossings[static_cast<std::size_t>(i.index)].point;
      CHECK(x.x == 0.5);
      CHECK(std::fabs(std::fabs(x.y) - std::sqrt(0.75)) <= 1e-15);
      CHECK(i.box.contains(Vec3{0.5, std::copysign(std::sqrt(0.75), x.y), 0.0}));
    }
  CHECK(tree.items().size() == cells.cells.size() + 2);
  CHECK(bad_nodes(tree) == 0);
  std::vector<Vec3> points;
  for (const Vec3& x : curve_points(ellipse_curve(1.0, 1.0), 4000))
    if (box.contains(x)) points.push_back(x);
  CHECK(outside_item(cells, tree, points) == 0);
}

TEST_CASE("CurveCellTree: beside a nearly straight arc a cell's item box is thin") {
  // y = 0.01 x + 0.1: along each cell the curve rises by 0.01 of the cell's width, so the arcs'
  // capsules (straight arcs: a zero second derivative and a constant slope) keep the item box
  // that thin, where the cell is a square.
  const Box3 box{{-1, -1, 0}, {1, 1, 0}};
  const CurveCells cells = subdivided_cells(planar_equations("y-0.01*x-0.1"), box);
  const CurveCellTree tree(cells, box);
  REQUIRE(!cells.cells.empty());
  int thick = 0;
  for (const CellItem& i : tree.items()) {
    if (i.kind != CellItemKind::proved_cell) continue;
    const Box3& cell = cells.cells[static_cast<std::size_t>(i.index)].box;
    thick += i.box.hi.y - i.box.lo.y > 0.02 * (cell.hi.x - cell.lo.x) + 1e-12;
  }
  CHECK(thick == 0);
  // The curve's two ends on x = -1 and x = 1.
  CHECK(count(tree, CellItemKind::box_face) == 2);
  CHECK(bad_nodes(tree) == 0);
}

TEST_CASE("CurveCellTree: nothing to hold, no nodes") {
  const CurveCellTree tree(CurveCells{}, kSpace);
  CHECK(tree.nodes().empty());
  CHECK(tree.items().empty());
  CHECK(CurveCellTree().nodes().empty());
}

}  // namespace curve_cell_tree_test
