// The nearest point of a geometry made of pieces (a NURBS cut at its knots into Bézier pieces,
// parametric/geometry/nurbs_patches.hpp), each with a box that holds it: a branch and bound over
// the pieces. The distance from p to a piece's box is a lower bound of the distance to the piece;
// the pieces are visited nearest box first, each solved by its own global method, and a piece is
// left out once its box is farther than the best distance found plus the certificate's gap
// (projection/certificate.hpp): no point of it can be nearer, nor tie. The answer's certificate is
// the pieces': its lower bound is the smallest of the solved pieces' lower bounds and the boxes
// of the pieces left out, so it is as rigorous as theirs; a foot on two pieces (their shared edge)
// or on several at the same distance is one answer with the multiplicity of the distinct feet.
//
// With options.all_minima every piece within options.max_distance is solved, and the minima are
// the pieces' merged (a minimum on a shared edge once), best first.
#pragma once
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "geometry/box3.hpp"
#include "projection/projection_result.hpp"

namespace footpoint {

// A lower bound of the distance from p to any point of the box (0 inside), rounded down.
double distance_lower_bound(const Box3& box, const Vec3& p);

// The pieces' boxes in a binary tree (each node's box holds its children's; split at the median of
// the boxes' centres along the longest side), walked best first: a point visits the nodes nearer
// than its best distance, not every piece ([CGAL] the AABB tree's traversal traits: one tree, many
// queries).
class PieceTree {
 public:
  PieceTree() = default;
  explicit PieceTree(std::vector<Box3> hulls);
  std::size_t size() const { return hulls_.size(); }
  const Box3& hull(std::size_t piece) const { return hulls_[piece]; }
  std::size_t memory_bytes() const;

  struct Node {
    Box3 box;
    std::int32_t first, count;  // the pieces order_[first, first + count) under it
    std::int32_t child[2];      // -1: a leaf
  };
  const std::vector<Node>& nodes() const { return nodes_; }
  const std::vector<std::int32_t>& order() const { return order_; }

 private:
  std::int32_t build(std::int32_t first, std::int32_t count);
  std::vector<Box3> hulls_;
  std::vector<std::int32_t> order_;
  std::vector<Node> nodes_;
};

struct PiecewiseNearest {
  ProjectionResult result;  // the answer, from the nearest piece's answer
  std::size_t piece = 0;    // that piece (meaningless without a finite answer)
  int pieces_solved = 0;
};

// `solve(k, options, cutoff)` projects p onto piece k with its global method (the options passed
// on; the caller decides what options.initial means for piece k). cutoff is the best distance
// found so far plus the gap (infinite at first): a piece none of whose points is within it can be
// neither the answer nor tied with it, so its answer may then be any point of it with a rigorous
// lower bound above cutoff, not its nearest point.
PiecewiseNearest nearest_over_pieces(
    const PieceTree& pieces, const Vec3& p, const Options& options,
    const std::function<ProjectionResult(std::size_t, const Options&, double)>& solve);

}  // namespace footpoint
