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
//  - room for each leaf's enclosures of f, grad f and the Hessian over it and of f and grad f at
//    its centre, which the certificate's bounds of a whole leaf use for every point p (they do not
//    depend on p): computed on a leaf's first use and kept (LeafEnclosureCache);
//  - the singular points of S (f = 0 and grad f = 0: a cone's apex), found by Newton on grad f = 0
//    from the leaves where the gradient's enclosure holds 0.
// Beyond the cell budget: GeometryError geometry_too_complex; past the compile deadline,
// compile_timeout (geometry/compile_budget.hpp).
#pragma once
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <type_traits>
#include <vector>

#include "geometry/box3.hpp"
#include "geometry/compile_budget.hpp"
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
  std::int32_t leaf = -1;    // leaves: its index in the leaf enclosure cache
};

// A leaf's enclosures: ImplicitSurfaceEquation::interval_jet over the leaf, value_enclosure and
// interval_gradient at its centre.
struct LeafEnclosures {
  ImplicitSurfaceIntervalJet over;
  Interval centre_value;
  Interval centre_f;
  IVec3 centre_grad{};
};
static_assert(std::is_trivially_copyable_v<LeafEnclosures>);

// Each leaf's LeafEnclosures, computed on first use and kept, from any number of threads: the
// first thread to claim a leaf (its state 0 -> 1) stores the enclosures and publishes them
// (state 2, release); a thread that finds the leaf claimed but not published computes its own.
class LeafEnclosureCache {
 public:
  void reset(std::size_t leaves);
  LeafEnclosures get(const ImplicitSurfaceEquation& equation, std::int32_t leaf, const Box3& box) const;
  std::size_t memory_bytes() const;

 private:
  std::size_t size_ = 0;
  std::unique_ptr<std::atomic<std::uint8_t>[]> state_;
  std::unique_ptr<unsigned char[]> storage_;  // LeafEnclosures, trivially copyable, by memcpy
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
  LeafEnclosureCache leaf_enclosures;
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
                                       CompileBudget& budget,
                                       const ImplicitSurfaceCellSettings& settings = {});

// The child `octant` (bit k: the upper half along axis k) of a box.
Box3 octant_of(const Box3& box, int octant);

// Newton steps along the gradient, x - f / |grad f|^2 grad f ([Hartmann] eq. of the surface point),
// from x until |f| / |grad f| is below 1e-14 (1 + |x|); false when the gradient vanishes, the
// iterates are not finite or do not settle within `iterations` steps.
bool land_on_surface(const ImplicitSurfaceEquation& equation, Vec3& x, int iterations = 40);

}  // namespace footpoint
