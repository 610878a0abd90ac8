// A closed axis-aligned box in space (planar curves: lo.z = hi.z = 0): the domain of an implicit
// curve, the cells that subdivide it, the enclosures of points.
#pragma once
#include "geometry/vec.hpp"

namespace footpoint {

struct Box3 {
  Vec3 lo, hi;
  bool contains(Vec3 x, double slack = 0.0) const {
    for (int k = 0; k < 3; ++k)
      if (x[k] < lo[k] - slack || x[k] > hi[k] + slack) return false;
    return true;
  }
  bool contains(const Box3& b) const {
    for (int k = 0; k < 3; ++k)
      if (b.lo[k] < lo[k] || b.hi[k] > hi[k]) return false;
    return true;
  }
  bool intersects(const Box3& b) const {
    for (int k = 0; k < 3; ++k)
      if (b.hi[k] < lo[k] || b.lo[k] > hi[k]) return false;
    return true;
  }
  Vec3 center() const { return 0.5 * (lo + hi); }
  double diagonal() const { return norm(hi - lo); }
  double max_edge() const { return std::fmax(std::fmax(hi.x - lo.x, hi.y - lo.y), hi.z - lo.z); }
};

}  // namespace footpoint
