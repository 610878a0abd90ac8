// Prometheus metrics (text exposition format 0.0.4), recorded lock-free with atomics:
//   footpoint_build_info{version}                            gauge (1)
//   process_*                                                the process's (process_metrics.hpp)
//   footpoint_http_requests_total{route,status}              counter
//   footpoint_http_request_duration_seconds{route}           histogram
//   footpoint_api_key_requests_total{key,status}             counter (with --api-keys)
//   footpoint_http_requests_in_flight                        gauge
//   footpoint_points_in_flight                               gauge
//   footpoint_memory_in_flight_bytes, footpoint_memory_budget_bytes   gauges (--max-inflight-bytes)
//   footpoint_memory_refusals_total                          counter (503 by that budget)
//   footpoint_points_projected_total                         counter
//   footpoint_projections_total{status}                      counter (solver statuses)
//   footpoint_batches_cancelled_total, footpoint_points_cancelled_total   counters (client gone)
//   footpoint_read_timeouts_total                            counter (--read-timeout-s)
//   footpoint_geometry_compile_seconds                       histogram
//   footpoint_geometry_cache_{entries,bytes}                 gauges
//   footpoint_geometry_cache_{hits,misses,evictions}_total   counters
//   footpoint_geometry_compilations_total{result}            counter (ok, error)
//   footpoint_worker_threads, footpoint_worker_queue_tasks   gauges (the numerical pool)
//   footpoint_shutting_down                                  gauge (1 while draining)
//   footpoint_registry_*                                     the shared registry's (registry_metrics.hpp)
#pragma once
#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <map>
#include <mutex>
#include <string>
#include <utility>

#include "cache/geometry_cache.hpp"
#include "projection/projection_result.hpp"
#include "prometheus_text.hpp"
#include "registry_metrics.hpp"
#include "route.hpp"

namespace footpoint::server {

class Metrics {
 public:
  // One answered request: its route, status and duration from the first header byte read.
  void observe_request(Route route, int status, double seconds);
  // One request that named a known API key (the key's name, never its secret).
  void observe_key(const std::string& key, int status);
  void observe_compile(double seconds);
  // The statuses of the points of one request (indexed by Status).
  static constexpr int kStatusCount = static_cast<int>(Status::deadline_exceeded) + 1;
  void add_projections(const std::array<std::uint64_t, kStatusCount>& by_status);
  // One batch dropped because its client closed the connection, and its points never started.
  void add_cancelled(std::size_t dropped_points);
  // One connection closed because its request did not arrive within --read-timeout-s.
  void add_read_timeout() { read_timeouts_.fetch_add(1, std::memory_order_relaxed); }

  struct Gauges {
    GeometryCacheStats cache;
    unsigned worker_threads = 0;
    std::size_t worker_queue = 0;
    std::size_t in_flight = 0;
    std::size_t in_flight_points = 0;
    std::size_t in_flight_bytes = 0;     // reserved from --max-inflight-bytes
    std::size_t max_inflight_bytes = 0;  // the budget
    std::uint64_t memory_refusals = 0;   // requests refused by it
    bool shutting_down = false;
    const RegistryMetrics* registry = nullptr;  // the shared registry's, when there is one
  };
  std::string render(const Gauges& gauges) const;

  // Latency buckets (upper bounds in seconds) for requests and compilations.
  static constexpr std::array<double, 14> kRequestBuckets{
      0.0001, 0.00025, 0.0005, 0.001, 0.0025, 0.005, 0.01, 0.025, 0.05, 0.1, 0.25, 1.0, 5.0, 30.0};
  static constexpr std::array<double, 10> kCompileBuckets{0.0001, 0.0005, 0.001, 0.005, 0.01,
                                                          0.05,   0.1,    0.5,   1.0,   5.0};

 private:
  // Statuses counted by name; anything else lands in "other".
  static constexpr std::array<int, 21> kHttpStatuses{200, 201, 204, 400, 401, 403, 404, 405, 408, 411, 413,
                                                     414, 415, 416, 422, 429, 499, 500, 503, 507, 0};
  static int status_index(int status);

  std::array<std::array<std::atomic<std::uint64_t>, kHttpStatuses.size()>, kRouteCount> requests_{};
  std::array<Histogram<kRequestBuckets.size()>, kRouteCount> durations_{};
  Histogram<kCompileBuckets.size()> compile_{};
  std::array<std::atomic<std::uint64_t>, kStatusCount> projections_{};
  std::atomic<std::uint64_t> points_{0};
  std::atomic<std::uint64_t> batches_cancelled_{0}, points_cancelled_{0}, read_timeouts_{0};
  // Requests by key name and status: as many names as the keys file holds.
  mutable std::mutex keys_mutex_;
  std::map<std::pair<std::string, int>, std::uint64_t> by_key_;
};

}  // namespace footpoint::server
