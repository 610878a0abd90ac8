#include "redis/redis_client.hpp"

#include <poll.h>
#include <sys/time.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cstring>
#include <ctime>

#include <hiredis/hiredis.h>

namespace footpoint::redis {

namespace {

int parse_number(std::string_view text, int lo, int hi, const char* what) {
  int value = 0;
  const auto r = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || r.ec != std::errc() || r.ptr != text.data() + text.size() || value < lo || value > hi)
    throw std::invalid_argument(std::string("registry URL: bad ") + what + " '" + std::string(text) + "'");
  return value;
}

// The time left before `deadline`, at least 1 µs (hiredis takes a zero timeout as "none").
timeval time_left(Clock::time_point deadline) {
  const auto left = std::max<std::int64_t>(
      1, std::chrono::duration_cast<std::chrono::microseconds>(deadline - Clock::now()).count());
  return timeval{static_cast<time_t>(left / 1000000), static_cast<suseconds_t>(left % 1000000)};
}

Reply copy_reply(const redisReply* r) {
  Reply out;
  switch (r->type) {
    case REDIS_REPLY_STRING:
      out.type = Reply::Type::string;
      out.str.assign(r->str, r->len);
      break;
    case REDIS_REPLY_ARRAY:
      out.type = Reply::Type::array;
      out.elements.reserve(r->elements);
      for (std::size_t i = 0; i < r->elements; ++i) out.elements.push_back(copy_reply(r->element[i]));
      break;
    case REDIS_REPLY_INTEGER:
      out.type = Reply::Type::integer;
      out.integer = r->integer;
      break;
    case REDIS_REPLY_STATUS:
      out.type = Reply::Type::status;
      out.str.assign(r->str, r->len);
      break;
    case REDIS_REPLY_ERROR:
      out.type = Reply::Type::error;
      out.str.assign(r->str, r->len);
      break;
    default:
      out.type = Reply::Type::nil;
  }
  return out;
}

bool starts_with(const std::string& s, std::string_view prefix) {
  return s.compare(0, prefix.size(), prefix) == 0;
}

// Errors that mean "not allowed as who we are": the password is wrong or missing.
bool is_auth_error(const Reply& r) {
  return r.type == Reply::Type::error &&
         (starts_with(r.str, "NOAUTH") || starts_with(r.str, "WRONGPASS") || starts_with(r.str, "NOPERM") ||
          starts_with(r.str, "ERR invalid password") || starts_with(r.str, "ERR AUTH"));
}

}  // namespace

const char* to_string(Error::Kind kind) {
  switch (kind) {
    case Error::Kind::connect:
      return "connect";
    case Error::Kind::timeout:
      return "timeout";
    case Error::Kind::auth:
      return "auth";
    case Error::Kind::io:
      return "io";
    case Error::Kind::reply:
      return "reply";
  }
  return "io";
}

Endpoint parse_url(std::string_view url) {
  constexpr std::string_view scheme = "redis://";
  if (url.substr(0, scheme.size()) != scheme)
    throw std::invalid_argument("registry URL: expected redis://[user@]host[:port][/db]");
  std::string_view rest = url.substr(scheme.size());
  Endpoint e;
  if (const auto at = rest.rfind('@'); at != std::string_view::npos) {
    const std::string_view user = rest.substr(0, at);
    if (user.find(':') != std::string_view::npos)
      throw std::invalid_argument(
          "registry URL: a password does not belong in the URL (it shows in process lists and logs): "
          "set FOOTPOINT_REGISTRY_PASSWORD or --registry-password-file");
    if (user.empty()) throw std::invalid_argument("registry URL: empty user name before @");
    e.user = std::string(user);
    rest = rest.substr(at + 1);
  }
  std::string_view authority = rest.substr(0, rest.find('/'));
  if (const auto slash = rest.find('/'); slash != std::string_view::npos) {
    const std::string_view db = rest.substr(slash + 1);
    if (!db.empty()) e.db = parse_number(db, 0, 1 << 20, "database number");
  }
  std::string_view port;
  if (!authority.empty() && authority.front() == '[') {  // [IPv6]:port
    const auto close = authority.find(']');
    if (close == std::string_view::npos) throw std::invalid_argument("registry URL: unclosed [ in the host");
    e.host = std::string(authority.substr(1, close - 1));
    const std::string_view after = authority.substr(close + 1);
    if (!after.empty()) {
      if (after.front() != ':') throw std::invalid_argument("registry URL: expected :port after ]");
      port = after.substr(1);
    }
  } else {
    const auto colon = authority.find(':');
    e.host = std::string(authority.substr(0, colon));
    if (colon != std::string_view::npos) port = authority.substr(colon + 1);
  }
  if (e.host.empty()) throw std::invalid_argument("registry URL: no host");
  if (!port.empty()) e.port = parse_number(port, 1, 65535, "port");
  return e;
}

// ---- Connection ---------------------------------------------------------------------------------

Connection::~Connection() { close(); }

Connection::Connection(Connection&& other) noexcept : context_(other.context_), queued_(other.queued_) {
  other.context_ = nullptr;
  other.queued_ = 0;
}

Connection& Connection::operator=(Connection&& other) noexcept {
  if (this != &other) {
    close();
    std::swap(context_, other.context_);
    std::swap(queued_, other.queued_);
  }
  return *this;
}

void Connection::close() {
  if (context_) redisFree(context_);
  context_ = nullptr;
  queued_ = 0;
}

int Connection::fd() const { return context_ ? context_->fd : -1; }

void Connection::fail(Error::Kind kind, const std::string& what) {
  close();
  throw Error(kind, what);
}

void Connection::set_socket_timeout(Clock::time_point deadline) {
  if (Clock::now() >= deadline) fail(Error::Kind::timeout, "registry: timed out");
  if (redisSetTimeout(context_, time_left(deadline)) != REDIS_OK)
    fail(Error::Kind::io, std::string("registry: cannot set the socket timeout: ") + context_->errstr);
}

void Connection::open(const std::string& address, const Endpoint& endpoint, Clock::time_point deadline) {
  close();
  if (Clock::now() >= deadline) throw Error(Error::Kind::timeout, "registry: timed out before connecting");
  context_ = redisConnectWithTimeout(address.c_str(), endpoint.port, time_left(deadline));
  if (!context_) throw Error(Error::Kind::connect, "registry: cannot allocate a connection");
  if (context_->err) {
    const std::string why = context_->errstr;
    const bool timed_out = why.find("timed out") != std::string::npos || Clock::now() >= deadline;
    fail(timed_out ? Error::Kind::timeout : Error::Kind::connect,
         "registry: cannot connect to " + address + ":" + std::to_string(endpoint.port) + ": " + why);
  }
  redisEnableKeepAlive(context_);
  if (!endpoint.password.empty()) {
    const Reply r = endpoint.user.empty() ? command({"AUTH", endpoint.password}, deadline)
                                          : command({"AUTH", endpoint.user, endpoint.password}, deadline);
    // The server's message names no password.
    if (r.type == Reply::Type::error) fail(Error::Kind::auth, "registry refused AUTH: " + r.str);
  }
  if (endpoint.db != 0) {
    const Reply r = command({"SELECT", std::to_string(endpoint.db)}, deadline);
    if (r.type == Reply::Type::error) fail(Error::Kind::auth, "registry refused SELECT: " + r.str);
  }
}

void Connection::append(const std::vector<std::string_view>& args) {
  if (!context_) throw Error(Error::Kind::io, "registry: connection not open");
  std::vector<const char*> argv;
  std::vector<std::size_t> lengths;
  argv.reserve(args.size());
  lengths.reserve(args.size());
  for (const auto& a : args) {
    argv.push_back(a.data());
    lengths.push_back(a.size());
  }
  if (redisAppendCommandArgv(context_, static_cast<int>(args.size()), argv.data(), lengths.data()) !=
      REDIS_OK)
    fail(Error::Kind::io, std::string("registry: cannot queue a command: ") + context_->errstr);
  ++queued_;
}

void Connection::send(Clock::time_point deadline) {
  if (!context_) throw Error(Error::Kind::io, "registry: connection not open");
  set_socket_timeout(deadline);
  int done = 0;
  while (!done) {
    if (redisBufferWrite(context_, &done) != REDIS_OK) {
      const bool timed_out = errno == EAGAIN || errno == EWOULDBLOCK;
      fail(timed_out ? Error::Kind::timeout : Error::Kind::io,
           std::string("registry: cannot send: ") + context_->errstr);
    }
  }
}

std::optional<Reply> Connection::take_reply() {
  void* raw = nullptr;
  if (redisGetReplyFromReader(context_, &raw) != REDIS_OK)
    fail(Error::Kind::io, std::string("registry: protocol error: ") + context_->errstr);
  if (!raw) return std::nullopt;
  Reply r = copy_reply(static_cast<redisReply*>(raw));
  freeReplyObject(raw);
  if (queued_ > 0) --queued_;
  return r;
}

void Connection::receive() {
  if (redisBufferRead(context_) != REDIS_OK)
    fail(Error::Kind::io, std::string("registry: connection lost: ") + context_->errstr);
}

std::vector<Reply> Connection::read_available() {
  if (!context_) throw Error(Error::Kind::io, "registry: connection not open");
  receive();
  std::vector<Reply> replies;
  while (auto r = take_reply()) replies.push_back(std::move(*r));
  return replies;
}

std::optional<Reply> Connection::read(Clock::time_point deadline) {
  if (!context_) throw Error(Error::Kind::io, "registry: connection not open");
  for (;;) {
    if (auto r = take_reply()) return r;
    const auto now = Clock::now();
    if (now >= deadline) return std::nullopt;
    const auto left = std::chrono::duration_cast<std::chrono::nanoseconds>(deadline - now).count();
    timespec wait{static_cast<time_t>(left / 1000000000), static_cast<long>(left % 1000000000)};
    pollfd p{context_->fd, POLLIN, 0};
    const int ready = ::ppoll(&p, 1, &wait, nullptr);
    if (ready < 0 && errno != EINTR)
      fail(Error::Kind::io, std::string("registry: poll: ") + std::strerror(errno));
    if (ready > 0) receive();  // else the deadline check above ends the wait
  }
}

std::vector<Reply> Connection::exchange(Clock::time_point deadline) {
  const std::size_t expected = queued_;
  send(deadline);
  std::vector<Reply> replies;
  replies.reserve(expected);
  while (replies.size() < expected) {
    std::optional<Reply> r = read(deadline);
    if (!r) fail(Error::Kind::timeout, "registry: no reply within the timeout");
    if (is_auth_error(*r)) fail(Error::Kind::auth, "registry refused the command: " + r->str);
    replies.push_back(std::move(*r));
  }
  return replies;
}

Reply Connection::command(const std::vector<std::string_view>& args, Clock::time_point deadline) {
  append(args);
  return std::move(exchange(deadline).back());
}

// ---- Pool ---------------------------------------------------------------------------------------

Pool::Pool(Endpoint endpoint, std::size_t size)
    : endpoint_(std::move(endpoint)), connections_(std::max<std::size_t>(size, 1)) {
  for (std::size_t i = connections_.size(); i-- > 0;) free_.push_back(i);
}

void Pool::set_address(const std::string& address) {
  std::lock_guard lock(mutex_);
  address_ = address;
}

std::string Pool::address() const {
  std::lock_guard lock(mutex_);
  return address_;
}

void Pool::close_idle() {
  std::lock_guard lock(mutex_);
  for (const std::size_t i : free_) connections_[i].close();
}

Pool::Lease::Lease(Pool& pool, Clock::time_point deadline) : pool_(pool) {
  std::unique_lock lock(pool_.mutex_);
  if (!pool_.freed_.wait_until(lock, deadline, [&] { return !pool_.free_.empty(); }))
    throw Error(Error::Kind::timeout, "registry: every connection of the pool was busy until the timeout");
  index_ = pool_.free_.back();
  pool_.free_.pop_back();
}

Pool::Lease::~Lease() {
  {
    std::lock_guard lock(pool_.mutex_);
    pool_.free_.push_back(index_);
  }
  pool_.freed_.notify_one();
}

}  // namespace footpoint::redis
