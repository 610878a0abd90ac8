#include "implicit/seeding/curve_cell_tree.hpp"

#include <algorithm>

#include "implicit/seeding/curve_cells.hpp"

namespace footpoint {
namespace {

// Items per leaf: with the arcs' thin boxes, testing a leaf's items directly is about as selective
// as descending further (build/bench/curve_bench compares leaf sizes).
constexpr std::int32_t kLeafItems = 8;

bool on_box_face(const FaceCrossing& x, const Box3& domain) {
  for (int a = 0; a < 3; ++a)
    if (domain.hi[a] > domain.lo[a] && x.enclosure.lo[a] == x.enclosure.hi[a] &&
        (x.enclosure.lo[a] == domain.lo[a] || x.enclosure.lo[a] == domain.hi[a]))
      return true;
  return false;
}

// The part of a proved cell its arcs can be in: the cell less what lies outside every capsule's
// box (thin beside a nearly straight arc, where the cell is a cube).
Box3 arcs_box(const CurveCells& cells, std::size_t cell) {
  const Box3& box = cells.cells[cell].box;
  const auto capsules = cells.arc_capsules(cell);
  if (capsules.empty()) return box;
  Box3 all = capsule_box(capsules.front());
  for (const ArcCapsule& c : capsules.subspan(1)) all = hull(all, capsule_box(c));
  return intersection(all, box);
}

}  // namespace

CurveCellTree::CurveCellTree(const CurveCells& cells, const Box3& domain) {
  for (std::size_t i = 0; i < cells.cells.size(); ++i)
    items_.push_back({arcs_box(cells, i), CellItemKind::proved_cell, static_cast<std::int32_t>(i)});
  for (std::size_t i = 0; i < cells.unproved.size(); ++i)
    items_.push_back({cells.unproved[i].box, CellItemKind::unproved, static_cast<std::int32_t>(i)});
  for (std::size_t i = 0; i < cells.crossings.size(); ++i)
    if (on_box_face(cells.crossings[i], domain))
      items_.push_back({cells.crossings[i].enclosure, CellItemKind::box_face, static_cast<std::int32_t>(i)});
  if (!items_.empty()) build(0, static_cast<std::int32_t>(items_.size()));
}

std::int32_t CurveCellTree::build(std::int32_t first, std::int32_t count) {
  Node node;
  node.box = items_[static_cast<std::size_t>(first)].box;
  for (std::int32_t i = first + 1; i < first + count; ++i)
    node.box = hull(node.box, items_[static_cast<std::size_t>(i)].box);
  const auto at = static_cast<std::int32_t>(nodes_.size());
  nodes_.push_back(node);
  if (count <= kLeafItems) {
    nodes_[static_cast<std::size_t>(at)].first = first;
    nodes_[static_cast<std::size_t>(at)].count = count;
    return at;
  }
  int axis = 0;
  for (int k = 1; k < 3; ++k)
    if (node.box.hi[k] - node.box.lo[k] > node.box.hi[axis] - node.box.lo[axis]) axis = k;
  const auto begin = items_.begin() + first;
  const auto middle = begin + count / 2;
  std::nth_element(begin, middle, begin + count, [axis](const CellItem& a, const CellItem& b) {
    return a.box.lo[axis] + a.box.hi[axis] < b.box.lo[axis] + b.box.hi[axis];
  });
  const std::int32_t left = build(first, count / 2);
  const std::int32_t right = build(first + count / 2, count - count / 2);
  nodes_[static_cast<std::size_t>(at)].left = left;
  nodes_[static_cast<std::size_t>(at)].right = right;
  return at;
}

}  // namespace footpoint
