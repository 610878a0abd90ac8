// The HTTP layer (cpp-httplib 0.11.4, a compiled library whose defaults need changing): one
// thread per connection from a pool of --connection-threads, TCP_NODELAY on, a real listen
// backlog, no SO_REUSEPORT (a second instance cannot silently share the port), long keep-alive.
// Every request first passes a pre-routing check that needs no body: shutting down (503),
// unknown route (404), method (405), framing (411 for chunked or missing Content-Length, 413 over
// the body limit, 415 for Content-Encoding or a non-JSON Content-Type) and load (503 beyond
// --max-inflight; the Api also sheds beyond --max-inflight-points once the body is read). Responses are never
// compressed (clients' Accept-Encoding is ignored), byte ranges are ignored. One JSON log line and the
// metrics are recorded per request. Graceful shutdown: stop accepting, close the idle keep-alive
// connections at once (httplib alone would wait out their keep-alive timeout), answer 503 to a request
// that arrives on an open connection meanwhile, let in-flight requests finish (their responses say
// Connection: close); run() returns when every connection is closed.
// Bodies are read whole before the Api sees them, except the binary points of a streamed
// projection over plain HTTP, read as they are answered (streamed_body.hpp).
// Exposure (docs/security.md): with --tls-cert/--tls-key the server speaks HTTPS only (tls.hpp);
// with --api-keys every API request needs `Authorization: Bearer SECRET` of a key with the
// route's scope (401, 403 from pre-routing, access.hpp), and --rate-limit takes each request's
// points from its key's token bucket (429 with Retry-After). reload() (SIGHUP) reads the keys and
// the TLS files again.
// Isolation (docs/operations.md, "Fair scheduling and cancellation"): the key's name is the tenant
// of the numerical pool's fair queue; a batch answered whole is cancelled when its client closes
// the connection (ConnectionWatch); a request that does not arrive whole within --read-timeout-s
// of its first byte has its connection closed (ReadDeadline).
#pragma once
#include <atomic>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string_view>
#include <thread>

#include "access.hpp"
#include "api.hpp"
#include "batch/thread_pool.hpp"
#include "cache/geometry_cache.hpp"
#include "config.hpp"
#include "connections.hpp"
#include "geometry_registry.hpp"
#include "metrics.hpp"
#include "tls.hpp"

namespace httplib {
class Server;
struct Request;
struct Response;
}  // namespace httplib

namespace footpoint::server {

class HttpServer {
 public:
  // Answers a request whose route and method passed the pre-routing checks. The default is the
  // Api; benchmarks substitute their own (e.g. an echo) to measure the HTTP and JSON layers.
  using Handler = std::function<ApiResponse(const RouteMatch&, std::string_view method, std::string_view body,
                                            std::string_view query, const Caller& caller)>;

  explicit HttpServer(ServerConfig config, Handler handler = nullptr);
  ~HttpServer();
  HttpServer(const HttpServer&) = delete;
  HttpServer& operator=(const HttpServer&) = delete;

  // Binds host:port (port 0: a free port) and starts listening, and the probe port when there is
  // one; returns the port. Throws std::runtime_error when an address is unavailable.
  int bind();
  // Serves until shutdown(); returns once in-flight requests are answered.
  void run();
  // Reads the API keys file and the TLS certificate and key again (SIGHUP). What cannot be read
  // is logged and the previous keys or credentials stay in use. Returns false then.
  bool reload();
  // Starts a graceful shutdown and returns at once: no new connection is accepted and the idle
  // ones are closed (once the streamed answers admitted have started: the time to read their
  // bodies). Thread-safe; later calls do nothing.
  void shutdown();

  int port() const { return port_; }
  const ServerConfig& config() const { return config_; }
  Api& api() { return api_; }
  GeometryCache& cache() { return cache_; }
  GeometryRegistry* registry() { return registry_.get(); }
  bool tls() const { return tls_ != nullptr; }

 private:
  // The constructor's stages, in order.
  void start_read_deadline();    // --read-timeout-s's watcher (ReadDeadline)
  void log_exposure() const;     // whether keys and TLS are in use
  void configure_listener();     // connection threads, socket options, timeouts, body limit
  void install_admission();      // admit() before every request's body (and for Expect: 100-continue)
  void install_routes();         // every admitted request to answer()
  void install_error_answers();  // httplib's own errors and exceptions as the API's JSON errors
  void install_request_log();    // one log line and the metrics per request

  // How the request's body is framed, from its headers.
  struct Framing {
    bool has_length = false;
    bool chunked = false;  // Transfer-Encoding (refused)
    std::size_t length = 0;
  };
  // Admission: the checks every request passes before its body is read, in this order (each
  // false when it answered the request itself, res holding the answer): the request's context
  // and id, framing errors (400), shutting down (503), route (404), cross-origin (preflights
  // answered), method (405), authorize (401, 403), rate_limit (429), accept_body (411, 413, 415,
  // a GET with a body 400) and shed_load (503 beyond --max-inflight, POST only).
  bool admit(const httplib::Request& req, httplib::Response& res);
  // CORS headers for a configured origin; a preflight OPTIONS answered (false) or refused
  // (false, 403); nullopt when the request goes on.
  std::optional<bool> cross_origin(const httplib::Request& req, httplib::Response& res, bool has_body) const;
  bool authorize(const httplib::Request& req, httplib::Response& res, bool has_body) const;
  bool rate_limit(const httplib::Request& req, httplib::Response& res, bool has_body) const;
  bool accept_body(const httplib::Request& req, httplib::Response& res, const Framing& framing) const;
  bool shed_load(httplib::Response& res);
  // Answers an admitted request (the route admit() matched). `source`: the body when it is read
  // as it is answered (req.body is empty then), and `socket` the connection's, on which the answer
  // is then written.
  void answer(const httplib::Request& req, httplib::Response& res, const BodySource* source, int socket);

  // The keys in use (nullptr: no authentication).
  std::shared_ptr<const KeyRing> keys() const;
  // Which connections are answering a request: one slot per connection thread holding the remote
  // port of the request it answers (0: between requests). shutdown() closes every connection of
  // this server whose port is in no slot.
  void mark_busy(int remote_port);
  void mark_idle();
  void close_idle_connections();
  // The request on this connection thread has started its streamed answer, or ended without one.
  void stream_started();

  ServerConfig config_;
  Metrics metrics_;
  GeometryCache cache_;
  std::unique_ptr<GeometryRegistry> registry_;  // nullptr without --registry-url
  ThreadPool pool_;
  Api api_;
  Handler handler_;
  std::unique_ptr<TlsCredentials> tls_;  // nullptr: plain HTTP
  mutable std::mutex keys_mutex_;
  std::shared_ptr<const KeyRing> keys_;
  std::unique_ptr<RateLimiter> limiter_;  // nullptr: no rate limit
  bool custom_handler_;                   // handler_ was given (tests, benches): it sees no RequestFormat
  std::unique_ptr<httplib::Server> http_;
  // The probes' listener (--probe-port), its thread, and whether its listen loop has returned.
  std::unique_ptr<httplib::Server> probes_;
  std::thread probe_thread_;
  std::atomic<bool> probes_done_{false};
  int listen_fd_ = -1;  // the listening socket, seen by httplib's socket options callback
  int port_ = -1;
  enum class RunState { idle, starting, finished };
  std::atomic<RunState> run_state_{RunState::idle};
  std::mutex stop_mutex_;
  bool stopped_ = false;
  std::atomic<int> streams_starting_{0};            // streamed answers admitted and not yet started
  std::unique_ptr<ReadDeadline> read_deadline_;     // nullptr with --read-timeout-s 0
  std::unique_ptr<std::atomic<int>[]> busy_ports_;  // config_.connection_threads slots
  std::atomic<unsigned> slots_taken_{0};
};

// Large transient buffers - request bodies, results, responses: a 10,000-point batch moves about
// 6 MB - are kept by malloc for the next request instead of being mapped and unmapped each time,
// which costs a page fault per 4 KiB touched (0.16 per point: a fifth of a batch's CPU time).
// glibc maps blocks above M_MMAP_THRESHOLD and returns free heap tops above M_TRIM_THRESHOLD to
// the kernel; both are raised. glibc keeps what is freed in the arena of the thread that freed
// it, and gives threads arenas of their own up to 8 per CPU of the machine (not of the
// container's quota): a batch on each new connection thread left its buffers in another arena,
// and resident memory grew by one batch's buffers per connection thread (bench/batch_memory.sh:
// +39 MiB per 100,000-point batch, up to ten threads). The arenas are therefore capped at one
// per compute thread (`compute_threads`, the core's pool: its threads allocate per point and
// share no arena), unless MALLOC_ARENA_MAX sets them; connection threads share those, and memory
// stays at the high-water mark of the requests in flight, which the body and in-flight point
// limits bound. Call once, before the server's threads exist.
void keep_large_buffers_for_reuse(unsigned compute_threads);

}  // namespace footpoint::server
