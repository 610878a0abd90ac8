// libFuzzer target: arbitrary bodies for POST /v1/project, answered in-process by the server's
// Api (the object behind the HTTP layer: routing match, JSON reading, geometry compilation and
// cache, projection on the numerical pool, JSON writing), with no network.
//
// Every answer must be one the API promises: a status from the documented set (never 500), a
// body that is valid JSON (so never NaN or Infinity), an error object with a code and a message
// for a 4xx, and for a 200 one result per point whose distance, when given, is |p - foot|
// (the service never states a distance its own foot point contradicts), with `converged` only
// when the status says converged.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <string_view>

#include <spdlog/spdlog.h>
#include <nlohmann/json.hpp>

#include "api.hpp"
#include "request_log.hpp"
#include "route.hpp"

namespace {

using footpoint::GeometryCache;
using footpoint::GeometryCacheOptions;
using footpoint::ThreadPool;
using namespace footpoint::server;
using nlohmann::json;

[[noreturn]] void fail(const std::string& what, std::string_view request, const ApiResponse& response) {
  std::fprintf(stderr, "request_fuzz: %s\n  request: %.*s\n  status %d: %s\n", what.c_str(),
               static_cast<int>(std::min<std::size_t>(request.size(), 2000)), request.data(), response.status,
               response.body.substr(0, 2000).c_str());
  std::abort();
}

// One Api for the whole run, as in a server process: the cache and the pool persist across
// inputs, so eviction and reuse are exercised too. Limits are the server's, made smaller where a
// default would only slow the fuzzer down (points per request, the deadline, the cache).
struct Service {
  ServerConfig config;
  Metrics metrics;
  std::unique_ptr<GeometryCache> cache;
  std::unique_ptr<ThreadPool> pool;
  std::unique_ptr<Api> api;
  Service() {
    init_logging("off");
    config.max_points = 2000;
    config.deadline = std::chrono::milliseconds(2000);
    config.cache_entries = 32;
    // 64 MiB, so that one geometry may hold a quarter, 16 MiB, as the server bounds it
    // (effective_max_geometry_bytes): an instrumented build is 20-50x slower than a release one,
    // and a structure of the server's default size (64 MiB, a million curve samples and their
    // k-d tree) takes it tens of seconds to build, past the slow-input report.
    config.cache_bytes = std::size_t{64} << 20;
    cache = std::make_unique<GeometryCache>(GeometryCacheOptions{
        config.cache_entries, config.cache_bytes, config.effective_max_geometry_bytes(), config.cache_share});
    pool = std::make_unique<ThreadPool>(2);
    api = std::make_unique<Api>(config, *cache, *pool, metrics);
  }
};

Service& service() {
  static Service* s = new Service;  // never destroyed: the pool's threads outlive every input
  return *s;
}

bool documented_error_status(int status) {
  return status == 400 || status == 404 || status == 413 || status == 415 || status == 422 || status == 503;
}

// The request's points as the client sent them (null when the body is not that shape).
json request_points(std::string_view body) {
  json req = json::parse(body, nullptr, false);
  if (!req.is_object()) return nullptr;
  if (req.contains("point")) return json::array({req["point"]});
  if (req.contains("points")) return req["points"];
  return nullptr;
}

void check_result(const json& result, const json& point, std::string_view body, const ApiResponse& response) {
  if (!result.is_object() || !result.contains("diagnostics"))
    fail("result without diagnostics", body, response);
  const json& d = result["diagnostics"];
  if (!d.contains("status") || !d["status"].is_string()) fail("result without a status", body, response);
  const bool converged = d.value("converged", false);
  if (converged != (d["status"] == "converged"))
    fail("`converged` disagrees with the status", body, response);
  const json& distance = result.value("distance", json());
  const json& foot = result.value("foot_point", json());
  if (converged && !distance.is_number()) fail("converged without a distance", body, response);
  if (!distance.is_number() || !foot.is_array() || !point.is_array() || foot.size() != point.size()) return;
  // |p - foot| computed apart, scaled against overflow.
  double scale = 0.0;
  for (std::size_t i = 0; i < foot.size(); ++i) {
    if (!foot[i].is_number() || !point[i].is_number()) fail("foot point with a non-number", body, response);
    scale = std::max({scale, std::fabs(foot[i].get<double>()), std::fabs(point[i].get<double>())});
  }
  if (scale == 0.0 || !std::isfinite(scale)) return;
  double sum = 0.0;
  for (std::size_t i = 0; i < foot.size(); ++i) {
    const double e = (point[i].get<double>() - foot[i].get<double>()) / scale;
    sum += e * e;
  }
  const double expected = scale * std::sqrt(sum), given = distance.get<double>();
  if (!(std::fabs(given - expected) <= 1e-12 * scale + 1e-300))
    fail("distance " + std::to_string(given) + " is not |p - foot| = " + std::to_string(expected), body,
         response);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view body(reinterpret_cast<const char*>(data), size);
  Service& s = service();
  const RouteMatch match = match_route("POST", "/v1/project");
  const ApiResponse response = s.api->handle(match, "POST", body);

  if (response.status != 200 && !documented_error_status(response.status))
    fail("undocumented status", body, response);
  const json answer = json::parse(response.body, nullptr, false);
  if (answer.is_discarded()) fail("the response is not JSON", body, response);
  if (response.status != 200) {
    const json& error = answer.value("error", json());
    if (!error.is_object() || !error.value("code", json()).is_string() ||
        !error.value("message", json()).is_string())
      fail("an error response without error.code and error.message", body, response);
    return 0;
  }
  if (!answer.contains("geometry_id") || !answer.contains("stats"))
    fail("a 200 without geometry_id/stats", body, response);
  const json points = request_points(body);
  if (!points.is_array()) fail("a 200 for a body without point(s)", body, response);
  if (answer.contains("result")) {
    check_result(answer["result"], points[0], body, response);
  } else {
    const json& results = answer.value("results", json());
    if (!results.is_array() || results.size() != points.size())
      fail("results do not match the points", body, response);
    for (std::size_t i = 0; i < results.size(); ++i) check_result(results[i], points[i], body, response);
  }
  return 0;
}
