#include "http_server.hpp"

#include <malloc.h>
#include <netdb.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/uio.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <httplib.h>

#include "connections.hpp"
#include "project_stream.hpp"
#include "request_log.hpp"

namespace footpoint::server {

namespace {

using Clock = std::chrono::steady_clock;

// What the log line and the metrics need about the request the current connection thread is
// answering: httplib runs pre-routing, the handler and the logger of one request on one thread.
struct RequestContext {
  bool active = false;  // false when httplib answered before pre-routing (malformed request)
  Clock::time_point start;
  std::string request_id;
  RouteMatch match;             // matched once, by admission ({id} views the request's path)
  std::size_t body_length = 0;  // Content-Length, read once by admission
  std::string media;            // the Content-Type's media type, read once by admission
  std::size_t points = 0;
  std::string error_code;       // the code of the error answered, for the log line
  bool admitted = false;        // already checked when the client asked "Expect: 100-continue"
  std::string key;              // the API key's name, "" without keys or before authentication
  bool stream_pending = false;  // a streamed answer admitted and not yet started (streams_starting_)
  // the body's bytes read so far when it is read as it is answered (else req.body holds it)
  std::shared_ptr<std::atomic<std::size_t>> body_read;
  std::function<void()> release;  // ApiResponse::release of the answer
};
thread_local RequestContext t_request;

// The busy slot of the connection thread running this code, and the server it belongs to.
struct ConnectionSlot {
  const void* owner = nullptr;
  std::atomic<int>* port = nullptr;
};
thread_local ConnectionSlot t_slot;

// The socket of the connection a request came on (httplib does not hand it to handlers), found by
// both ends' addresses as httplib wrote them (numeric host); -1 when there is none.
int connection_socket(const httplib::Request& req) {
  int found = -1;
  for_each_connection(req.local_port, [&](int fd, const sockaddr_storage& peer) {
    if (found < 0 && port_of(peer) == req.remote_port && host_of(peer) == req.remote_addr) found = fd;
  });
  return found;
}

// Sends `piece` on fd as one chunk of a chunked HTTP/1.1 body (RFC 9112 section 7.1), waiting up
// to timeout_s for room each time the socket is full; false when the peer is gone or the time
// passed.
bool send_chunk(int fd, std::string_view piece, int timeout_s) {
  char size_line[24];
  const int n = std::snprintf(size_line, sizeof size_line, "%zx\r\n", piece.size());
  char crlf[] = "\r\n";
  iovec parts[3] = {
      {size_line, static_cast<std::size_t>(n)}, {const_cast<char*>(piece.data()), piece.size()}, {crlf, 2}};
  iovec* part = parts;
  std::size_t left = 3;
  while (left > 0) {
    pollfd p{fd, POLLOUT, 0};
    const int ready = ::poll(&p, 1, timeout_s * 1000);
    if (ready < 0 && errno == EINTR) continue;
    if (ready <= 0 || (p.revents & (POLLERR | POLLHUP | POLLNVAL))) return false;
    msghdr message{};
    message.msg_iov = part;
    message.msg_iovlen = left;
    const ssize_t sent = ::sendmsg(fd, &message, MSG_NOSIGNAL | MSG_DONTWAIT);
    if (sent < 0) {
      if (errno == EINTR || errno == EAGAIN || errno == EWOULDBLOCK) continue;
      return false;
    }
    auto done = static_cast<std::size_t>(sent);
    while (left > 0 && done >= part->iov_len) {
      done -= part->iov_len;
      ++part;
      --left;
    }
    if (left > 0) {
      part->iov_base = static_cast<char*>(part->iov_base) + done;
      part->iov_len -= done;
    }
  }
  return true;
}

std::string lower(std::string s) {
  for (auto& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// "application/json; charset=utf-8" -> "application/json"
std::string media_type(const std::string& content_type) {
  std::string t = content_type.substr(0, content_type.find(';'));
  const auto b = t.find_first_not_of(" \t"), e = t.find_last_not_of(" \t");
  return b == std::string::npos ? std::string() : lower(t.substr(b, e - b + 1));
}

bool parse_length(const std::string& text, std::size_t& length) {
  if (text.empty() || text.size() > 18) return false;
  length = 0;
  for (char c : text) {
    if (c < '0' || c > '9') return false;
    length = length * 10 + static_cast<std::size_t>(c - '0');
  }
  return true;
}

// `socket` >= 0: a stream's pieces are sent on it directly (see the POST handler).
void set_response(httplib::Response& res, ApiResponse&& r, int socket = -1, int timeout_s = 0) {
  t_request.error_code = std::move(r.error_code);
  res.status = r.status;
  res.body = std::move(r.body);
  // (a stream's type is set with its provider, which would add a second header)
  if (!r.content_type.empty() && !r.stream) res.set_header("Content-Type", r.content_type);
  if (!r.location.empty()) res.set_header("Location", r.location);
  if (r.retry_after_s > 0) res.set_header("Retry-After", std::to_string(r.retry_after_s));
  for (const auto& [name, value] : r.headers) res.set_header(name, value);
  if (r.stream) {
    // Sent with chunked transfer as it is produced; the provider is called once (the stream
    // loops over its windows itself) and must not write an empty piece: httplib takes one for
    // the end of the stream.
    res.set_chunked_content_provider(r.content_type, [stream = std::move(r.stream), socket, timeout_s](
                                                         std::size_t, httplib::DataSink& sink) {
      const bool whole = stream([&sink, socket, timeout_s](std::string_view piece) {
        if (piece.empty()) return true;
        if (socket >= 0) return send_chunk(socket, piece, timeout_s);
        return sink.is_writable() && sink.write(piece.data(), piece.size());
      });
      if (whole) sink.done();
      return whole;
    });
  }
}

// Answers from admission (false: not admitted). When the request carries a body that will now
// not be read, the connection must close: its unread bytes cannot be taken for the next request.
bool reject(httplib::Response& res, const ApiError& error, bool close) {
  set_response(res, Api::error_response(error));
  if (close) res.set_header("Connection", "close");
  return false;
}

// How long, and how many bytes, a connection refused before its body was read goes on reading
// and dropping what its client still sends, after the answer (end_after_answer).
constexpr auto kLingerTime = std::chrono::seconds(2);
constexpr std::size_t kLingerBytes = std::size_t{256} << 20;

// A lingering close's reading half (RFC 9112 section 9.6): after the answer, the socket is
// half-closed (FIN: the client reads the answer to its end), then what the client still sends is
// read and dropped until it closes its side, for at most kLingerTime and kLingerBytes. Closing at
// once with the client's bytes unread would make the kernel reset the connection, and a client
// still sending may then lose the answer before it reads it.
void linger(int fd) {
  ::shutdown(fd, SHUT_WR);
  std::vector<char> scratch(64 << 10);
  std::size_t dropped = 0;
  const auto until = Clock::now() + kLingerTime;
  while (dropped < kLingerBytes) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(until - Clock::now()).count();
    if (left <= 0) return;
    pollfd p{fd, POLLIN, 0};
    const int ready = ::poll(&p, 1, static_cast<int>(left));
    if (ready < 0 && errno == EINTR) continue;
    if (ready <= 0) return;
    const ssize_t got = ::recv(fd, scratch.data(), scratch.size(), MSG_DONTWAIT);
    if (got < 0 && (errno == EINTR || errno == EAGAIN || errno == EWOULDBLOCK)) continue;
    if (got <= 0) return;  // the client closed its side, or the connection failed
    dropped += static_cast<std::size_t>(got);
  }
}

// Ends the connection of a request refused before its body was read, once its answer is sent.
// httplib (0.11) keeps a connection open whatever the answer's Connection header says, and would
// read the unread body as the next requests (thousands of 400s for a binary body, or a request
// smuggled in it). The answer's body is therefore sent by a content provider that lingers
// (linger) and then returns false, on which httplib closes the connection.
void end_after_answer(const httplib::Request& req, httplib::Response& res) {
  const int fd = req.method == "HEAD" ? -1 : connection_socket(req);
  if (fd < 0) return;
  const std::string type = res.get_header_value("Content-Type");
  res.headers.erase("Content-Type");  // the provider sets it
  std::string body = std::move(res.body);
  res.body.clear();
  const std::size_t size = body.size();
  res.set_content_provider(
      size, type,
      [body = std::move(body), fd](std::size_t offset, std::size_t length, httplib::DataSink& sink) {
        if (sink.write(body.data() + offset, length)) linger(fd);
        return false;
      });
}

// The JSON error for a status httplib set itself.
ApiError http_error(int status) {
  switch (status) {
    case 400:
      return ApiError(400, "bad_request", "malformed HTTP request");
    case 404:
      return ApiError(404, "route_not_found", "no such route (see GET /openapi.yaml)");
    case 408:
      return ApiError(408, "request_timeout", "the request was not received in time");
    case 413:
      return ApiError(
          413, "body_too_large",
          "the body is over the size limit (--max-body-bytes): split the batch into smaller requests",
          "body");
    case 414:
      return ApiError(414, "uri_too_long", "the request URI is too long");
    case 416:
      return ApiError(416, "range_not_satisfiable", "ranges are not supported");
    default:
      return ApiError(status, "http_error", "HTTP error " + std::to_string(status));
  }
}

// The shared registry the configuration names, started (logging first: it logs its connection).
std::unique_ptr<GeometryRegistry> start_registry(const ServerConfig& config, GeometryCache& cache) {
  if (config.registry_url.empty()) return nullptr;
  init_logging(config.log_level);
  RegistryOptions options;
  options.endpoint = redis::parse_url(config.registry_url);
  options.endpoint.password = config.registry_password;
  options.timeout = config.registry_timeout;
  options.pool_size = config.registry_pool_size;
  options.ttl = config.registry_ttl;
  options.max_entry_bytes = config.max_body_bytes;
  return std::make_unique<GeometryRegistry>(std::move(options), cache);
}

// The keys file the configuration names, read (nullptr: no authentication).
std::shared_ptr<const KeyRing> load_keys(const ServerConfig& config) {
  if (config.api_keys.empty()) return nullptr;
  return std::make_shared<const KeyRing>(KeyRing::load(config.api_keys));
}

std::unique_ptr<TlsCredentials> load_tls(const ServerConfig& config) {
  if (config.tls_cert.empty()) return nullptr;
  return std::make_unique<TlsCredentials>(config.tls_cert, config.tls_key);
}

// httplib's HTTPS server when there are credentials, its plain one otherwise.
std::unique_ptr<httplib::Server> make_listener(TlsCredentials* tls) {
  if (!tls) return std::make_unique<httplib::Server>();
  auto server = std::make_unique<httplib::SSLServer>([tls](SSL_CTX& ctx) { return tls->configure(ctx); });
  if (!server->is_valid()) throw std::runtime_error("OpenSSL refused the TLS settings");
  return server;
}

// The secret of "Authorization: Bearer SECRET" (RFC 6750 section 2.1; the scheme's case is free),
// or "" when the header is absent or of another scheme.
std::string_view bearer_token(const std::string& authorization) {
  constexpr std::string_view scheme = "bearer ";
  if (authorization.size() <= scheme.size() || lower(authorization.substr(0, scheme.size())) != scheme)
    return {};
  std::string_view token = std::string_view(authorization).substr(scheme.size());
  const auto b = token.find_first_not_of(' '), e = token.find_last_not_of(' ');
  return b == std::string_view::npos ? std::string_view() : token.substr(b, e - b + 1);
}

// 429 for a request whose points the bucket of `key` ("": the one shared without keys) lacks.
ApiError rate_limited(const std::string& key, std::size_t points, std::size_t rate,
                      const RateLimiter::Decision& decision) {
  ApiError error(429, "rate_limited",
                 "the request's " + std::to_string(points) + (points == 1 ? " point is" : " points are") +
                     " over the rate limit of " +
                     (key.empty() ? std::string("this server") : "the key " + key) + " (--rate-limit " +
                     std::to_string(rate) + " points/s): retry after the Retry-After seconds");
  error.retry_after_s = decision.retry_after_s;
  return error;
}

bool counts_points(Route r) {
  return r == Route::project || r == Route::geometry_project || r == Route::geometry_evaluate;
}

}  // namespace

HttpServer::HttpServer(ServerConfig config, Handler handler)
    : config_(std::move(config)),
      cache_(GeometryCacheOptions{config_.cache_entries, config_.cache_bytes,
                                  config_.effective_max_geometry_bytes(), config_.cache_share}),
      registry_(start_registry(config_, cache_)),
      pool_(config_.threads),
      api_(config_, cache_, pool_, metrics_, registry_.get()),
      handler_(std::move(handler)),
      tls_(load_tls(config_)),
      keys_(load_keys(config_)),
      limiter_(config_.rate_limit
                   ? std::make_unique<RateLimiter>(static_cast<double>(config_.rate_limit),
                                                   static_cast<double>(config_.effective_rate_burst()))
                   : nullptr),
      custom_handler_(static_cast<bool>(handler_)),
      http_(make_listener(tls_.get())),
      busy_ports_(std::make_unique<std::atomic<int>[]>(config_.connection_threads)) {
  start_read_deadline();
  init_logging(config_.log_level);
  log_exposure();
  if (!handler_)
    handler_ = [this](const RouteMatch& m, std::string_view method, std::string_view body,
                      std::string_view query,
                      const Caller& caller) { return api_.handle(m, method, body, query, caller); };
  configure_listener();
  install_admission();
  install_routes();
  install_error_answers();
  install_request_log();
}

void HttpServer::start_read_deadline() {
  if (config_.read_timeout_s <= 0) return;
  const std::chrono::milliseconds timeout(1000 * config_.read_timeout_s);
  read_deadline_ = std::make_unique<ReadDeadline>(
      timeout, std::min<std::chrono::milliseconds>(timeout / 4, std::chrono::seconds(1)),
      [this](const std::string& host, int port) {
        metrics_.add_read_timeout();
        log_event(spdlog::level::warn,
                  "connection closed: its request did not arrive within --read-timeout-s",
                  {{"remote", host}, {"port", port}, {"read_timeout_s", config_.read_timeout_s}});
      });
}

void HttpServer::log_exposure() const {
  if (keys_)
    log_event(spdlog::level::info, "API keys loaded", {{"file", config_.api_keys}, {"keys", keys_->size()}});
  else
    log_event(spdlog::level::warn, "no authentication: every client may call every route (see --api-keys)");
  if (tls_) log_event(spdlog::level::info, "TLS certificate loaded", {{"certificate", tls_->describe()}});
}

void HttpServer::configure_listener() {
  httplib::Server& http = *http_;
  const unsigned connection_threads = config_.connection_threads;
  http.new_task_queue = [connection_threads] { return new httplib::ThreadPool(connection_threads); };
  http.set_tcp_nodelay(true);
  // SO_REUSEADDR only: restarts need not wait for TIME_WAIT, but unlike httplib's default
  // SO_REUSEPORT a second instance cannot bind the same port and silently share it.
  // httplib calls this for the listening socket only (each address it tries; the last is kept):
  // the backlog is set on it after binding.
  http.set_socket_options([this](socket_t fd) {
    int yes = 1;
    ::setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
    listen_fd_ = fd;
  });
  http.set_keep_alive_max_count(config_.keep_alive_max);
  http.set_keep_alive_timeout(config_.keep_alive_timeout_s);
  http.set_read_timeout(config_.io_timeout_s);
  http.set_write_timeout(config_.io_timeout_s);
  http.set_payload_max_length(config_.max_body_bytes);
}

void HttpServer::install_admission() {
  httplib::Server& http = *http_;
  // A client that waits for "100 Continue" before sending its body (curl does for large
  // bodies) gets the final answer instead when the request would be refused anyway.
  http.set_expect_100_continue_handler([this](const httplib::Request& req, httplib::Response& res) {
    if (!admit(req, res)) return res.status;
    t_request.admitted = true;
    return 100;
  });
  http.set_pre_routing_handler([this](const httplib::Request& req, httplib::Response& res) {
    if (t_request.admitted) {
      t_request.admitted = false;
      return httplib::Server::HandlerResponse::Unhandled;
    }
    if (admit(req, res)) return httplib::Server::HandlerResponse::Unhandled;
    // Refused with its body unread (reject's close): the connection ends after the answer. Over
    // TLS the raw socket is not ours to half-close; the connection stays as httplib keeps it.
    if (!tls_ && res.get_header_value("Connection") == "close") end_after_answer(req, res);
    return httplib::Server::HandlerResponse::Handled;
  });
}

bool HttpServer::admit(const httplib::Request& req, httplib::Response& res) {
  RequestContext& ctx = t_request;
  ctx = RequestContext{};
  ctx.active = true;
  ctx.start = Clock::now();
  mark_busy(req.remote_port);
  if (read_deadline_) read_deadline_->admitted(req.remote_addr, req.remote_port);
  // httplib would compress the response by the client's Accept-Encoding (brotli at quality 11
  // costs far more than the projection) and cut it by Range: the service sends plain, whole
  // bodies. The request object is httplib's own mutable one, handed over as const.
  auto& mutable_req = const_cast<httplib::Request&>(req);
  mutable_req.headers.erase("Accept-Encoding");
  mutable_req.headers.erase("Range");
  mutable_req.ranges.clear();

  const std::string given_id = req.get_header_value("X-Request-Id");
  ctx.request_id = acceptable_request_id(given_id) ? given_id : make_request_id();
  res.set_header("X-Request-Id", ctx.request_id);

  Framing framing;
  framing.has_length = req.has_header("Content-Length");
  framing.chunked = req.has_header("Transfer-Encoding");
  if (framing.has_length && !parse_length(req.get_header_value("Content-Length"), framing.length))
    return reject(res, ApiError(400, "bad_request", "invalid Content-Length"), true);
  // Several Content-Length headers that disagree make the body's end ambiguous (request smuggling).
  for (std::size_t i = 1; framing.has_length && i < req.get_header_value_count("Content-Length"); ++i) {
    std::size_t other = 0;
    if (!parse_length(req.get_header_value("Content-Length", i), other) || other != framing.length)
      return reject(res, ApiError(400, "bad_request", "conflicting Content-Length headers"), true);
  }
  const bool has_body = framing.chunked || framing.length > 0;
  ctx.body_length = framing.length;
  ctx.media = media_type(req.get_header_value("Content-Type"));

  // The route is matched here once; the handlers read it from the request's context.
  ctx.match = match_route(req.method, req.path);
  const RouteMatch& match = ctx.match;
  // A streamed projection is counted from here until its answer starts (shutdown() waits for
  // them: see there). Counted before the shutting-down check, which shutdown() makes visible
  // before it reads the count: one of the two sees the other.
  if (req.method == "POST" && (match.route == Route::geometry_project || match.route == Route::project) &&
      answer_format(req.get_header_value("Accept")) != AnswerFormat::json) {
    ctx.stream_pending = true;
    streams_starting_.fetch_add(1);
  }
  if (api_.shutting_down())
    return reject(
        res, ApiError(503, "shutting_down", "the server is shutting down; retry on another replica"), true);
  if (match.route == Route::none)
    return reject(res, ApiError(404, "route_not_found", "no route " + req.path + " (see GET /openapi.yaml)"),
                  has_body);
  if (const auto cors = cross_origin(req, res, has_body)) return *cors;
  if (!match.method_allowed) {
    res.set_header("Allow", match.allow);
    return reject(res,
                  ApiError(405, "method_not_allowed",
                           req.method + " is not allowed on " + route_template(match.route) +
                               " (allowed: " + match.allow + ")"),
                  has_body);
  }
  if (!authorize(req, res, has_body)) return false;
  if (!rate_limit(req, res, has_body)) return false;
  if (!accept_body(req, res, framing)) return false;
  return req.method != "POST" || shed_load(res);
}

std::optional<bool> HttpServer::cross_origin(const httplib::Request& req, httplib::Response& res,
                                             bool has_body) const {
  if (config_.cors_origins.empty() || !req.has_header("Origin")) return std::nullopt;
  // Cross-origin calls from the configured origins' pages: their responses (errors too) may be
  // read by the page, and a preflight OPTIONS is answered here.
  const std::string origin = req.get_header_value("Origin");
  bool any = false, allowed = false;
  for (const auto& o : config_.cors_origins) {
    any = any || o == "*";
    allowed = allowed || o == "*" || o == origin;
  }
  res.set_header("Vary", "Origin");
  if (allowed) {
    res.set_header("Access-Control-Allow-Origin", any ? "*" : origin);
    res.set_header("Access-Control-Expose-Headers",
                   "X-Request-Id, Location, Retry-After, Content-Disposition, X-Footpoint-Record, "
                   "X-Footpoint-Record-Bytes");
  }
  if (req.method != "OPTIONS") return std::nullopt;
  if (!allowed)
    return reject(res,
                  ApiError(403, "origin_not_allowed",
                           "origin " + origin + " may not call this API (--cors-origins lists the origins)"),
                  has_body);
  res.status = 204;
  res.set_header("Access-Control-Allow-Methods", t_request.match.allow);
  res.set_header("Access-Control-Allow-Headers", "Authorization, Content-Type, X-Request-Id");
  res.set_header("Access-Control-Max-Age", "600");
  return false;
}

bool HttpServer::authorize(const httplib::Request& req, httplib::Response& res, bool has_body) const {
  // Who calls, and may they: the key's scope for the route (RFC 6750 section 3 for the
  // WWW-Authenticate values).
  RequestContext& ctx = t_request;
  const Route route = ctx.match.route;
  const Scope scope = required_scope(route, req.method, config_.metrics_key_free);
  const auto keys = this->keys();
  if (!keys || scope == kScopeNone) return true;
  const std::string authorization = req.get_header_value("Authorization");
  const std::string_view secret = bearer_token(authorization);
  const ApiKey* key = keys->authenticate(secret);
  if (!key) {
    res.set_header("WWW-Authenticate", secret.empty() ? R"(Bearer realm="footpoint")"
                                                      : R"(Bearer realm="footpoint", error="invalid_token")");
    return reject(res,
                  secret.empty()
                      ? ApiError(401, "missing_api_key",
                                 "this route needs an API key: send Authorization: Bearer SECRET")
                      : ApiError(401, "invalid_api_key", "the API key is not known to this server"),
                  has_body);
  }
  ctx.key = key->name;
  if (key->allows(scope)) return true;
  res.set_header("WWW-Authenticate",
                 std::string(R"(Bearer realm="footpoint", error="insufficient_scope", scope=")") +
                     scope_name(scope) + "\"");
  return reject(res,
                ApiError(403, "insufficient_scope",
                         "the API key " + key->name + " lacks the scope " + scope_name(scope) +
                             " (or admin) that " + req.method + " " + route_template(route) + " needs"),
                has_body);
}

bool HttpServer::rate_limit(const httplib::Request& req, httplib::Response& res, bool has_body) const {
  const RequestContext& ctx = t_request;
  const Route route = ctx.match.route;
  if (!limiter_ || route == Route::metrics || required_scope(route, req.method, false) == kScopeNone)
    return true;
  // Point-counting requests take their points once the body is read (Caller::charge); the others
  // take one point now.
  const auto decision = counts_points(route) ? limiter_->check(ctx.key) : limiter_->take(ctx.key, 1.0);
  if (decision.allowed) return true;
  return reject(res, rate_limited(ctx.key, 1, config_.rate_limit, decision), has_body);
}

bool HttpServer::accept_body(const httplib::Request& req, httplib::Response& res,
                             const Framing& framing) const {
  if (framing.chunked)
    return reject(res,
                  ApiError(411, "length_required",
                           "send the body with a Content-Length (Transfer-Encoding is not accepted)"),
                  true);
  if (req.method != "POST") {
    if (framing.length > 0)
      return reject(res, ApiError(400, "body_not_allowed", req.method + " takes no body"), true);
    return true;
  }
  if (!framing.has_length)
    return reject(res, ApiError(411, "length_required", "a Content-Length header is required"), true);
  if (framing.length > config_.max_body_bytes)
    return reject(res,
                  ApiError(413, "body_too_large",
                           "the body has " + std::to_string(framing.length) + " bytes, over the limit of " +
                               std::to_string(config_.max_body_bytes) +
                               " (--max-body-bytes): split the batch into smaller requests, or have the "
                               "operator raise --max-body-bytes",
                           "body"),
                  true);
  const std::string encoding = lower(req.get_header_value("Content-Encoding"));
  if (!encoding.empty() && encoding != "identity")
    return reject(res,
                  ApiError(415, "unsupported_content_encoding",
                           "Content-Encoding " + encoding + " is not accepted; send the JSON uncompressed"),
                  true);
  // Points may also come as binary (application/octet-stream) to the projection routes.
  const std::string& media = t_request.media;
  const Route route = t_request.match.route;
  const bool projection = route == Route::geometry_project || route == Route::project;
  if (media != "application/json" && !(projection && media == "application/octet-stream"))
    return reject(res,
                  ApiError(415, "unsupported_media_type",
                           projection ? "the body must be JSON (Content-Type: application/json) or points in "
                                        "binary (Content-Type: application/octet-stream)"
                                      : "the body must be JSON (Content-Type: application/json)"),
                  true);
  return true;
}

bool HttpServer::shed_load(httplib::Response& res) {
  if (is_compute_route(t_request.match.route) && api_.in_flight() >= config_.effective_max_inflight())
    return reject(res, ApiError(503, "overloaded", "too many requests in progress; retry shortly"), true);
  return true;
}

void HttpServer::answer(const httplib::Request& req, httplib::Response& res, const BodySource* source,
                        int socket) {
  if (read_deadline_) read_deadline_->handling(req.remote_addr, req.remote_port);
  const RouteMatch& match = t_request.match;
  const auto question = req.target.find('?');
  const std::string_view query =
      question == std::string::npos ? std::string_view() : std::string_view(req.target).substr(question + 1);
  Caller caller;
  caller.key = t_request.key;
  if (req.method == "POST") {
    auto watch = std::make_shared<ConnectionWatch>(port_, req.remote_addr, req.remote_port);
    caller.client_gone = [watch] { return watch->closed(); };
  }
  if (limiter_ && counts_points(match.route))
    caller.charge = [this](std::size_t points) {
      const std::string& key = t_request.key;
      if (static_cast<double>(points) > limiter_->burst())
        throw ApiError(413, "points_over_burst",
                       "the request has " + std::to_string(points) +
                           " points, more than the rate limit's burst of " +
                           std::to_string(config_.effective_rate_burst()) +
                           " (--rate-burst): split it into smaller requests",
                       "points");
      const auto decision = limiter_->take(key, static_cast<double>(points));
      if (decision.allowed) return;
      throw rate_limited(key, points, config_.rate_limit, decision);
    };
  ApiResponse r = custom_handler_
                      ? handler_(match, req.method, req.body, query, caller)
                      : api_.handle(match, req.method, req.body, query, caller,
                                    RequestFormat{t_request.media, req.get_header_value("Accept"), source});
  t_request.points = r.points;
  t_request.release = std::move(r.release);
  // an answer that left part of the body unread is the connection's last: the rest cannot be
  // taken for the next request
  const bool unread = source && !r.stream && t_request.body_read->load() < source->length;
  if (r.stream)
    r.stream = [this, stream = std::move(r.stream)](const ApiResponse::Write& write) {
      stream_started();
      return stream(write);
    };
  set_response(res, std::move(r), socket, config_.io_timeout_s);
  if (unread) {
    res.set_header("Connection", "close");
    end_after_answer(req, res);
  }
  // A request answered while the server shuts down is the connection's last.
  if (api_.shutting_down()) res.set_header("Connection", "close");
}

void HttpServer::install_routes() {
  httplib::Server& http = *http_;
  auto handle = [this](const httplib::Request& req, httplib::Response& res) {
    answer(req, res, nullptr, -1);
  };
  http.Get(".*", handle);
  http.Post(".*", handle);  // without a body
  http.Delete(".*", handle);
  // A POST with a body. The binary points of a streamed projection are read as they are answered
  // (streamed_body.hpp), so that the memory a stream holds does not grow with its points; other
  // bodies are read whole first. One thread reads the body through httplib while the connection's
  // thread writes the answer; that one writes on the socket itself: httplib checks before each
  // write that the peer is alive by peeking at the socket when it is readable, a peek that blocks
  // when the reading thread took the bytes in between. Over TLS the points are read whole: an
  // OpenSSL connection cannot be read by one thread while another writes it.
  http.Post(".*", [this](const httplib::Request& req, httplib::Response& res,
                         const httplib::ContentReader& content_reader) {
    const Route route = t_request.match.route;
    const bool as_sent = !custom_handler_ && !tls_ &&
                         (route == Route::geometry_project || route == Route::project) &&
                         t_request.media == "application/octet-stream" &&
                         answer_format(req.get_header_value("Accept")) != AnswerFormat::json;
    const std::size_t length = t_request.body_length;
    const int socket = as_sent ? connection_socket(req) : -1;
    if (socket < 0) {
      auto& mutable_req = const_cast<httplib::Request&>(req);
      mutable_req.body.reserve(length);
      // false: the body ended short, and httplib set the status (400)
      if (!content_reader([&mutable_req](const char* data, std::size_t size) {
            mutable_req.body.append(data, size);
            return true;
          })) {
        res.set_header("Connection", "close");
        return;
      }
      answer(req, res, nullptr, -1);
      return;
    }
    auto read = std::make_shared<std::atomic<std::size_t>>(0);
    t_request.body_read = read;
    BodySource source;
    source.length = length;
    source.read = [content_reader, read](const BodySource::Receiver& receive) {
      return content_reader([&](const char* data, std::size_t size) {
        read->fetch_add(size);
        return receive(data, size);
      });
    };
    answer(req, res, &source, socket);
  });
}

void HttpServer::install_error_answers() {
  httplib::Server& http = *http_;
  // Called for every status >= 400. Errors httplib answers itself (malformed request line or
  // headers, URI too long, a body that could not be read) get the same JSON error shape.
  http.set_error_handler(
      httplib::Server::HandlerWithResponse([](const httplib::Request& req, httplib::Response& res) {
        // "Handled" also makes httplib set Content-Length on a response it would otherwise send
        // without one (an answer to "Expect: 100-continue").
        const_cast<httplib::Request&>(req).headers.erase("Accept-Encoding");
        if (!res.has_header("X-Request-Id"))
          res.set_header("X-Request-Id", t_request.active ? t_request.request_id : make_request_id());
        if (res.body.empty() && !res.content_provider_) {  // (a provider: end_after_answer's)
          const ApiError error = http_error(res.status);
          res.body = error_body(error);
          res.set_header("Content-Type", "application/json");
          t_request.error_code = error.code;
        }
        return httplib::Server::HandlerResponse::Handled;
      }));
  // Without this, httplib would put the exception text in a response header.
  http.set_exception_handler([](const httplib::Request&, httplib::Response& res, const std::exception_ptr&) {
    set_response(res, Api::error_response(ApiError(500, "internal_error", "internal error")));
  });
}

void HttpServer::install_request_log() {
  // Called once per request after its response is written; an exception here would abort the
  // process, hence the catch-all.
  http_->set_logger([this](const httplib::Request& req, const httplib::Response& res) {
    try {
      RequestContext& ctx = t_request;
      if (ctx.release) std::exchange(ctx.release, nullptr)();
      const double seconds =
          ctx.active ? std::chrono::duration<double>(Clock::now() - ctx.start).count() : 0.0;
      const Route route = ctx.active ? ctx.match.route : Route::none;
      metrics_.observe_request(route, res.status, seconds);
      if (ctx.active && !ctx.key.empty()) metrics_.observe_key(ctx.key, res.status);
      RequestRecord record;
      record.request_id = ctx.active ? std::string_view(ctx.request_id) : std::string_view("-");
      record.method = req.method;
      record.path = req.path;
      record.route = route_template(route);
      record.remote_addr = req.remote_addr;
      record.status = res.status;
      record.code = ctx.error_code;
      record.points = ctx.active ? ctx.points : 0;
      record.body_bytes = ctx.active && ctx.body_read ? ctx.body_read->load() : req.body.size();
      record.duration_ms = seconds * 1e3;
      record.key = ctx.active ? std::string_view(ctx.key) : std::string_view();
      log_request(record);
      if (read_deadline_) read_deadline_->answered(req.remote_addr, req.remote_port);
      stream_started();  // an answer that was no stream (an error), or one never started
      ctx.active = false;
      ctx.key.clear();
      ctx.error_code.clear();
      ctx.body_read.reset();
      mark_idle();
    } catch (...) {
    }
  });
}

HttpServer::~HttpServer() { shutdown(); }

int HttpServer::bind() {
  const bool any = config_.port == 0;
  const int port = any ? http_->bind_to_any_port(config_.host) : config_.port;
  if (port < 0 || (!any && !http_->bind_to_port(config_.host, config_.port)))
    throw std::runtime_error("cannot listen on " + config_.host + ":" + std::to_string(config_.port) + ": " +
                             std::strerror(errno));
  // httplib listens with a backlog of 5: connection bursts beyond it would be refused or
  // retried by the kernel, so listen again with the configured length.
  if (listen_fd_ < 0 || ::listen(listen_fd_, config_.backlog) != 0)
    throw std::runtime_error(std::string("listen() failed: ") + std::strerror(errno));
  if (config_.probe_port > 0) {
    // Two threads of its own and short timeouts: a probe is one small request.
    probes_ = std::make_unique<httplib::Server>();
    probes_->new_task_queue = [] { return new httplib::ThreadPool(2); };
    probes_->set_read_timeout(2);
    probes_->set_write_timeout(2);
    probes_->set_keep_alive_timeout(2);
    auto probe = [this](const httplib::Request& req, httplib::Response& res) {
      ApiResponse r = api_.handle(match_route("GET", req.path), "GET", "");
      res.status = r.status;
      res.set_content(r.body, r.content_type);
    };
    probes_->Get("/healthz", probe);
    probes_->Get("/readyz", probe);
    if (!probes_->bind_to_port(config_.host, config_.probe_port))
      throw std::runtime_error("cannot listen on " + config_.host + ":" + std::to_string(config_.probe_port) +
                               " (--probe-port): " + std::strerror(errno));
  }
  port_ = port;
  return port;
}

void HttpServer::run() {
  // Publish "starting" before looking at the shutdown flag: shutdown() sets the flag before
  // reading the state, so one of the two always sees the other.
  run_state_.store(RunState::starting);
  if (probes_)
    probe_thread_ = std::thread([this] {
      probes_->listen_after_bind();
      probes_done_.store(true);
    });
  if (read_deadline_ && port_ >= 0) read_deadline_->start(port_);
  if (!api_.shutting_down() && port_ >= 0) http_->listen_after_bind();
  if (read_deadline_) read_deadline_->stop();
  if (probes_) {
    // httplib ignores stop() until its listen loop runs: wait for it to start (or to have failed).
    while (!probes_->is_running() && !probes_done_.load())
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    probes_->stop();
    probe_thread_.join();
  }
  run_state_.store(RunState::finished);
}

std::shared_ptr<const KeyRing> HttpServer::keys() const {
  std::lock_guard lock(keys_mutex_);
  return keys_;
}

bool HttpServer::reload() {
  bool ok = true;
  if (!config_.api_keys.empty()) {
    try {
      auto fresh = load_keys(config_);
      const std::size_t count = fresh->size();
      {
        std::lock_guard lock(keys_mutex_);
        keys_ = std::move(fresh);
      }
      log_event(spdlog::level::info, "API keys reloaded", {{"file", config_.api_keys}, {"keys", count}});
    } catch (const std::exception& e) {
      ok = false;
      log_event(spdlog::level::err, "API keys not reloaded: the previous keys stay in use",
                {{"error", e.what()}});
    }
  }
  if (tls_) {
    try {
      tls_->reload();
      log_event(spdlog::level::info, "TLS certificate reloaded", {{"certificate", tls_->describe()}});
    } catch (const std::exception& e) {
      ok = false;
      log_event(spdlog::level::err, "TLS certificate not reloaded: the previous one stays in use",
                {{"error", e.what()}});
    }
  }
  return ok;
}

void HttpServer::shutdown() {
  api_.set_shutting_down();
  std::lock_guard lock(stop_mutex_);
  if (stopped_) return;
  // httplib ignores stop() until listen_after_bind() is running: wait for it to start (or to
  // have given up). When run() was never called there is nothing to stop.
  while (run_state_.load() == RunState::starting && !http_->is_running())
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  if (http_->is_running()) {
    // httplib calls a streamed answer's producer only while it has not been stopped (its chunked
    // writer checks before every call): a stream admitted but not yet started would be cut. Those
    // are waited for (the time to read and check their bodies, bounded by the timeouts); a stream
    // that has started runs to its end as a batch does.
    const auto give_up = Clock::now() + std::chrono::seconds(config_.io_timeout_s) +
                         std::max(config_.deadline, config_.compile_deadline);
    while (streams_starting_.load() > 0 && Clock::now() < give_up)
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    http_->stop();
    stopped_ = true;
    close_idle_connections();
  }
}

void HttpServer::stream_started() {
  if (!t_request.stream_pending) return;
  t_request.stream_pending = false;
  streams_starting_.fetch_sub(1);
}

void HttpServer::mark_busy(int remote_port) {
  if (t_slot.owner != this) {
    const unsigned slot = slots_taken_.fetch_add(1);
    t_slot = {this, slot < config_.connection_threads ? &busy_ports_[slot] : nullptr};
  }
  if (t_slot.port && remote_port > 0) t_slot.port->store(remote_port);
}

void HttpServer::mark_idle() {
  if (t_slot.owner == this && t_slot.port) t_slot.port->store(0);
}

void HttpServer::close_idle_connections() {
  std::set<int> busy;
  for (unsigned i = 0; i < std::min(slots_taken_.load(), config_.connection_threads); ++i)
    if (const int port = busy_ports_[i].load(); port > 0) busy.insert(port);
  // The process's sockets connected from this server's port: its connections. httplib keeps no
  // list of them, the kernel does.
  for_each_connection(port_, [&busy](int fd, const sockaddr_storage& peer) {
    // Its thread waits for the next request: it reads the end of the stream and closes.
    if (busy.count(port_of(peer)) == 0) ::shutdown(fd, SHUT_RDWR);
  });
}

void keep_large_buffers_for_reuse(unsigned compute_threads) {
  // the largest threshold glibc accepts (half its 64 MiB per-thread heap): below it are the
  // body, points, results and response of batches up to ~90,000 points (a larger one's response
  // is mapped for itself, as before)
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
  mallopt(M_TRIM_THRESHOLD, 512 << 20);
  if (std::getenv("MALLOC_ARENA_MAX") == nullptr)
    mallopt(M_ARENA_MAX, static_cast<int>(std::max(1u, compute_threads)));
}

}  // namespace footpoint::server
