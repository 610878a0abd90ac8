// What `auto` precomputes once per parametric surface and reuses for every point: an adaptive
// subdivision of the parameter domain into cells, stored as a binary tree (a bounding-volume
// hierarchy over the parameter rectangles), with
//  - per cell: the jet of s at the cell's centre (value, first and second partials), and ρ, a bound
//    on |s(t) - (s_c + s_u δu + s_v δv)| over the cell (the tangent-plane model's error, estimated
//    from 16 samples plus twice the quadratic model's error there, which bounds the gap between the
//    samples), and ρ2, the same for the quadratic model (twice its sampled error);
//  - per node: an axis-aligned box containing s over the node's rectangle. For a leaf it is the
//    formula engine's interval enclosure (rigorous, outward rounded); a parent's box is the union
//    of its children's. dist(p, box) is a lower bound on the distance from p to that part of the
//    surface.
// Cells are split (in the direction where the surface is longer) until the tangent-plane model is
// good to `flatness` of the cell's size, so that the Newton model of a cell predicts where the
// distance is least, and most points need a single local solve.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "geometry/parametric_surface.hpp"

namespace footpoint {

struct SurfaceSeedingOptions {
  // Uniform subdivision first, to at least this many cells: no feature narrower than a cell of
  // this grid is missed by the error estimate.
  int min_cells = 256;
  // Refinement stops here whatever the flatness (memory: about 250 bytes per cell).
  int max_cells = 4096;
  // Refine while ρ > flatness x the cell's extent on the surface (chord length).
  double flatness = 0.05;
};

struct SurfaceCell {
  double u0 = 0.0, u1 = 0.0, v0 = 0.0, v1 = 0.0;  // the parameter rectangle
  SurfaceJet centre;                              // s and its partials at ((u0+u1)/2, (v0+v1)/2)
  double rho = 0.0;                               // tangent-plane model error bound (see above)
  double rho2 = 0.0;                              // the same for the quadratic (Taylor) model
  double extent = 0.0;                            // largest chord of the cell on the surface
  bool finite = true;                             // the centre jet is finite
  bool resolved = true;                           // ρ <= flatness x extent (refinement succeeded)
  double uc() const { return 0.5 * (u0 + u1); }
  double vc() const { return 0.5 * (v0 + v1); }
};

struct SurfaceCellNode {
  Vec3 lo, hi;                 // box containing s over the node's rectangle
  std::int32_t child[2]{-1, -1};
  std::int32_t cell = -1;      // leaf: index into cells()
  bool leaf() const { return cell >= 0; }
};

class SurfaceCells {
 public:
  SurfaceCells(const SurfaceFormulas& formulas, const ParamBox& box, const SurfaceSeedingOptions& options = {});

  const std::vector<SurfaceCellNode>& nodes() const { return nodes_; }  // nodes()[0] is the root
  const std::vector<SurfaceCell>& cells() const { return cells_; }
  int depth() const { return depth_; }
  std::size_t memory_bytes() const;

  // Lower bound on |p - x| over the node's box (0 inside it).
  static double box_distance(const SurfaceCellNode& node, const Vec3& p);

 private:
  std::vector<SurfaceCellNode> nodes_;
  std::vector<SurfaceCell> cells_;
  int depth_ = 0;
};

}  // namespace footpoint
