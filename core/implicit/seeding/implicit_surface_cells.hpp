// What `auto` precomputes for an implicit surface S = {f = 0} clipped to its box B:
//  - an octree of B by interval subdivision: a cell is kept only where the enclosure of f over it
//    (the natural interval evaluation intersected with the mean value form f(c) + grad f(C) . (C - c),
//    R. E. Moore, R. B. Kearfott, M. J. Cloud, Introduction to Interval Analysis, SIAM 2009, Sec. 6.4)
//    contains 0, so every point of S lies in a leaf; the tree is what the search orders its starts by
//    and what the certificate's branch and bound descends;
//  - a sample point of S in each leaf (Newton steps along the gradient from the leaf's centre), and
//    a k-d tree over the samples;
//  - the points where S meets the twelve edges of B (1-D interval subdivision of f along each edge,
//    then bisection and Newton on each sign change), the corners among them;
//  - the singular points of S (f = 0 and grad f = 0: a cone's apex), found by Newton on grad f = 0
//    from the leaves where the gradient's enclosure holds 0.
// Beyond the cell budget: GeometryError geometry_too_complex; past the compile deadline,
// compile_timeout (geometry/compile_budget.hpp).
#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "geometry/box3.hpp"
#include "implicit/geometry/implicit_surface.hpp"
#include "seeding/point_index.hpp"

namespace footpoint {

struct ImplicitSurfaceCellSettings {
  // Leaves are at most this many levels below the box (edges 2^-levels of the box's).
  int levels = 5;
  // Cells examined before the surface is refused as too intricate for its box (a full octree of
  // 5 levels has 37449).
  std::size_t max_cells = 30000;
};

struct ImplicitSurfaceCell {
  Box3 box;
  std::int32_t first_child = -1;  // children are consecutive; -1 for a leaf
  std::int32_t children = 0;
  std::int32_t sample = -1;  // leaves: index of its sample point, or -1 (Newton did not land)
};

// Where S meets an edge of the box (a corner when the point is one).
struct BoxEdgePoint {
  Vec3 x;
  bool corner = false;
};

struct ImplicitSurfaceCells {
  Box3 box;
  std::vector<ImplicitSurfaceCell> cells;  // cells[0] is the box itself, unless S misses it (no cells)
  std::vector<Vec3> samples;
  std::shared_ptr<const PointIndex> sample_index;  // a k-d tree over the samples (the nearest to p)
  std::vector<BoxEdgePoint> edge_points;
  std::vector<Vec3> singular_points;
  std::size_t examined = 0;  // cells whose enclosure was computed
  std::size_t leaves = 0;
  double leaf_diagonal = 0.0;  // every leaf's (the box's over 2^levels)
  bool empty() const { return cells.empty(); }
  std::size_t memory_bytes() const;
};

ImplicitSurfaceCells subdivide_surface(const ImplicitSurfaceEquation& equation, const Box3& box,
                                       const ImplicitSurfaceCellSettings& settings = {});

// The child `octant` (bit k: the upper half along axis k) of a box.
Box3 octant_of(const Box3& box, int octant);

// Newton steps along the gradient, x - f / |grad f|^2 grad f ([Hartmann] eq. of the surface point),
// from x until |f| / |grad f| is below 1e-14 (1 + |x|); false when the gradient vanishes, the
// iterates are not finite or do not settle within `iterations` steps.
bool land_on_surface(const ImplicitSurfaceEquation& equation, Vec3& x, int iterations = 40);

}  // namespace footpoint
