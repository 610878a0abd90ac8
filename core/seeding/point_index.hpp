// A k-d tree (nanoflann) over a copy of a set of points in space, and its one query: the point
// nearest to p. The copy keeps the index valid wherever its owner is moved or copied to.
#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "geometry/vec.hpp"

namespace footpoint {

class PointIndex {
 public:
  explicit PointIndex(std::vector<Vec3> points);
  ~PointIndex();
  PointIndex(const PointIndex&) = delete;
  PointIndex& operator=(const PointIndex&) = delete;

  // The index of the point nearest to p (-1 when there are none); distance2 = |p - point|^2.
  std::int32_t nearest(Vec3 p, double& distance2) const;
  // Whether a point t other than s (t != s) with |t - s| <= radius has |q - t|^2 < distance2.
  bool nearer_within(Vec3 s, double radius, Vec3 q, double distance2) const;
  // The same among the points whose indices `among` lists (sorted ascending).
  bool nearer_within(Vec3 s, double radius, Vec3 q, double distance2,
                     std::span<const std::int32_t> among) const;
  std::size_t memory_bytes() const;

 private:
  struct Tree;
  std::unique_ptr<Tree> tree_;
};

}  // namespace footpoint
