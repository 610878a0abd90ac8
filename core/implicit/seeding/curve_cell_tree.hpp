// A bounding volume hierarchy over what a curve's certified subdivision left to look at when a
// point is projected: its proved cells, its unproved boxes and its exact box-face crossings (the
// items). A certificate (implicit/solvers/implicit_curve_certificate) visits only the items whose box
// is nearer to p than the answer: a binary tree of boxes, split at the median of the items'
// centres along the longest side, pruned by the rigorous box distance (interval_vec3.hpp). A
// proved cell's item box is the part of the cell its arcs' capsules can reach (thin beside a
// nearly straight arc), an unproved box and a crossing's enclosure are their own.
#pragma once
#include <cstdint>
#include <vector>

#include "geometry/box3.hpp"

namespace footpoint {

struct CurveCells;

enum class CellItemKind : std::uint8_t {
  proved_cell,  // CurveCells::cells[index]
  unproved,     // CurveCells::unproved[index]
  box_face,     // CurveCells::crossings[index], a crossing on a face of the curve's box
};

struct CellItem {
  Box3 box;  // holds every point of the curve the item stands for
  CellItemKind kind = CellItemKind::proved_cell;
  std::int32_t index = 0;
};

class CurveCellTree {
 public:
  CurveCellTree() = default;
  CurveCellTree(const CurveCells& cells, const Box3& domain);

  struct Node {
    Box3 box;
    std::int32_t first = 0, count = 0;  // leaf: items [first, first + count)
    std::int32_t left = -1, right = -1;
  };
  const std::vector<Node>& nodes() const { return nodes_; }
  const std::vector<CellItem>& items() const { return items_; }
  std::size_t memory_bytes() const {
    return nodes_.capacity() * sizeof(Node) + items_.capacity() * sizeof(CellItem);
  }

 private:
  std::int32_t build(std::int32_t first, std::int32_t count);
  std::vector<Node> nodes_;
  std::vector<CellItem> items_;
};

}  // namespace footpoint
