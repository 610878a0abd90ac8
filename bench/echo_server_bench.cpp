// The echo baseline for bench/http_bench.sh: footpoint's own HTTP layer and JSON reader/writer,
// with the projection replaced by an echo. POST /v1/geometries/{id}/project and /v1/project
// parse the request exactly as the server does and answer a response of the same shape and
// size (every result filled with full-precision numbers taken from its point), so
// "footpoint points/s / echo points/s" is the share of the time the JSON and HTTP layers leave to
// the projection. Not a product route: it lives only in this benchmark executable.
//   build/bench/echo_server_bench --port 18182 --host 127.0.0.1   (same flags as footpoint-server)
#include <pthread.h>

#include <atomic>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <thread>

#include "config.hpp"
#include "http_server.hpp"
#include "project_request.hpp"
#include "result_json.hpp"
#include "shutdown_signals.hpp"

using namespace footpoint;
using namespace footpoint::server;

namespace {

ApiResponse echo(const RouteMatch& match, std::string_view body, std::size_t max_points) {
  try {
    const bool inline_geometry = match.route == Route::project;
    const ProjectRequest request = read_project_request(body, inline_geometry, max_points);
    std::vector<ProjectionResult> results(request.count);
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
    ApiResponse response;
    response.body = project_response(inline_geometry ? "8ca9f0e028af69e7a85f954715c1f082" : std::string(match.id),
                                     results, request.single, false, false, 0.0);
    response.points = results.size();
    return response;
  } catch (const ApiError& e) {
    return Api::error_response(e);
  }
}

}  // namespace

int main(int argc, char** argv) {
  block_shutdown_signals();
  ServerConfig config;
  const int exit_code = configure_from_command_line(argc, argv, "echo_server_bench", config);
  if (exit_code >= 0) return exit_code;
  HttpServer* self = nullptr;
  HttpServer server(config, [&self, &config](const RouteMatch& m, std::string_view method, std::string_view body) {
    if (m.route == Route::project || m.route == Route::geometry_project) return echo(m, body, config.max_points);
    return self->api().handle(m, method, body);
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
  if (!signalled.load()) pthread_kill(signals.native_handle(), SIGTERM);
  signals.join();
  return 0;
}
