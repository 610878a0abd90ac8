// The statistics of a batch's deviations, what inspection reads off a scan: per point the signed
// distance (ProjectionResult::signed_distance), or the distance where the geometry has no normal
// there; points without a finite answer are not counted. Count, extremes, mean, root mean square,
// a histogram of equal bins over [min, max], and the share within a tolerance band.
//
// Memory. Count, extremes, sums and the band are kept as running values. The histogram's bins
// depend on the final min and max, so one pass cannot place every value exactly without keeping
// it: deviation_stats reads its results twice (exact), and DeviationAccumulator (one pass, a
// stream's windows) keeps the values themselves up to kExactValues, then a fine histogram of
// kFineBinsPerBin sub-bins per bin (at least kMinFineBins) over a range that doubles when a value
// falls outside it (the sub-bins merged in pairs). Each sub-bin's count goes to the bin holding
// its middle: a deviation farther than histogram_resolution (the sub-bin width) from every edge
// is counted in its own bin, one nearer may be counted in the neighbouring one; min, max, mean,
// RMS, the counts' sum and the band stay exact.
#pragma once
#include <array>
#include <cstddef>
#include <optional>
#include <vector>

#include "projection/projection_result.hpp"

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
  // 0: every deviation is counted in its bin; else one within this distance of an edge may be
  // counted in the bin on the edge's other side
  double histogram_resolution = 0.0;
};

// The deviation of one result: its signed distance, else its distance; NaN without an answer.
double deviation_of(const ProjectionResult& r);

// Count, extremes, compensated sums and the band of deviations, one at a time.
struct DeviationMoments {
  std::size_t count = 0, signed_count = 0, within_band = 0;
  double min = 0.0, max = 0.0, sum = 0.0, sum_c = 0.0, squares = 0.0, squares_c = 0.0;
  void add(double d, bool has_sign, const DeviationOptions& options);
  // count, signed_count, min, max, mean, rms, within_band
  DeviationStats stats() const;
};

// Collects the deviations of results in any number of pieces (a stream's windows) in memory
// bounded by the number of bins (see above).
class DeviationAccumulator {
 public:
  static constexpr std::size_t kExactValues = std::size_t{1} << 16;
  static constexpr std::size_t kFineBinsPerBin = 64, kMinFineBins = 4096;

  explicit DeviationAccumulator(const DeviationOptions& options = {});
  void add(const ProjectionResult& r);
  void add(double deviation, bool has_sign);
  DeviationStats stats() const;

 private:
  void add_fine(double half);
  // Widens the fine range by a power of two until it holds `half`.
  void widen(double half);

  DeviationOptions options_;
  DeviationMoments moments_;
  std::vector<double> exact_;                // the finite deviations while there are at most kExactValues
  std::vector<std::size_t> fine_;            // then the sub-bins' counts, over d / 2 (no overflow of ranges)
  double fine_lo_ = 0.0, fine_width_ = 0.0;  // sub-bin k holds d / 2 in [lo + k w, lo + (k + 1) w)
};

// Exact statistics, reading the results twice.
DeviationStats deviation_stats(const std::vector<ProjectionResult>& results, const DeviationOptions& options);

}  // namespace footpoint
