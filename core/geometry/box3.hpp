// A closed axis-aligned box in space (planar curves: lo.z = hi.z = 0): the domain of an implicit
// curve, the cells that subdivide it, the enclosures of points.
#pragma once
#include <algorithm>

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
  // No point: lo > hi along some axis (or a NaN bound), as an intersection of disjoint boxes is.
  bool empty() const {
    for (int k = 0; k < 3; ++k)
      if (!(lo[k] <= hi[k])) return true;
    return false;
  }
  Vec3 center() const { return 0.5 * (lo + hi); }
  double diagonal() const { return norm(hi - lo); }
  double max_edge() const { return std::fmax(std::fmax(hi.x - lo.x, hi.y - lo.y), hi.z - lo.z); }
};

// Coordinate by coordinate: the smaller and the larger of a and b.
inline Vec3 min(Vec3 a, Vec3 b) { return {std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)}; }
inline Vec3 max(Vec3 a, Vec3 b) { return {std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)}; }

// The smallest box holding a and b.
inline Box3 hull(const Box3& a, const Box3& b) { return {min(a.lo, b.lo), max(a.hi, b.hi)}; }

// The points common to a and b: empty() when the boxes do not meet.
inline Box3 intersection(const Box3& a, const Box3& b) { return {max(a.lo, b.lo), min(a.hi, b.hi)}; }

}  // namespace footpoint
