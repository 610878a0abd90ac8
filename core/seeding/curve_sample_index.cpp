#include "seeding/curve_sample_index.hpp"

#include <cmath>
#include <limits>

#include "seeding/points_kd_tree.hpp"

namespace footpoint {
namespace {

// A nanoflann result set that keeps, among the samples within the search radius, only the
// discrete local minima of the distance along the curve (each sample is compared with its linked
// neighbours), and tracks the nearest sample. The radius |p - nearest| + margin shrinks as nearer
// samples are met, which prunes the tree like a nearest-neighbour search.
class LocalMinimaResultSet {
 public:
  LocalMinimaResultSet(const CurveSamples& s, Vec3 p, double margin, SampleCandidates& out)
      : s_(s), p_(p), margin_(margin), out_(out) {
    out_.count = 0;
  }
  double worstDist() const { return radius2_; }
  bool full() const { return true; }
  bool addPoint(double d2, std::uint32_t index) {
    if (d2 < nearest2_) {
      nearest2_ = d2;
      nearest_ = static_cast<std::int32_t>(index);
      const double r = std::sqrt(d2) + margin_;
      radius2_ = r * r;
    }
    const auto i = static_cast<std::size_t>(index);
    if (s_.prev[i] >= 0 && norm2(p_ - s_.points[static_cast<std::size_t>(s_.prev[i])]) < d2) return true;
    if (s_.next[i] >= 0 && norm2(p_ - s_.points[static_cast<std::size_t>(s_.next[i])]) < d2) return true;
    // Insertion into the sorted, bounded list.
    int pos = out_.count < kMaxSampleCandidates ? out_.count : kMaxSampleCandidates - 1;
    if (out_.count == kMaxSampleCandidates && !(d2 < out_.items[static_cast<std::size_t>(pos)].distance2))
      return true;
    while (pos > 0 && out_.items[static_cast<std::size_t>(pos - 1)].distance2 > d2) {
      out_.items[static_cast<std::size_t>(pos)] = out_.items[static_cast<std::size_t>(pos - 1)];
      --pos;
    }
    out_.items[static_cast<std::size_t>(pos)] = {static_cast<std::int32_t>(index), d2};
    if (out_.count < kMaxSampleCandidates) ++out_.count;
    return true;
  }
  // Drops the candidates met before the radius shrank to its final value.
  void finish() {
    while (out_.count > 0 && out_.items[static_cast<std::size_t>(out_.count - 1)].distance2 > radius2_)
      --out_.count;
  }
  std::int32_t nearest() const { return nearest_; }
  double nearest2() const { return nearest2_; }

 private:
  const CurveSamples& s_;
  Vec3 p_;
  double margin_;
  SampleCandidates& out_;
  double radius2_ = std::numeric_limits<double>::infinity();
  double nearest2_ = std::numeric_limits<double>::infinity();
  std::int32_t nearest_ = -1;
};

}  // namespace

struct CurveSampleIndex::Tree {
  PointsAdaptor adaptor;
  PointsKdTree tree;
  explicit Tree(const std::vector<Vec3>* points)
      : adaptor{points}, tree(3, adaptor, nanoflann::KDTreeSingleIndexAdaptorParams(16)) {
    if (!points->empty()) tree.buildIndex();
  }
};

CurveSampleIndex::CurveSampleIndex(const CurveSamples& samples)
    : samples_(samples), tree_(std::make_unique<Tree>(&samples.points)) {}

CurveSampleIndex::~CurveSampleIndex() = default;

std::int32_t CurveSampleIndex::nearest(Vec3 p, double& distance2) const {
  return nearest_point(tree_->tree, samples_.points.size(), p, distance2);
}

std::int32_t CurveSampleIndex::nearest_and_local_minima(Vec3 p, double margin, SampleCandidates& out,
                                                        double& nearest2) const {
  LocalMinimaResultSet result(samples_, p, margin, out);
  if (!samples_.points.empty()) {
    const double q[3] = {p.x, p.y, p.z};
    tree_->tree.findNeighbors(result, q, nanoflann::SearchParams());
  }
  result.finish();
  nearest2 = result.nearest2();
  return result.nearest();
}

std::size_t CurveSampleIndex::memory_bytes() const {
  return sizeof(Tree) + tree_->tree.usedMemory(tree_->tree);
}

}  // namespace footpoint
