// The pieces of the Prometheus text exposition format (0.0.4) that every metrics block writes:
// HELP/TYPE headers, sample lines, and histograms recorded lock-free with atomics.
#pragma once
#include <algorithm>
#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <string>

namespace footpoint::server {

// "name{labels} value\n" (value in shortest round-trip form, +Inf or NaN when not finite).
void line(std::string& out, const std::string& name, const std::string& labels, double value);
void header(std::string& out, const char* name, const char* type, const char* help);

// A histogram over the upper bounds `bounds` (seconds): counts per bucket (not cumulative; the
// last is +Inf), the sum in nanoseconds, the count.
template <std::size_t N>
struct Histogram {
  std::array<std::atomic<std::uint64_t>, N + 1> buckets{};
  std::atomic<std::uint64_t> sum_ns{0};
  std::atomic<std::uint64_t> count{0};

  void observe(const std::array<double, N>& bounds, double seconds) {
    std::size_t b = 0;
    while (b < N && seconds > bounds[b]) ++b;
    buckets[b].fetch_add(1, std::memory_order_relaxed);
    sum_ns.fetch_add(static_cast<std::uint64_t>(std::max(0.0, seconds) * 1e9), std::memory_order_relaxed);
    count.fetch_add(1, std::memory_order_relaxed);
  }
};

// The _bucket (cumulative), _sum and _count lines of a histogram.
void histogram_lines(std::string& out, const std::string& name, const std::string& labels,
                     const std::uint64_t* buckets, std::size_t bounds_count, const double* bounds,
                     double sum_seconds, std::uint64_t count);

template <std::size_t N>
void histogram_lines(std::string& out, const std::string& name, const std::string& labels,
                     const Histogram<N>& h, const std::array<double, N>& bounds) {
  std::array<std::uint64_t, N + 1> counts;
  for (std::size_t b = 0; b <= N; ++b) counts[b] = h.buckets[b].load(std::memory_order_relaxed);
  histogram_lines(out, name, labels, counts.data(), N, bounds.data(),
                  static_cast<double>(h.sum_ns.load(std::memory_order_relaxed)) * 1e-9,
                  h.count.load(std::memory_order_relaxed));
}

}  // namespace footpoint::server
