#include "batch/deviation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace footpoint {

double deviation_of(const ProjectionResult& r) {
  if (std::isfinite(r.signed_distance)) return r.signed_distance;
  if (std::isfinite(r.distance)) return r.distance;
  return std::numeric_limits<double>::quiet_NaN();
}

void DeviationAccumulator::add(const ProjectionResult& r) {
  const double d = deviation_of(r);
  if (!std::isfinite(d)) return;
  values_.push_back(d);
  if (std::isfinite(r.signed_distance)) ++signed_count_;
}

DeviationStats DeviationAccumulator::stats(const DeviationOptions& options) const {
  DeviationStats s;
  s.count = values_.size();
  s.signed_count = signed_count_;
  if (s.count == 0) return s;
  const auto [lo, hi] = std::minmax_element(values_.begin(), values_.end());
  s.min = *lo;
  s.max = *hi;
  // Neumaier's compensated sums of d and d^2: the mean and RMS of 10^7 deviations keep their
  // digits whatever the order of magnitude of the terms.
  double sum = 0.0, sum_c = 0.0, squares = 0.0, squares_c = 0.0;
  auto add = [](double& total, double& c, double x) {
    const double t = total + x;
    c += std::fabs(total) >= std::fabs(x) ? (total - t) + x : (x - t) + total;
    total = t;
  };
  for (const double d : values_) {
    add(sum, sum_c, d);
    add(squares, squares_c, d * d);
  }
  const double n = static_cast<double>(s.count);
  s.mean = (sum + sum_c) / n;
  s.rms = std::sqrt((squares + squares_c) / n);

  // equal deviations make one bin of width 0
  const int bins = s.max > s.min ? std::max(1, options.histogram_bins) : 1;
  s.edges.resize(static_cast<std::size_t>(bins) + 1);
  for (int k = 0; k <= bins; ++k) s.edges[static_cast<std::size_t>(k)] = s.min + (s.max - s.min) * k / bins;
  s.edges.back() = s.max;
  s.counts.assign(static_cast<std::size_t>(bins), 0);
  const double width = s.max - s.min;
  for (const double d : values_) {
    // bin k holds [edge_k, edge_k+1), the last one [edge_bins-1, max]
    // (a width beyond the largest double makes the share NaN: the edges place the value)
    const double share = width > 0.0 ? (d - s.min) / width * bins : 0.0;
    std::size_t k = share >= 1.0 ? static_cast<std::size_t>(std::min(share, bins - 1.0)) : 0;
    // the computed index may sit one off at an edge: the edges decide
    while (k > 0 && d < s.edges[k]) --k;
    while (k + 1 < static_cast<std::size_t>(bins) && d >= s.edges[k + 1]) ++k;
    ++s.counts[k];
  }
  if (options.tolerance_band) {
    // (named copies, not a structured binding: clang 14 cannot capture one in a lambda)
    const double band_lo = (*options.tolerance_band)[0], band_hi = (*options.tolerance_band)[1];
    s.within_band = static_cast<std::size_t>(std::count_if(
        values_.begin(), values_.end(), [&](double d) { return d >= band_lo && d <= band_hi; }));
  }
  return s;
}

DeviationStats deviation_stats(const std::vector<ProjectionResult>& results,
                               const DeviationOptions& options) {
  DeviationAccumulator a;
  for (const auto& r : results) a.add(r);
  return a.stats(options);
}

}  // namespace footpoint
