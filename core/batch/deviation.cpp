#include "batch/deviation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace footpoint {

double deviation_of(const ProjectionResult& r) {
  if (std::isfinite(r.signed_distance)) return r.signed_distance;
  if (std::isfinite(r.distance)) return r.distance;
  return std::numeric_limits<double>::quiet_NaN();
}

namespace {

// Neumaier's compensated sum: the mean and RMS of 10^7 deviations keep their digits whatever the
// order of magnitude of the terms.
void compensated_add(double& total, double& c, double x) {
  const double t = total + x;
  c += std::fabs(total) >= std::fabs(x) ? (total - t) + x : (x - t) + total;
  total = t;
}

// histogram_bins + 1 edges from min to max (one bin of width 0 when min = max) and zero counts.
void set_edges(DeviationStats& s, const DeviationOptions& options) {
  const int bins = s.max > s.min ? std::max(1, options.histogram_bins) : 1;
  s.edges.resize(static_cast<std::size_t>(bins) + 1);
  for (int k = 0; k <= bins; ++k) s.edges[static_cast<std::size_t>(k)] = s.min + (s.max - s.min) * k / bins;
  s.edges.back() = s.max;
  s.counts.assign(static_cast<std::size_t>(bins), 0);
}

// The bin of d in [min, max]: bin k holds [edge_k, edge_k+1), the last one [edge_bins-1, max].
std::size_t bin_of(const DeviationStats& s, double d) {
  const std::size_t bins = s.counts.size();
  const double width = s.max - s.min;
  // (a width beyond the largest double makes the share NaN: the edges place the value)
  const double share = width > 0.0 ? (d - s.min) / width * static_cast<double>(bins) : 0.0;
  std::size_t k = share >= 1.0 ? static_cast<std::size_t>(std::min(share, bins - 1.0)) : 0;
  // the computed index may sit one off at an edge: the edges decide
  while (k > 0 && d < s.edges[k]) --k;
  while (k + 1 < bins && d >= s.edges[k + 1]) ++k;
  return k;
}

}  // namespace

void DeviationMoments::add(double d, bool has_sign, const DeviationOptions& options) {
  min = count == 0 ? d : std::min(min, d);
  max = count == 0 ? d : std::max(max, d);
  ++count;
  if (has_sign) ++signed_count;
  compensated_add(sum, sum_c, d);
  compensated_add(squares, squares_c, d * d);
  if (options.tolerance_band && d >= (*options.tolerance_band)[0] && d <= (*options.tolerance_band)[1])
    ++within_band;
}

DeviationStats DeviationMoments::stats() const {
  DeviationStats s;
  s.count = count;
  s.signed_count = signed_count;
  s.within_band = within_band;
  if (count == 0) return s;
  s.min = min;
  s.max = max;
  const double n = static_cast<double>(count);
  s.mean = (sum + sum_c) / n;
  s.rms = std::sqrt((squares + squares_c) / n);
  return s;
}

DeviationAccumulator::DeviationAccumulator(const DeviationOptions& options) : options_(options) {}

void DeviationAccumulator::add(const ProjectionResult& r) {
  const double d = deviation_of(r);
  if (std::isfinite(d)) add(d, std::isfinite(r.signed_distance));
}

void DeviationAccumulator::add(double d, bool has_sign) {
  moments_.add(d, has_sign, options_);
  if (fine_.empty() && exact_.size() < kExactValues) {
    exact_.push_back(d);
    return;
  }
  if (fine_.empty()) {
    // from the values to sub-bins over [min, max] (their halves), the first range
    const std::size_t bins = static_cast<std::size_t>(std::max(1, options_.histogram_bins));
    fine_.assign(std::max(kMinFineBins, kFineBinsPerBin * bins), 0);
    const double lo = moments_.min / 2, hi = moments_.max / 2;
    fine_lo_ = lo;
    fine_width_ =
        hi > lo ? (hi - lo) / static_cast<double>(fine_.size() - 1) : std::max(std::fabs(lo), 1.0) * 0x1p-40;
    for (const double v : exact_) add_fine(v / 2);
    exact_ = std::vector<double>();
  }
  add_fine(d / 2);
}

void DeviationAccumulator::add_fine(double half) {
  const double m = static_cast<double>(fine_.size());
  if (!(half >= fine_lo_ && half < fine_lo_ + m * fine_width_)) widen(half);
  const double at = (half - fine_lo_) / fine_width_;
  // (NaN bounds after absurd ranges fall to an end instead of a conversion without a value)
  const std::size_t k = at >= 0.0 ? static_cast<std::size_t>(std::min(at, m - 1.0)) : 0;
  ++fine_[k];
}

void DeviationAccumulator::widen(double half) {
  const std::size_t n = fine_.size();
  const double m = static_cast<double>(n);
  const bool up = half >= fine_lo_;
  const double hi = fine_lo_ + m * fine_width_;
  int k = 0;
  double w = fine_width_;
  // the range [lo, lo + m w) doubles k times, anchored at its low end (up) or its high end
  while (k < 2100 && (up ? !(half < fine_lo_ + m * w) : half < hi - m * w)) {
    w *= 2;
    ++k;
  }
  std::vector<std::size_t> merged(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    if (fine_[i] == 0) continue;
    std::size_t j;
    if (k >= 40)
      j = up ? 0 : n - 1;
    else if (up)
      j = i >> k;
    else  // sub-bin i sits n (2^k - 1) old widths above the new low end
      j = static_cast<std::size_t>((i + n * ((std::uint64_t{1} << k) - 1)) >> k);
    merged[j] += fine_[i];
  }
  fine_ = std::move(merged);
  if (!up) fine_lo_ = hi - m * w;
  fine_width_ = w;
}

DeviationStats DeviationAccumulator::stats() const {
  DeviationStats s = moments_.stats();
  if (s.count == 0) return s;
  set_edges(s, options_);
  if (fine_.empty()) {
    for (const double d : exact_) ++s.counts[bin_of(s, d)];
    return s;
  }
  for (std::size_t i = 0; i < fine_.size(); ++i) {
    if (fine_[i] == 0) continue;
    const double middle = 2 * (fine_lo_ + (static_cast<double>(i) + 0.5) * fine_width_);
    s.counts[bin_of(s, std::clamp(middle, s.min, s.max))] += fine_[i];
  }
  s.histogram_resolution = 2 * fine_width_;
  return s;
}

DeviationStats deviation_stats(const std::vector<ProjectionResult>& results,
                               const DeviationOptions& options) {
  DeviationMoments moments;
  for (const auto& r : results)
    if (const double d = deviation_of(r); std::isfinite(d))
      moments.add(d, std::isfinite(r.signed_distance), options);
  DeviationStats s = moments.stats();
  if (s.count == 0) return s;
  set_edges(s, options);
  for (const auto& r : results)
    if (const double d = deviation_of(r); std::isfinite(d)) ++s.counts[bin_of(s, d)];
  return s;
}

}  // namespace footpoint
