#include "metrics.hpp"

#include <algorithm>
#include <cmath>

#include "json_writer.hpp"
#include "process_metrics.hpp"
#include "prometheus_text.hpp"
#include "version.hpp"

namespace footpoint::server {

void line(std::string& out, const std::string& name, const std::string& labels, double value) {
  out += name;
  if (!labels.empty()) out += "{" + labels + "}";
  out += ' ';
  if (std::isfinite(value))
    append_shortest(out, value);
  else
    out += value > 0 ? "+Inf" : "NaN";
  out += '\n';
}

void header(std::string& out, const char* name, const char* type, const char* help) {
  out += std::string("# HELP ") + name + " " + help + "\n# TYPE " + name + " " + type + "\n";
}

void histogram_lines(std::string& out, const std::string& name, const std::string& labels,
                     const std::uint64_t* buckets, std::size_t bounds_count, const double* bounds,
                     double sum_seconds, std::uint64_t count) {
  const std::string sep = labels.empty() ? "" : labels + ",";
  std::uint64_t cumulative = 0;
  for (std::size_t b = 0; b < bounds_count; ++b) {
    cumulative += buckets[b];
    std::string le;
    append_shortest(le, bounds[b]);
    line(out, name + "_bucket", sep + "le=\"" + le + "\"", static_cast<double>(cumulative));
  }
  cumulative += buckets[bounds_count];
  line(out, name + "_bucket", sep + "le=\"+Inf\"", static_cast<double>(cumulative));
  line(out, name + "_sum", labels, sum_seconds);
  line(out, name + "_count", labels, static_cast<double>(count));
}

int Metrics::status_index(int status) {
  for (std::size_t i = 0; i + 1 < kHttpStatuses.size(); ++i)
    if (kHttpStatuses[i] == status) return static_cast<int>(i);
  return static_cast<int>(kHttpStatuses.size()) - 1;
}

void Metrics::observe_request(Route route, int status, double seconds) {
  const auto r = static_cast<std::size_t>(route);
  requests_[r][static_cast<std::size_t>(status_index(status))].fetch_add(1, std::memory_order_relaxed);
  durations_[r].observe(kRequestBuckets, seconds);
}

void Metrics::observe_key(const std::string& key, int status) {
  std::lock_guard lock(keys_mutex_);
  ++by_key_[{key, status}];
}

void Metrics::observe_compile(double seconds) { compile_.observe(kCompileBuckets, seconds); }

void Metrics::add_projections(const std::array<std::uint64_t, kStatusCount>& by_status) {
  std::uint64_t total = 0;
  for (int s = 0; s < kStatusCount; ++s) {
    if (by_status[s] == 0) continue;
    projections_[s].fetch_add(by_status[s], std::memory_order_relaxed);
    total += by_status[s];
  }
  points_.fetch_add(total, std::memory_order_relaxed);
}

void Metrics::add_cancelled(std::size_t dropped_points) {
  batches_cancelled_.fetch_add(1, std::memory_order_relaxed);
  points_cancelled_.fetch_add(dropped_points, std::memory_order_relaxed);
}

std::string Metrics::render(const Gauges& g) const {
  std::string out;
  out.reserve(8192);
  header(out, "footpoint_build_info", "gauge",
         "The footpoint version this server was built from (always 1).");
  line(out, "footpoint_build_info", "version=\"" + std::string(kVersion) + "\"", 1.0);
  render_process_metrics(out);
  header(out, "footpoint_http_requests_total", "counter", "HTTP requests answered, by route and status.");
  for (int r = 0; r < kRouteCount; ++r)
    for (std::size_t s = 0; s < kHttpStatuses.size(); ++s) {
      const auto n = requests_[r][s].load(std::memory_order_relaxed);
      if (n == 0) continue;
      const std::string status = kHttpStatuses[s] ? std::to_string(kHttpStatuses[s]) : "other";
      line(out, "footpoint_http_requests_total",
           std::string("route=\"") + route_template(static_cast<Route>(r)) + "\",status=\"" + status + "\"",
           static_cast<double>(n));
    }
  header(out, "footpoint_http_request_duration_seconds", "histogram",
         "Time from reading a request to writing its response, by route.");
  for (int r = 0; r < kRouteCount; ++r) {
    if (durations_[r].count.load(std::memory_order_relaxed) == 0) continue;
    histogram_lines(out, "footpoint_http_request_duration_seconds",
                    std::string("route=\"") + route_template(static_cast<Route>(r)) + "\"", durations_[r],
                    kRequestBuckets);
  }
  {
    std::lock_guard lock(keys_mutex_);
    if (!by_key_.empty()) {
      header(out, "footpoint_api_key_requests_total", "counter", "HTTP requests by API key name and status.");
      for (const auto& [key_status, n] : by_key_)
        line(out, "footpoint_api_key_requests_total",
             "key=\"" + key_status.first + "\",status=\"" + std::to_string(key_status.second) + "\"",
             static_cast<double>(n));
    }
  }
  header(out, "footpoint_http_requests_in_flight", "gauge", "API requests being answered now.");
  line(out, "footpoint_http_requests_in_flight", "", static_cast<double>(g.in_flight));
  header(out, "footpoint_points_in_flight", "gauge", "Points of the requests being projected now.");
  line(out, "footpoint_points_in_flight", "", static_cast<double>(g.in_flight_points));
  header(out, "footpoint_memory_in_flight_bytes", "gauge",
         "Memory reserved by the requests being answered (estimates, --max-inflight-bytes).");
  line(out, "footpoint_memory_in_flight_bytes", "", static_cast<double>(g.in_flight_bytes));
  header(out, "footpoint_memory_budget_bytes", "gauge",
         "The in-flight memory budget (--max-inflight-bytes).");
  line(out, "footpoint_memory_budget_bytes", "", static_cast<double>(g.max_inflight_bytes));
  header(out, "footpoint_memory_refusals_total", "counter",
         "Requests refused (503 overloaded) because the in-flight memory budget was taken.");
  line(out, "footpoint_memory_refusals_total", "", static_cast<double>(g.memory_refusals));
  header(out, "footpoint_points_projected_total", "counter", "Points projected (every status).");
  line(out, "footpoint_points_projected_total", "",
       static_cast<double>(points_.load(std::memory_order_relaxed)));
  header(out, "footpoint_projections_total", "counter", "Projections by solver status.");
  for (int s = 0; s < kStatusCount; ++s)
    line(out, "footpoint_projections_total",
         std::string("status=\"") + to_string(static_cast<Status>(s)) + "\"",
         static_cast<double>(projections_[s].load(std::memory_order_relaxed)));
  header(out, "footpoint_batches_cancelled_total", "counter",
         "Batches dropped because their client closed the connection.");
  line(out, "footpoint_batches_cancelled_total", "",
       static_cast<double>(batches_cancelled_.load(std::memory_order_relaxed)));
  header(out, "footpoint_points_cancelled_total", "counter", "Points of those batches never started.");
  line(out, "footpoint_points_cancelled_total", "",
       static_cast<double>(points_cancelled_.load(std::memory_order_relaxed)));
  header(out, "footpoint_read_timeouts_total", "counter",
         "Connections closed because a request did not arrive within --read-timeout-s.");
  line(out, "footpoint_read_timeouts_total", "",
       static_cast<double>(read_timeouts_.load(std::memory_order_relaxed)));
  header(out, "footpoint_geometry_compile_seconds", "histogram", "Time to compile a new geometry.");
  histogram_lines(out, "footpoint_geometry_compile_seconds", "", compile_, kCompileBuckets);
  header(out, "footpoint_geometry_compilations_total", "counter", "Geometry compilations, by result.");
  line(out, "footpoint_geometry_compilations_total", "result=\"ok\"",
       static_cast<double>(g.cache.compilations));
  line(out, "footpoint_geometry_compilations_total", "result=\"error\"",
       static_cast<double>(g.cache.failed_compilations));
  header(out, "footpoint_geometry_cache_entries", "gauge", "Compiled geometries held by the cache.");
  line(out, "footpoint_geometry_cache_entries", "", static_cast<double>(g.cache.size));
  header(out, "footpoint_geometry_cache_bytes", "gauge", "Memory held by the cached geometries.");
  line(out, "footpoint_geometry_cache_bytes", "", static_cast<double>(g.cache.bytes));
  header(out, "footpoint_geometry_cache_hits_total", "counter", "Cache lookups that found the geometry.");
  line(out, "footpoint_geometry_cache_hits_total", "", static_cast<double>(g.cache.hits));
  header(out, "footpoint_geometry_cache_misses_total", "counter", "Cache lookups that did not.");
  line(out, "footpoint_geometry_cache_misses_total", "", static_cast<double>(g.cache.misses));
  header(out, "footpoint_geometry_cache_evictions_total", "counter",
         "Geometries evicted to respect the bounds.");
  line(out, "footpoint_geometry_cache_evictions_total", "", static_cast<double>(g.cache.evictions));
  header(out, "footpoint_worker_threads", "gauge", "Threads of the numerical pool.");
  line(out, "footpoint_worker_threads", "", g.worker_threads);
  header(out, "footpoint_worker_queue_tasks", "gauge", "Jobs (requests' points) waiting for a worker.");
  line(out, "footpoint_worker_queue_tasks", "", static_cast<double>(g.worker_queue));
  header(out, "footpoint_shutting_down", "gauge", "1 while the server drains before exiting.");
  line(out, "footpoint_shutting_down", "", g.shutting_down ? 1.0 : 0.0);
  if (g.registry) g.registry->render(out);
  return out;
}

}  // namespace footpoint::server
