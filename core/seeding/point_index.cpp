#include "seeding/point_index.hpp"

#include <limits>

#include "seeding/points_kd_tree.hpp"

namespace footpoint {

struct PointIndex::Tree {
  std::vector<Vec3> points;
  PointsAdaptor adaptor;
  PointsKdTree tree;
  explicit Tree(std::vector<Vec3> p)
      : points(std::move(p)),
        adaptor{&points},
        tree(3, adaptor, nanoflann::KDTreeSingleIndexAdaptorParams(8)) {
    if (!points.empty()) tree.buildIndex();
  }
};

PointIndex::PointIndex(std::vector<Vec3> points) : tree_(std::make_unique<Tree>(std::move(points))) {}

PointIndex::~PointIndex() = default;

std::int32_t PointIndex::nearest(Vec3 p, double& distance2) const {
  return nearest_point(tree_->tree, tree_->points.size(), p, distance2);
}

std::size_t PointIndex::memory_bytes() const {
  return sizeof(Tree) + tree_->points.capacity() * sizeof(Vec3) + tree_->tree.usedMemory(tree_->tree);
}

}  // namespace footpoint
