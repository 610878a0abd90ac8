// The statistics of a batch's deviations, what inspection reads off a scan: per point the signed
// distance (ProjectionResult::signed_distance), or the distance where the geometry has no normal
// there; points without a finite answer are not counted. Count, extremes, mean, root mean square,
// a histogram of equal bins over [min, max], and the share within a tolerance band.
#pragma once
#include <array>
#include <cstddef>
#include <optional>
#include <vector>

#include "geometry/projection_result.hpp"

namespace footpoint {

struct DeviationOptions {
  static constexpr int kDefaultBins = 20;
  static constexpr int kMaxBins = 10000;
  int histogram_bins = kDefaultBins;
  std::optional<std::array<double, 2>> tolerance_band;  // [lo, hi], lo <= hi
};

struct DeviationStats {
  std::size_t count = 0;                               // points with a finite deviation
  std::size_t signed_count = 0;                        // of them, those with a sign (a normal at the foot)
  double min = 0.0, max = 0.0, mean = 0.0, rms = 0.0;  // meaningful when count > 0
  // histogram_bins + 1 edges from min to max (the last bin closed; one bin when min = max), and
  // the counts of the bins; empty when count is 0.
  std::vector<double> edges;
  std::vector<std::size_t> counts;
  std::size_t within_band = 0;  // deviations d with lo <= d <= hi (tolerance_band given)
};

// The deviation of one result: its signed distance, else its distance; NaN without an answer.
double deviation_of(const ProjectionResult& r);

// Collects the deviations of results in any number of pieces (a stream's windows), in order.
class DeviationAccumulator {
 public:
  void add(const ProjectionResult& r);
  DeviationStats stats(const DeviationOptions& options) const;

 private:
  std::vector<double> values_;  // finite deviations
  std::size_t signed_count_ = 0;
};

DeviationStats deviation_stats(const std::vector<ProjectionResult>& results, const DeviationOptions& options);

}  // namespace footpoint
