// The echo baseline for bench/http_bench.sh: footpoint's own HTTP layer and JSON reader/writer,
// with the projection replaced by an echo. POST /v1/geometries/{id}/project and /v1/project
// parse the request exactly as the server does and answer a response of the same shape, so
// "footpoint points/s / echo points/s" is the share of the time the JSON and HTTP layers leave to
// the projection. Not a product route: it lives only in this benchmark executable.
// The results it writes:
//  - with --replay ID=FILE (FILE: footpoint-server's response to a batch for geometry ID) and a
//    request for ID with as many points: that response's results, so the response is byte for
//    byte the server's (the same size, the same numbers to write);
//  - otherwise every result filled with full-precision numbers taken from its point (the same
//    shape; larger than the server's when it has short numbers, e.g. corner answers).
//   build/bench/echo_server_bench --port 18182 --host 127.0.0.1 [--replay ID=FILE ...]
//   (and the same flags as footpoint-server)
#include <pthread.h>

#include <atomic>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "config.hpp"
#include "http_server.hpp"
#include "project_request.hpp"
#include "result_json.hpp"
#include "shutdown_signals.hpp"

using namespace footpoint;
using namespace footpoint::server;

namespace {

// Responses to replay: geometry id -> the server's results for a batch.
using Replays = std::map<std::string, std::vector<ProjectionResult>, std::less<>>;

template <typename Enum>
Enum parse_enum(const std::string& name, Enum last) {
  for (int i = 0; i <= static_cast<int>(last); ++i)
    if (name == to_string(static_cast<Enum>(i))) return static_cast<Enum>(i);
  throw std::runtime_error("unknown name '" + name + "'");
}

// The results of a footpoint-server response to a batch on a surface, as the server had them
// (the residual goes back in as the first orthogonality residual, which gives it back).
std::vector<ProjectionResult> read_replay(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path);
  const nlohmann::json response = nlohmann::json::parse(in);
  std::vector<ProjectionResult> results;
  for (const nlohmann::json& x : response.at("results")) {
    ProjectionResult r;
    const nlohmann::json& d = x.at("diagnostics");
    r.dim = 3;
    r.num_params = 2;
    r.summary.method = d.at("method").get<std::string>();
    r.summary.status = parse_enum(d.at("status").get<std::string>(), Status::deadline_exceeded);
    r.summary.iterations = d.at("iterations").get<int>();
    r.summary.starts = d.at("starts").get<int>();
    r.summary.location = parse_enum(d.at("location").get<std::string>(), Location::unknown);
    if (!d.at("residual").is_null()) r.summary.orthogonality = {d.at("residual").get<double>(), 0.0};
    if (!d.at("step_norm").is_null()) r.summary.step_norm = d.at("step_norm").get<double>();
    if (!x.at("distance").is_null()) {
      r.distance = x.at("distance").get<double>();
      r.foot = x.at("foot_point").get<std::array<double, 3>>();
      r.params = x.at("parameters").get<std::array<double, 2>>();
    }
    results.push_back(r);
  }
  return results;
}

ApiResponse echo(const RouteMatch& match, std::string_view body, std::size_t max_points,
                 const Replays& replays) {
  try {
    const bool inline_geometry = match.route == Route::project;
    const ProjectRequest request = read_project_request(body, inline_geometry, max_points);
    std::vector<ProjectionResult> results(request.count);
    const auto replay = inline_geometry ? replays.end() : replays.find(match.id);
    if (replay != replays.end() && replay->second.size() == request.count) {
      for (std::size_t i = 0; i < request.count; ++i) results[i] = replay->second[i];
    } else {
      const int dim = request.point_length;
      for (std::size_t i = 0; i < request.count; ++i) {
        const double* p = request.coords.data() + i * static_cast<std::size_t>(dim);
        ProjectionResult& r = results[i];
        r.dim = dim;
        r.num_params = 2;
        for (int k = 0; k < dim; ++k) r.foot[k] = p[k] * 0.9999999999999999;
        r.params = {p[0] * 0.3183098861837907, p[1] * 0.3183098861837907};
        r.distance = std::sqrt(p[0] * p[0] + p[1] * p[1]) * 1.0000000000000002;
        r.summary.method = request.method;
        r.summary.status = Status::converged;
        r.summary.iterations = 5;
        r.summary.step_norm = std::abs(p[0]) * 1e-9;
        r.summary.orthogonality = {std::abs(p[1]) * 1e-17, std::abs(p[0]) * 1e-17};
        r.summary.starts = 3;
        r.summary.location = Location::interior;
      }
    }
    ApiResponse response;
    response.body =
        project_response(inline_geometry ? "8ca9f0e028af69e7a85f954715c1f082" : std::string(match.id),
                         results, request.single, request.fields, 0.0);
    response.points = results.size();
    return response;
  } catch (const ApiError& e) {
    return Api::error_response(e);
  }
}

}  // namespace

int main(int argc, char** argv) {
  block_shutdown_signals();
  // --replay ID=FILE (repeatable) is this executable's own; the other flags are the server's
  Replays replays;
  std::vector<char*> args{argv[0]};
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a != "--replay") {
      args.push_back(argv[i]);
      continue;
    }
    const std::string spec = i + 1 < argc ? argv[++i] : "";
    const auto eq = spec.find('=');
    if (eq == std::string::npos) {
      std::fprintf(stderr, "echo_server_bench: --replay needs ID=FILE\n");
      return 2;
    }
    try {
      replays[spec.substr(0, eq)] = read_replay(spec.substr(eq + 1));
    } catch (const std::exception& e) {
      std::fprintf(stderr, "echo_server_bench: --replay %s: %s\n", spec.c_str(), e.what());
      return 2;
    }
  }
  ServerConfig config;
  const int exit_code =
      configure_from_command_line(static_cast<int>(args.size()), args.data(), "echo_server_bench", config);
  if (exit_code >= 0) return exit_code;
  // the server's buffer policy: the same cost of moving the JSON
  keep_large_buffers_for_reuse(config.threads ? config.threads : footpoint::default_threads());
  HttpServer* self = nullptr;
  HttpServer server(
      config, [&self, &config, &replays](const RouteMatch& m, std::string_view method, std::string_view body,
                                         std::string_view query, const Caller& caller) {
        if (m.route == Route::project || m.route == Route::geometry_project)
          return echo(m, body, config.max_points, replays);
        return self->api().handle(m, method, body, query, caller);
      });
  self = &server;
  try {
    std::printf("echo_server_bench listening on %s:%d\n", config.host.c_str(), server.bind());
    std::fflush(stdout);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "echo_server_bench: %s\n", e.what());
    return 1;
  }
  std::atomic<bool> signalled{false};
  std::thread signals([&server, &signalled] {
    wait_for_shutdown_signal();
    signalled.store(true);
    server.shutdown();
  });
  server.run();
  // SIGTERM is blocked in every thread: it wakes the signal thread's sigwait, nothing else
  if (!signalled.load())
    pthread_kill(signals.native_handle(), SIGTERM);  // NOLINT(bugprone-bad-signal-to-kill-thread)
  signals.join();
  return 0;
}
