// The TCP connections of a listening port, as the kernel lists them: httplib 0.11.4 keeps no list
// of its connections and hands a request's handler no socket, so the sockets are found among the
// process's file descriptors (/proc/self/fd) by their local port and peer address.
#pragma once
#include <sys/socket.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <functional>
#include <map>
#include <mutex>
#include <string>
#include <thread>
#include <utility>

namespace footpoint::server {

// The port of a socket address (IPv4 or IPv6), or -1.
int port_of(const sockaddr_storage& address);
// The numeric host of a socket address as httplib writes Request::remote_addr (getnameinfo with
// NI_NUMERICHOST), or "".
std::string host_of(const sockaddr_storage& address);

// Calls f(fd, peer) for every connected stream socket of this process whose local port is
// `local_port`. The descriptors are only valid while their connections are open: f must not keep them.
void for_each_connection(int local_port, const std::function<void(int fd, const sockaddr_storage& peer)>& f);

// Whether the client of one request has closed its connection, asked while its handler runs (the
// connection thread holds the socket open until then, so the descriptor stays this connection's).
// The socket is looked up on the first call only (a scan of the descriptors); each call is then one
// poll(2) without waiting: the peer's FIN (POLLRDHUP), a reset or an error (POLLHUP, POLLERR) mean
// it is gone. A request and its body already read, a client that only shut down its sending side is
// taken for gone as well (HTTP/1.1 clients close both sides). Thread-safe.
class ConnectionWatch {
 public:
  ConnectionWatch(int local_port, std::string remote_addr, int remote_port)
      : local_port_(local_port), remote_addr_(std::move(remote_addr)), remote_port_(remote_port) {}
  bool closed();

 private:
  const int local_port_;
  const std::string remote_addr_;
  const int remote_port_;
  std::once_flag found_;
  int fd_ = -1;  // -1: not found (never taken for closed)
};

// Slow-loris protection: a request must arrive whole - request line, headers and body - within
// `timeout` of its first byte, or its connection is closed (httplib's read timeout bounds each
// read only, so a client sending a byte a second would hold a connection thread for ever).
// The connection threads report each request's progress (admitted: headers read; handling: body
// read; answered); a watchdog thread scans the port's connections every `interval` and, for each
// connection not in a handler, decides since when a request has been arriving:
//   - a connection with no request answered yet: since it was first seen (a new connection must
//     deliver its first request in time; httplib itself closes a silent one after the keep-alive
//     timeout);
//   - headers read, body not yet: since the headers were read, or since its bytes were first
//     seen arriving, the earlier;
//   - between requests: since the scan that first saw bytes received after the last answer (the
//     kernel's tcpi_last_data_recv, TCP_INFO, in whole clock ticks: bytes within 20 ms of the
//     answer are taken for its request's): idle time on a keep-alive connection does not count.
// A late connection is shut down (both directions): its thread's read fails and it closes. The
// bounds hold to within one interval.
class ReadDeadline {
 public:
  using Clock = std::chrono::steady_clock;
  // on_close(host, port): called on the watchdog thread for each connection closed.
  ReadDeadline(std::chrono::milliseconds timeout, std::chrono::milliseconds interval,
               std::function<void(const std::string& host, int port)> on_close);
  ~ReadDeadline();
  ReadDeadline(const ReadDeadline&) = delete;
  ReadDeadline& operator=(const ReadDeadline&) = delete;

  // From the connection threads.
  void admitted(const std::string& host, int port);
  void handling(const std::string& host, int port);
  void answered(const std::string& host, int port);

  // Starts the watchdog on the connections of `local_port`; stop() ends it (also the destructor).
  void start(int local_port);
  void stop();
  // One scan at `now` (the watchdog's step): the number of connections closed.
  std::size_t scan(int local_port, Clock::time_point now);

 private:
  enum class Phase { none, body, handling, answered };
  struct Progress {
    Phase phase = Phase::none;
    Clock::time_point since;
    bool answered_before = false;  // a request was answered earlier on this connection
  };
  struct Seen {
    Clock::time_point first;     // the connection's first sighting
    Clock::time_point arriving;  // a request seen arriving since (the epoch: none)
    std::size_t scan = 0;        // the last scan that saw it
  };
  using Key = std::pair<std::string, int>;  // the peer's host and port
  void set(const std::string& host, int port, Phase phase);

  const std::chrono::milliseconds timeout_, interval_;
  const std::function<void(const std::string&, int)> on_close_;
  std::mutex mutex_;  // progress_
  std::map<Key, Progress> progress_;
  std::map<Key, Seen> seen_;  // the watchdog's own
  std::size_t scans_ = 0;
  std::mutex stop_mutex_;
  std::condition_variable stop_cv_;
  bool stopping_ = false;
  std::thread thread_;
};

}  // namespace footpoint::server
