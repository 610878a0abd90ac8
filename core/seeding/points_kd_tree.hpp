// nanoflann's k-d tree over a std::vector<Vec3>, for the sample indexes (curve_sample_index,
// point_index): the adaptor answers "how many points" and "coordinate k of point i".
#pragma once
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include <nanoflann.hpp>

#include "geometry/vec.hpp"

namespace footpoint {

struct PointsAdaptor {
  const std::vector<Vec3>* points;
  std::size_t kdtree_get_point_count() const { return points->size(); }
  double kdtree_get_pt(std::size_t i, std::size_t k) const { return (*points)[i][static_cast<int>(k)]; }
  template <class Box>
  bool kdtree_get_bbox(Box&) const {
    return false;
  }
};

using PointsKdTree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, PointsAdaptor>,
                                                         PointsAdaptor, 3, std::uint32_t>;

// The index of the point of the tree nearest to p (-1 when it has none); distance2 = |p - point|^2.
inline std::int32_t nearest_point(const PointsKdTree& tree, std::size_t count, Vec3 p, double& distance2) {
  distance2 = std::numeric_limits<double>::infinity();
  if (count == 0) return -1;
  std::uint32_t index = 0;
  nanoflann::KNNResultSet<double, std::uint32_t> result(1);
  result.init(&index, &distance2);
  const double q[3] = {p.x, p.y, p.z};
  tree.findNeighbors(result, q, nanoflann::SearchParams());
  return static_cast<std::int32_t>(index);
}

}  // namespace footpoint
