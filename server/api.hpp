// The v1 API behind the HTTP layer: given a matched route, the method and the body, produce the
// response. Validation and error mapping live here (core error kinds -> HTTP status + JSON error);
// the numerical work is handed to the core (cache, thread pool, project_batch). No HTTP library
// types: the same object serves the HTTP server, the tests and the fuzzers.
#pragma once
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <mutex>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "api_error.hpp"
#include "batch/thread_pool.hpp"
#include "cache/geometry_cache.hpp"
#include "config.hpp"
#include "geometry_registry.hpp"
#include "metrics.hpp"
#include "route.hpp"
#include "streamed_body.hpp"

namespace footpoint::server {

// An in-flight budget (points, memory) that requests reserve from (api.cpp).
struct InflightBudget;

// What the HTTP layer tells of a request's representations.
struct RequestFormat {
  std::string content_type;  // the body's media type, lower case, no parameters ("application/json")
  std::string accept;        // the Accept header as sent ("" when none)
  // The body not read yet (then `body` is empty): a streamed projection of binary points reads it
  // as it answers; other requests read it whole first. nullptr: `body` is the whole body.
  const BodySource* source = nullptr;
};

struct ApiResponse {
  int status = 200;
  std::string content_type = "application/json";
  std::string body;
  std::string location;    // Location header (201 Created), empty otherwise
  std::size_t points = 0;  // points projected (for the request log)
  int retry_after_s = 0;   // Retry-After header (503 overloaded, registry_unavailable), 0: none
  std::vector<std::pair<std::string, std::string>> headers;  // further headers (the pages' security policy)
  std::string error_code;  // the error's code when this answers one (for the request log)
  // A body produced while it is sent (chunked transfer), instead of `body`: the HTTP layer calls
  // it once, while the request and its body are alive, with `write` sending one piece (false
  // once the client is gone); it returns false when it stopped before the end (the HTTP layer
  // then closes the connection, so that the client sees the answer cut).
  using Write = std::function<bool(std::string_view)>;
  std::function<bool(const Write&)> stream;
  // Stops what the answer keeps running beside `stream` (the reader of a body read as it is
  // answered). The HTTP layer calls it once the response is done, whether or not the stream ran.
  std::function<void()> release;
};

// Who is calling, for what the Api decides once a body is read. Empty: no keys, no limit.
struct Caller {
  std::string_view key;  // the API key's name ("" without keys): the audit log names it
  // Takes a request's points from the caller's rate limit; throws ApiError (429 rate_limited,
  // with Retry-After) when they are not there. Empty: no limit.
  std::function<void(std::size_t points)> charge;
  // Whether the client has closed its connection, asked between the grains of a batch answered
  // whole (JSON): its points not started are then dropped (499 client_closed_request, which nobody
  // reads, in the log and footpoint_batches_cancelled_total). Empty: never.
  std::function<bool()> client_gone;
};

class Api {
 public:
  // `registry`: the shared level 2 under `cache` (nullptr: one process, the cache alone).
  Api(const ServerConfig& config, GeometryCache& cache, ThreadPool& pool, Metrics& metrics,
      GeometryRegistry* registry = nullptr);

  // Answers a request that matched `match` with an allowed method; `query` is the target's text
  // after '?' (empty when there is none). Never throws: every failure becomes a JSON error
  // response with its status.
  ApiResponse handle(const RouteMatch& match, std::string_view method, std::string_view body,
                     std::string_view query = {}, const Caller& caller = {},
                     const RequestFormat& format = {});

  // While shutting down, /readyz answers 503 (the HTTP layer refuses new API requests).
  void set_shutting_down() { shutting_down_.store(true); }
  bool shutting_down() const { return shutting_down_.load(); }
  // API requests being answered now, and the points they are projecting (load shedding, metrics).
  std::size_t in_flight() const { return in_flight_.load(std::memory_order_relaxed); }
  std::size_t in_flight_points() const { return in_flight_points_.load(std::memory_order_relaxed); }

  Metrics::Gauges gauges() const;
  static ApiResponse error_response(const ApiError& error);

 private:
  ApiResponse health() const;
  ApiResponse ready() const;
  ApiResponse metrics() const;
  ApiResponse openapi() const;
  ApiResponse methods();
  ApiResponse create_geometry(std::string_view body, const Caller& caller);
  // GET /v1/geometries?limit=N&after=ID: a page of this replica's cache in id order.
  ApiResponse list_geometries(std::string_view query);
  static constexpr long long kDefaultListLimit = 100, kMaxListLimit = 1000;
  ApiResponse get_geometry(std::string_view id);
  ApiResponse delete_geometry(std::string_view id, const Caller& caller);
  // id empty: inline geometry. A binary body (application/octet-stream) reads its options from
  // the query; Accept application/x-ndjson or application/octet-stream streams the answer.
  ApiResponse project(std::string_view id, std::string_view body, std::string_view query,
                      const RequestFormat& format, const Caller& caller);
  ApiResponse mesh(std::string_view id, std::string_view query);
  ApiResponse evaluate(std::string_view id, std::string_view body, const Caller& caller);
  ApiResponse ui(const RouteMatch& match) const;

  formula::CompileLimits compile_limits() const;
  // Compiles through the cache, the caller's key the entry's owner (its cache share, posted_by).
  GeometryCache::Lookup compile(const GeometryDefinition& def, const std::string& field_prefix,
                                const Caller& caller);
  // The geometry with this id from the cache, else from the registry; nullptr when neither holds
  // it. Throws ApiError (503 registry_unavailable, 422 when a stored definition does not compile).
  std::shared_ptr<const CompiledGeometry> held_geometry(std::string_view id);
  // The held geometry with this id; 400 invalid_geometry_id for what is no id, 404
  // geometry_not_found (post it again; `alternative` adds another way) when it is not held.
  std::shared_ptr<const CompiledGeometry> geometry_by_id(std::string_view id, const char* alternative = "");

  const ServerConfig& config_;
  GeometryCache& cache_;
  ThreadPool& pool_;
  Metrics& metrics_;
  GeometryRegistry* registry_;
  std::atomic<bool> shutting_down_{false};
  std::atomic<std::size_t> in_flight_{0};
  std::atomic<std::size_t> in_flight_points_{0};
  // The memory budget (--max-inflight-bytes): bytes reserved by the requests in flight, the
  // budget, and the requests refused by it.
  InflightBudget memory_budget();
  std::atomic<std::size_t> in_flight_bytes_{0};
  const std::size_t max_inflight_bytes_;
  std::atomic<std::uint64_t> memory_refusals_{0};
  std::mutex methods_mutex_;
  std::string methods_body_;  // built on first use
};

}  // namespace footpoint::server
