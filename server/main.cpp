// footpoint-server: the HTTP/JSON service. Flags and environment variables: see --help
// (server/config.hpp). Exits 0 after a graceful shutdown on SIGTERM or SIGINT; SIGHUP reads the
// API keys and the TLS certificate and key again.
#include <pthread.h>
#include <unistd.h>

#include <csignal>

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <thread>

#include <spdlog/spdlog.h>

#include "batch/thread_pool.hpp"
#include "config.hpp"
#include "http_server.hpp"
#include "request_log.hpp"
#include "shutdown_signals.hpp"
#include "version.hpp"

int main(int argc, char** argv) {
  using namespace footpoint::server;
  // Before any thread exists, so that every thread inherits the mask.
  block_shutdown_signals();

  ServerConfig config;
  const int exit_code = configure_from_command_line(argc, argv, "footpoint-server", config);
  if (exit_code >= 0) return exit_code;
  keep_large_buffers_for_reuse(config.threads ? config.threads : footpoint::default_threads());

  int status = 0;
  try {
    HttpServer server(config);
    const int port = server.bind();
    const unsigned threads = config.threads ? config.threads : footpoint::default_threads();
    for (const std::string& name : unknown_environment(environ))
      log_event(spdlog::level::warn, "unknown environment variable",
                {{"variable", name}, {"hint", "no setting reads it (footpoint-server --help lists them)"}});
    log_event(spdlog::level::info, "listening",
              {{"version", kVersion},
               {"host", config.host},
               {"port", port},
               {"threads", threads},
               {"connection_threads", config.connection_threads},
               {"settings", LogValue::json(effective_settings_json(config))}});

    std::atomic<bool> signalled{false};
    std::thread signals([&server, &signalled] {
      const int sig = wait_for_shutdown_signal([&server] { server.reload(); });
      signalled.store(true);
      log_event(spdlog::level::info, "shutting down", {{"signal", sig == SIGTERM ? "SIGTERM" : "SIGINT"}});
      server.shutdown();
    });
    server.run();
    // run() also returns when listening fails; release the signal thread then.
    // SIGTERM is blocked in every thread: it wakes the signal thread's sigwait, nothing else
    if (!signalled.load())
      pthread_kill(signals.native_handle(), SIGTERM);  // NOLINT(bugprone-bad-signal-to-kill-thread)
    signals.join();
    log_event(spdlog::level::info, "stopped");
  } catch (const std::exception& e) {
    log_event(spdlog::level::critical, "cannot start", {{"error", e.what()}});
    status = 1;
  }
  spdlog::shutdown();
  return status;
}
