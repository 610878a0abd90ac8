#include "seeding/point_index.hpp"

#include <algorithm>
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

namespace {

// A nanoflann result set over the points within a radius of s that stops at the first one nearer
// to q than distance2 (the radius is checked again exactly: nanoflann's bound is strict).
class NearerWithin {
 public:
  NearerWithin(const std::vector<Vec3>& points, Vec3 s, double radius, Vec3 q, double distance2,
               std::span<const std::int32_t> among, bool restricted)
      : points_(points),
        s_(s),
        q_(q),
        r2_(radius * radius),
        d2_(distance2),
        worst_(r2_ * (1.0 + 1e-12)),
        among_(among),
        restricted_(restricted) {}
  double worstDist() const { return worst_; }
  bool full() const { return true; }
  bool addPoint(double, std::uint32_t index) {
    const Vec3 t = points_[index];
    if (t.x == s_.x && t.y == s_.y && t.z == s_.z) return true;
    if (norm2(t - s_) <= r2_ && norm2(q_ - t) < d2_ &&
        (!restricted_ ||
         std::binary_search(among_.begin(), among_.end(), static_cast<std::int32_t>(index)))) {
      found_ = true;
      return false;  // done
    }
    return true;
  }
  bool found() const { return found_; }

 private:
  const std::vector<Vec3>& points_;
  Vec3 s_, q_;
  double r2_, d2_, worst_;
  std::span<const std::int32_t> among_;
  bool restricted_;
  bool found_ = false;
};

bool nearer_in(const PointsKdTree& tree, const std::vector<Vec3>& points, NearerWithin& result, Vec3 s) {
  if (points.empty()) return false;
  const double at[3] = {s.x, s.y, s.z};
  tree.findNeighbors(result, at, nanoflann::SearchParams());
  return result.found();
}

}  // namespace

bool PointIndex::nearer_within(Vec3 s, double radius, Vec3 q, double distance2) const {
  NearerWithin result(tree_->points, s, radius, q, distance2, {}, false);
  return nearer_in(tree_->tree, tree_->points, result, s);
}

bool PointIndex::nearer_within(Vec3 s, double radius, Vec3 q, double distance2,
                               std::span<const std::int32_t> among) const {
  NearerWithin result(tree_->points, s, radius, q, distance2, among, true);
  return nearer_in(tree_->tree, tree_->points, result, s);
}

std::size_t PointIndex::memory_bytes() const {
  return sizeof(Tree) + tree_->points.capacity() * sizeof(Vec3) + tree_->tree.usedMemory(tree_->tree);
}

}  // namespace footpoint
