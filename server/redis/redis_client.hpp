// A Redis client for the shared geometry registry, over hiredis 0.14 (Debian 12), with every step
// bounded by a deadline. hiredis's blocking calls wait as long as the socket options say and a
// redisContext is unusable after any error, so: connecting takes the time left as its timeout,
// every send sets the socket's send timeout to the time left, every read waits with ppoll() for at
// most the time left (a read that finds nothing in time leaves the connection usable: the
// subscriber waits for messages that way), and a connection that failed is closed, never reused.
// A Connection is used by one thread at a time; a Pool lends its connections one thread each.
// No geometry, no HTTP: the registry (server/geometry_registry.hpp) builds on this.
#pragma once
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

struct redisContext;

namespace footpoint::redis {

using Clock = std::chrono::steady_clock;

// Where the registry is and how to log in: redis://[user@]host[:port][/db]. The password is not
// part of the URL (it would show in `ps` and in logs): it comes from a variable or a file.
struct Endpoint {
  std::string host;
  int port = 6379;
  int db = 0;
  std::string user;      // ACL user (AUTH user password); empty: the default user
  std::string password;  // empty: no AUTH
};

// Parses redis://[user@]host[:port][/db] (host may be [IPv6]). Throws std::invalid_argument, which
// never repeats a password: a URL with one (user:password@) is refused as such.
Endpoint parse_url(std::string_view url);

struct Error : std::runtime_error {
  enum class Kind {
    connect,  // no connection (refused, unreachable, name not resolved)
    timeout,  // the deadline passed (connecting, sending, or waiting for a reply)
    auth,     // AUTH or SELECT refused, or a command refused for want of it (NOAUTH)
    io,       // the connection broke (reset, closed by the server, protocol error)
    reply,    // the server answered a command with an error (e.g. a script or type error)
  };
  static constexpr int kKinds = 5;
  Error(Kind kind, const std::string& message) : std::runtime_error(message), kind(kind) {}
  Kind kind;
};
const char* to_string(Error::Kind kind);

// An owned copy of a RESP2 reply.
struct Reply {
  enum class Type { string, array, integer, nil, status, error };
  Type type = Type::nil;
  long long integer = 0;
  std::string str;  // string, status and error replies
  std::vector<Reply> elements;

  bool is_string() const { return type == Type::string; }
};

class Connection {
 public:
  Connection() = default;
  ~Connection();
  Connection(Connection&& other) noexcept;
  Connection& operator=(Connection&& other) noexcept;
  Connection(const Connection&) = delete;
  Connection& operator=(const Connection&) = delete;

  // Connects to address:port (a numeric address: the caller resolves names beforehand, so that no
  // request ever waits for DNS), then AUTH and SELECT as the endpoint says. Throws Error and
  // leaves the connection closed.
  void open(const std::string& address, const Endpoint& endpoint, Clock::time_point deadline);
  bool is_open() const { return context_ != nullptr; }
  void close();
  int fd() const;

  // Queues a command (binary-safe arguments); nothing is sent before send() or exchange().
  void append(const std::vector<std::string_view>& args);
  // Sends what is queued. Throws Error.
  void send(Clock::time_point deadline);
  // The next reply: nullopt when none arrived by `deadline` (the connection stays usable). Throws
  // Error when the connection broke.
  std::optional<Reply> read(Clock::time_point deadline);
  // Reads what the socket holds now (call it when poll() says it is readable) and returns the
  // complete replies. Throws Error when the connection was closed or broke.
  std::vector<Reply> read_available();
  // Sends the queued commands and returns their replies, in order. An error reply is returned as
  // such, except NOAUTH/WRONGPASS/NOPERM, which throw Error(auth). Throws Error(timeout) when a
  // reply is missing at the deadline (the connection is closed then).
  std::vector<Reply> exchange(Clock::time_point deadline);
  // One command, one reply (exchange of one).
  Reply command(const std::vector<std::string_view>& args, Clock::time_point deadline);

 private:
  [[noreturn]] void fail(Error::Kind kind, const std::string& what);
  std::optional<Reply> take_reply();  // a complete reply already read, if any
  void receive();                     // one read from the socket into hiredis's buffer
  void set_socket_timeout(Clock::time_point deadline);

  redisContext* context_ = nullptr;
  std::size_t queued_ = 0;  // commands appended and not yet answered
};

// A fixed number of connections, each lent to one thread at a time, opened on first use and again
// after a failure. The address is set by the owner (who resolves the endpoint's host name).
class Pool {
 public:
  Pool(Endpoint endpoint, std::size_t size);

  void set_address(const std::string& address);
  std::string address() const;
  const Endpoint& endpoint() const { return endpoint_; }

  // Runs f(connection, deadline) on a free connection, opened when needed, everything before
  // `deadline` (waiting for a free connection included: Error(timeout) when none is free in
  // time). A connection that f leaves by an exception is closed. When a connection kept from
  // before turns out broken (the server restarted or closed it while idle), f runs once more on
  // a new one: the registry's commands can all be repeated.
  template <class F>
  auto run(Clock::time_point deadline, F&& f) {
    Lease lease(*this, deadline);
    Connection& c = lease.connection();
    const bool reused = c.is_open();
    try {
      if (!reused) c.open(address(), endpoint_, deadline);
      return f(c, deadline);
    } catch (const Error& e) {
      c.close();
      if (!reused || e.kind != Error::Kind::io) throw;
    } catch (...) {
      c.close();
      throw;
    }
    try {
      c.open(address(), endpoint_, deadline);
      return f(c, deadline);
    } catch (...) {
      c.close();
      throw;
    }
  }

  // Closes every idle connection (after the server restarted or the address changed).
  void close_idle();

 private:
  class Lease {
   public:
    Lease(Pool& pool, Clock::time_point deadline);
    ~Lease();
    Lease(const Lease&) = delete;
    Lease& operator=(const Lease&) = delete;
    Connection& connection() { return pool_.connections_[index_]; }

   private:
    Pool& pool_;
    std::size_t index_;
  };

  const Endpoint endpoint_;
  mutable std::mutex mutex_;
  std::condition_variable freed_;
  std::vector<Connection> connections_;
  std::vector<std::size_t> free_;  // indices of connections not lent
  std::string address_;
};

}  // namespace footpoint::redis
