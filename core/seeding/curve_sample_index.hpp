// A k-d tree (nanoflann) over the samples of a curve, and the one query `auto` needs: the samples
// near p that are discrete local minima of the distance along the curve. No allocation per query.
#pragma once
#include <array>
#include <cstdint>
#include <memory>

#include "geometry/vec.hpp"
#include "seeding/curve_samples.hpp"

namespace footpoint {

struct SampleCandidate {
  std::int32_t index = -1;
  double distance2 = 0.0;  // |p - sample|^2
};

// At most kMaxSampleCandidates candidates are kept, the nearest ones (more arise only where the
// distance is nearly constant along the curve, p near an axis of symmetry, and then any of the
// nearest is as good).
inline constexpr int kMaxSampleCandidates = 24;
struct SampleCandidates {
  std::array<SampleCandidate, kMaxSampleCandidates> items;
  int count = 0;
};

class CurveSampleIndex {
 public:
  // Indexes samples.points; `samples` must outlive the index and not change after.
  explicit CurveSampleIndex(const CurveSamples& samples);
  ~CurveSampleIndex();
  CurveSampleIndex(const CurveSampleIndex&) = delete;
  CurveSampleIndex& operator=(const CurveSampleIndex&) = delete;

  // The sample nearest to p (-1 when there are no samples); distance2 = |p - sample|^2.
  std::int32_t nearest(Vec3 p, double& distance2) const;

  // In one pass of the tree: the nearest sample (returned, -1 when there are none; nearest2 =
  // |p - sample|^2) and every sample s within |p - nearest| + margin of p with
  // |p - s| <= |p - neighbour| for its neighbours along the curve (a discrete local minimum of
  // the distance), nearest first. margin = infinity lists every discrete local minimum.
  std::int32_t nearest_and_local_minima(Vec3 p, double margin, SampleCandidates& out, double& nearest2) const;

  // The samples it indexes.
  const CurveSamples& samples() const { return samples_; }
  std::size_t memory_bytes() const;

 private:
  struct Tree;
  const CurveSamples& samples_;
  std::unique_ptr<Tree> tree_;
};

}  // namespace footpoint
