#include "connections.hpp"

#include <dirent.h>
#include <netdb.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>

#include <cstdlib>

namespace footpoint::server {

namespace {
constexpr std::chrono::milliseconds kJiffySlack{20};
}  // namespace

int port_of(const sockaddr_storage& a) {
  if (a.ss_family == AF_INET) return ntohs(reinterpret_cast<const sockaddr_in&>(a).sin_port);
  if (a.ss_family == AF_INET6) return ntohs(reinterpret_cast<const sockaddr_in6&>(a).sin6_port);
  return -1;
}

std::string host_of(const sockaddr_storage& a) {
  char host[NI_MAXHOST];
  const socklen_t length = a.ss_family == AF_INET6 ? sizeof(sockaddr_in6) : sizeof(sockaddr_in);
  if (::getnameinfo(reinterpret_cast<const sockaddr*>(&a), length, host, sizeof host, nullptr, 0,
                    NI_NUMERICHOST) != 0)
    return {};
  return host;
}

void for_each_connection(int local_port, const std::function<void(int fd, const sockaddr_storage& peer)>& f) {
  DIR* dir = opendir("/proc/self/fd");
  if (!dir) return;
  while (const dirent* entry = readdir(dir)) {
    if (entry->d_name[0] == '.') continue;
    const int fd = std::atoi(entry->d_name);
    int type = 0;
    socklen_t type_length = sizeof type;
    sockaddr_storage local{}, peer{};
    socklen_t local_length = sizeof local, peer_length = sizeof peer;
    if (::getsockopt(fd, SOL_SOCKET, SO_TYPE, &type, &type_length) != 0 || type != SOCK_STREAM) continue;
    if (::getsockname(fd, reinterpret_cast<sockaddr*>(&local), &local_length) != 0 ||
        port_of(local) != local_port)
      continue;
    if (::getpeername(fd, reinterpret_cast<sockaddr*>(&peer), &peer_length) != 0) continue;
    f(fd, peer);
  }
  closedir(dir);
}

bool ConnectionWatch::closed() {
  std::call_once(found_, [this] {
    for_each_connection(local_port_, [this](int fd, const sockaddr_storage& peer) {
      if (port_of(peer) == remote_port_ && host_of(peer) == remote_addr_) fd_ = fd;
    });
  });
  if (fd_ < 0) return false;
  pollfd p{fd_, POLLIN | POLLRDHUP, 0};
  return ::poll(&p, 1, 0) > 0 && (p.revents & (POLLRDHUP | POLLHUP | POLLERR)) != 0;
}

ReadDeadline::ReadDeadline(std::chrono::milliseconds timeout, std::chrono::milliseconds interval,
                           std::function<void(const std::string& host, int port)> on_close)
    : timeout_(timeout), interval_(interval), on_close_(std::move(on_close)) {}

ReadDeadline::~ReadDeadline() { stop(); }

void ReadDeadline::set(const std::string& host, int port, Phase phase) {
  std::lock_guard lock(mutex_);
  Progress& p = progress_[Key(host, port)];
  p.answered_before = p.answered_before || p.phase == Phase::answered;
  p.phase = phase;
  p.since = Clock::now();
}

void ReadDeadline::admitted(const std::string& host, int port) { set(host, port, Phase::body); }
void ReadDeadline::handling(const std::string& host, int port) { set(host, port, Phase::handling); }
void ReadDeadline::answered(const std::string& host, int port) { set(host, port, Phase::answered); }

void ReadDeadline::start(int local_port) {
  thread_ = std::thread([this, local_port] {
    std::unique_lock lock(stop_mutex_);
    while (!stop_cv_.wait_for(lock, interval_, [this] { return stopping_; })) {
      lock.unlock();
      scan(local_port, Clock::now());
      lock.lock();
    }
  });
}

void ReadDeadline::stop() {
  {
    std::lock_guard lock(stop_mutex_);
    stopping_ = true;
  }
  stop_cv_.notify_all();
  if (thread_.joinable()) thread_.join();
}

std::size_t ReadDeadline::scan(int local_port, Clock::time_point now) {
  const std::size_t this_scan = ++scans_;
  std::size_t closed = 0;
  for_each_connection(local_port, [&](int fd, const sockaddr_storage& peer) {
    const Key key(host_of(peer), port_of(peer));
    auto [it, inserted] = seen_.try_emplace(key);
    Seen& seen = it->second;
    if (inserted) seen.first = now;
    seen.scan = this_scan;
    Progress progress;
    {
      std::lock_guard lock(mutex_);
      const auto p = progress_.find(key);
      if (p == progress_.end()) {
        progress.phase = Phase::none;
      } else {
        progress = p->second;
      }
    }
    Clock::time_point since;
    switch (progress.phase) {
      case Phase::none:  // no request admitted yet
        since = seen.first;
        break;
      case Phase::handling:
        seen.arriving = {};
        return;
      case Phase::answered: {
        tcp_info info{};
        socklen_t length = sizeof info;
        if (::getsockopt(fd, IPPROTO_TCP, TCP_INFO, &info, &length) != 0) return;
        // tcpi_last_data_recv counts whole jiffies (up to 10 ms): data within kJiffySlack after the
        // answer is taken for the answered request's.
        if (now - std::chrono::milliseconds(info.tcpi_last_data_recv) <= progress.since + kJiffySlack) {
          seen.arriving = {};  // idle since its last answer
          return;
        }
        if (seen.arriving <= progress.since) seen.arriving = now;
        since = seen.arriving;
        break;
      }
      case Phase::body:
        since = !progress.answered_before ? std::min(seen.first, progress.since)
                : seen.arriving != Clock::time_point{} && seen.arriving < progress.since ? seen.arriving
                                                                                         : progress.since;
        break;
    }
    if (now - since <= timeout_) return;
    ::shutdown(fd, SHUT_RDWR);
    ++closed;
    if (on_close_) on_close_(key.first, key.second);
  });
  // Forget the connections gone.
  std::erase_if(seen_, [&](const auto& entry) { return entry.second.scan != this_scan; });
  std::lock_guard lock(mutex_);
  std::erase_if(progress_, [&](const auto& entry) { return seen_.count(entry.first) == 0; });
  return closed;
}

}  // namespace footpoint::server
