#include "geometry_registry.hpp"

#include <fcntl.h>
#include <netdb.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <vector>

#include "access.hpp"
#include "compiled/sha256.hpp"
#include "request_log.hpp"

namespace footpoint::server {

namespace {

using Clock = std::chrono::steady_clock;
using std::chrono::milliseconds;

// Between two connection attempts while the registry is down (recovery takes at most this long
// once Redis is back), and between two heartbeats of the subscriber connection.
constexpr milliseconds kRetryInterval{250};
constexpr milliseconds kHeartbeatInterval{1000};
// Commands per pipelined round trip of the monitor (revalidation, TTL refreshes).
constexpr std::size_t kBatch = 256;
// Ids remembered for the monitor (used since the last refresh; posted while down).
constexpr std::size_t kMaxRemembered = 65536;

bool is_geometry_id(std::string_view id) {
  if (id.size() != 32) return false;
  return std::all_of(id.begin(), id.end(),
                     [](char c) { return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'); });
}

// The first address of `host`, numeric. Throws redis::Error(connect).
std::string resolve(const std::string& host) {
  addrinfo hints{};
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = SOCK_STREAM;
  addrinfo* found = nullptr;
  if (const int rc = ::getaddrinfo(host.c_str(), nullptr, &hints, &found); rc != 0)
    throw redis::Error(redis::Error::Kind::connect,
                       "registry: cannot resolve " + host + ": " + gai_strerror(rc));
  char text[NI_MAXHOST] = {};
  const int rc =
      ::getnameinfo(found->ai_addr, found->ai_addrlen, text, sizeof text, nullptr, 0, NI_NUMERICHOST);
  ::freeaddrinfo(found);
  if (rc != 0) throw redis::Error(redis::Error::Kind::connect, "registry: cannot resolve " + host);
  return text;
}

// How often the TTLs of the ids used are refreshed: well inside the TTL.
milliseconds refresh_interval(std::chrono::seconds ttl) {
  if (ttl.count() == 0) return milliseconds(300000);
  return std::clamp<milliseconds>(std::chrono::duration_cast<milliseconds>(ttl) / 4, milliseconds(250),
                                  milliseconds(300000));
}

}  // namespace

std::string GeometryRegistry::key(std::string_view id) { return "footpoint:v1:geometry:" + std::string(id); }

namespace {
constexpr std::string_view kPostedBy = "posted_by=";
}

std::string GeometryRegistry::record_text(std::string_view canonical, std::string_view posted_by) {
  if (posted_by.empty()) return std::string(canonical);
  return std::string(kPostedBy) + std::string(posted_by) + "\n" + std::string(canonical);
}

std::optional<GeometryRegistry::Record> GeometryRegistry::parse_record(std::string_view text) {
  if (text.substr(0, kPostedBy.size()) != kPostedBy) return Record{{}, text};
  const auto end = text.find('\n');
  if (end == std::string_view::npos) return std::nullopt;
  const std::string_view name = text.substr(kPostedBy.size(), end - kPostedBy.size());
  if (!valid_key_name(name)) return std::nullopt;
  return Record{std::string(name), text.substr(end + 1)};
}

// Pub/sub channels are global to a Redis server, not per database: the database number keeps two
// deployments on one server (e.g. /0 and /1) apart.
std::string GeometryRegistry::channel() const {
  return "footpoint:v1:db" + std::to_string(options_.endpoint.db) + ":deleted";
}

GeometryRegistry::GeometryRegistry(RegistryOptions options, GeometryCache& cache)
    : options_(std::move(options)),
      cache_(cache),
      pool_(options_.endpoint, options_.pool_size),
      ttl_text_(std::to_string(options_.ttl.count())) {
  if (::pipe2(wake_pipe_, O_CLOEXEC | O_NONBLOCK) != 0)
    throw std::runtime_error("registry: cannot create a pipe");
  monitor_ = std::thread([this] { monitor(); });
  std::unique_lock lock(state_mutex_);
  state_changed_.wait_for(lock, 2 * options_.timeout + milliseconds(100),
                          [&] { return first_attempt_done_; });
}

GeometryRegistry::~GeometryRegistry() {
  {
    std::lock_guard lock(state_mutex_);
    stopping_ = true;
  }
  const char byte = 1;
  [[maybe_unused]] const auto n = ::write(wake_pipe_[1], &byte, 1);
  state_changed_.notify_all();
  if (monitor_.joinable()) monitor_.join();
  ::close(wake_pipe_[0]);
  ::close(wake_pipe_[1]);
}

void GeometryRegistry::mark_down(const std::string& why) {
  const bool was_up = metrics_.up.exchange(false);
  std::lock_guard lock(state_mutex_);
  if (was_up || why != last_failure_)
    log_event(spdlog::level::warn, "registry unavailable",
              {{"error", why}, {"host", options_.endpoint.host}});
  last_failure_ = why;
}

template <class F>
auto GeometryRegistry::run(RegistryMetrics::Command command, F&& f, bool probe) {
  if (!probe && !metrics_.up.load()) throw RegistryUnavailable("the registry is unavailable (reconnecting)");
  const auto start = Clock::now();
  try {
    auto result = pool_.run(start + options_.timeout, std::forward<F>(f));
    metrics_.observe(command, std::chrono::duration<double>(Clock::now() - start).count());
    return result;
  } catch (const redis::Error& e) {
    metrics_.observe(command, std::chrono::duration<double>(Clock::now() - start).count());
    metrics_.count_error(e.kind);
    // An error reply is about the command, not about the connection.
    if (e.kind != redis::Error::Kind::reply) mark_down(e.what());
    throw RegistryUnavailable(e.what());
  }
}

void GeometryRegistry::note_use(const std::string& id) {
  std::lock_guard lock(used_mutex_);
  if (used_.size() < kMaxRemembered) used_.insert(id);
}

GeometryCache::Lookup GeometryRegistry::load(const std::string& id, const formula::CompileLimits& limits) {
  if (!is_geometry_id(id)) return {};  // nothing else can have been stored
  std::shared_ptr<Loading> loading;
  std::shared_future<std::shared_ptr<const CompiledGeometry>> other;
  {
    std::lock_guard lock(loading_mutex_);
    auto [it, inserted] = loading_.try_emplace(id);
    if (inserted)
      it->second = loading = std::make_shared<Loading>();
    else
      other = it->second->result;
  }
  if (!loading) return {other.get(), false, {}};  // another request is loading it; get() rethrows its error
  GeometryCache::Lookup lookup;
  std::exception_ptr error;
  try {
    lookup = fetch_and_compile(id, limits);
  } catch (...) {
    error = std::current_exception();
  }
  bool deleted = false;
  {
    std::lock_guard lock(loading_mutex_);
    loading_.erase(id);
    deleted = loading->deleted;
  }
  // A deletion that arrived while this was loading: this request keeps its answer, the cache
  // does not keep the geometry.
  if (deleted && lookup.geometry) cache_.erase(id);
  if (error) {
    loading->promise.set_exception(error);
    std::rethrow_exception(error);
  }
  loading->promise.set_value(lookup.geometry);
  return lookup;
}

GeometryCache::Lookup GeometryRegistry::fetch_and_compile(const std::string& id,
                                                          const formula::CompileLimits& limits) {
  const std::string k = key(id);
  std::optional<std::string> text =
      run(RegistryMetrics::Command::get, [&](redis::Connection& c, Clock::time_point deadline) {
        // GETEX refreshes the TTL of what is read; without a TTL a read refreshes the LRU clock.
        const redis::Reply r = options_.ttl.count() > 0 ? c.command({"GETEX", k, "EX", ttl_text_}, deadline)
                                                        : c.command({"GET", k}, deadline);
        if (r.type == redis::Reply::Type::nil) return std::optional<std::string>();
        if (r.is_string()) return std::optional<std::string>(r.str);
        // WRONGTYPE and the like: something else sits at the key.
        throw redis::Error(redis::Error::Kind::reply, "registry: " + k + ": " + r.str);
      });
  if (!text) {
    metrics_.misses.fetch_add(1, std::memory_order_relaxed);
    return {};
  }
  auto refuse = [&](const std::string& why) {
    metrics_.rejected.fetch_add(1, std::memory_order_relaxed);
    log_event(spdlog::level::err, "registry entry refused",
              {{"id", id}, {"key", k}, {"reason", why}, {"bytes", text->size()}});
    return GeometryCache::Lookup{};
  };
  if (text->size() > options_.max_entry_bytes) return refuse("longer than the request body limit");
  const std::optional<Record> record = parse_record(*text);
  if (!record) return refuse("its posted_by line is not a key name");
  if (sha256_hex(record->canonical).substr(0, 32) != id) return refuse("its content hash is not its id");
  GeometryDefinition definition;
  try {
    definition = parse_canonical(record->canonical);
  } catch (const GeometryError& e) {
    return refuse(e.what());
  }
  metrics_.hits.fetch_add(1, std::memory_order_relaxed);
  // Kept under its poster's share when it fits there; a lookup is answered either way.
  return cache_.get_or_compile(definition, limits, record->posted_by, false);
}

void GeometryRegistry::write_record(redis::Connection& c, Clock::time_point deadline, const std::string& k,
                                    const std::string& id, const std::string& record) const {
  const bool ttl = options_.ttl.count() > 0;
  redis::Reply r = ttl ? c.command({"SET", k, record, "NX", "EX", ttl_text_}, deadline)
                       : c.command({"SET", k, record, "NX"}, deadline);
  if (r.type == redis::Reply::Type::error)
    throw redis::Error(redis::Error::Kind::reply, "registry: SET: " + r.str);
  if (r.type != redis::Reply::Type::nil) return;  // written
  // Held already: kept (its first poster with it) when it is this id's record, else replaced.
  r = ttl ? c.command({"GETEX", k, "EX", ttl_text_}, deadline) : c.command({"GET", k}, deadline);
  if (r.is_string()) {
    const auto held = parse_record(r.str);
    if (held && sha256_hex(held->canonical).substr(0, 32) == id) return;
  }
  r = ttl ? c.command({"SET", k, record, "EX", ttl_text_}, deadline)
          : c.command({"SET", k, record}, deadline);
  if (r.type == redis::Reply::Type::error)
    throw redis::Error(redis::Error::Kind::reply, "registry: SET: " + r.str);
}

bool GeometryRegistry::store(const CompiledGeometry& geometry, std::string_view posted_by) {
  const std::string text = record_text(geometry.definition().canonical(), posted_by);
  const std::string k = key(geometry.id());
  try {
    run(RegistryMetrics::Command::set, [&](redis::Connection& c, Clock::time_point deadline) {
      write_record(c, deadline, k, geometry.id(), text);
      return true;
    });
  } catch (const RegistryUnavailable&) {
    metrics_.not_stored.fetch_add(1, std::memory_order_relaxed);
    std::lock_guard lock(unstored_mutex_);
    if (unstored_.size() < kMaxRemembered) unstored_.emplace(geometry.id(), text);
    return false;
  }
  metrics_.stored.fetch_add(1, std::memory_order_relaxed);
  std::lock_guard lock(unstored_mutex_);
  unstored_.erase(geometry.id());
  return true;
}

GeometryRegistry::Erased GeometryRegistry::erase(const std::string& id) {
  if (!is_geometry_id(id)) return {};
  const std::string k = key(id), ch = channel();
  Erased erased = run(RegistryMetrics::Command::del, [&](redis::Connection& c, Clock::time_point deadline) {
    // One transaction: the entry goes and every replica hears of it, or neither happens; the
    // record read in it names its poster for the audit line.
    c.append({"MULTI"});
    c.append({"GET", k});
    c.append({"DEL", k});
    c.append({"PUBLISH", ch, id});
    c.append({"EXEC"});
    const auto replies = c.exchange(deadline);
    const redis::Reply& exec = replies.back();
    if (exec.type != redis::Reply::Type::array || exec.elements.size() != 3)
      throw redis::Error(redis::Error::Kind::reply, "registry: DELETE transaction failed: " + exec.str);
    Erased e;
    e.held = exec.elements[1].integer > 0;
    if (exec.elements[0].is_string())
      if (const auto record = parse_record(exec.elements[0].str)) e.posted_by = record->posted_by;
    return e;
  });
  std::lock_guard lock(unstored_mutex_);
  if (auto it = unstored_.find(id); it != unstored_.end()) {
    if (const auto record = parse_record(it->second); record && erased.posted_by.empty())
      erased.posted_by = record->posted_by;
    unstored_.erase(it);
    erased.held = true;
  }
  return erased;
}

void GeometryRegistry::on_deleted(const std::string& id) {
  {
    std::lock_guard lock(loading_mutex_);
    if (auto it = loading_.find(id); it != loading_.end()) it->second->deleted = true;
  }
  {
    std::lock_guard lock(unstored_mutex_);
    unstored_.erase(id);
  }
  if (cache_.erase(id)) metrics_.invalidated_by_message.fetch_add(1, std::memory_order_relaxed);
}

// ---- the monitor thread ---------------------------------------------------------------------

void GeometryRegistry::sleep_for(milliseconds d) {
  pollfd p{wake_pipe_[0], POLLIN, 0};
  ::poll(&p, 1, static_cast<int>(d.count()));
}

void GeometryRegistry::subscribe(redis::Connection& subscriber) {
  const std::string address = resolve(options_.endpoint.host);
  if (address != pool_.address()) {
    pool_.set_address(address);
    pool_.close_idle();
  }
  const auto deadline = Clock::now() + options_.timeout;
  subscriber.open(address, options_.endpoint, deadline);
  subscriber.append({"SUBSCRIBE", channel()});
  subscriber.send(deadline);
  const auto confirmation = subscriber.read(deadline);
  if (!confirmation)
    throw redis::Error(redis::Error::Kind::timeout, "registry: SUBSCRIBE was not confirmed in time");
  if (confirmation->type != redis::Reply::Type::array || confirmation->elements.empty() ||
      confirmation->elements[0].str != "subscribe")
    throw redis::Error(redis::Error::Kind::auth, "registry refused SUBSCRIBE: " + confirmation->str);
}

// From a live subscription on, every deletion reaches on_deleted; what was deleted before is
// found here: each id of level 1 that Redis no longer holds is dropped, unless it was posted
// while the registry was unavailable, in which case it is stored now.
void GeometryRegistry::recover() {
  run(
      RegistryMetrics::Command::ping,
      [&](redis::Connection& c, Clock::time_point deadline) { return c.command({"PING"}, deadline); }, true);
  // Up before revalidating: a post from now on is stored by its own request.
  if (!metrics_.up.exchange(true))
    log_event(
        spdlog::level::info, "registry connected",
        {{"host", options_.endpoint.host}, {"address", pool_.address()}, {"port", options_.endpoint.port}});
  const std::vector<std::string> ids = cache_.ids();
  for (std::size_t begin = 0; begin < ids.size(); begin += kBatch) {
    const std::size_t end = std::min(ids.size(), begin + kBatch);
    const auto replies =
        run(RegistryMetrics::Command::exists, [&](redis::Connection& c, Clock::time_point deadline) {
          for (std::size_t i = begin; i < end; ++i) c.append({"EXISTS", key(ids[i])});
          return c.exchange(deadline);
        });
    for (std::size_t i = begin; i < end; ++i) {
      std::string text;  // the record's text when the id was posted here while down
      {
        std::lock_guard lock(unstored_mutex_);
        if (auto it = unstored_.find(ids[i]); it != unstored_.end()) {
          text = std::move(it->second);
          unstored_.erase(it);
        }
      }
      if (replies[i - begin].integer != 0) continue;
      if (text.empty()) {
        if (cache_.erase(ids[i]))
          metrics_.invalidated_by_revalidation.fetch_add(1, std::memory_order_relaxed);
        continue;
      }
      const std::string k = key(ids[i]);
      run(RegistryMetrics::Command::set, [&](redis::Connection& c, Clock::time_point deadline) {
        write_record(c, deadline, k, ids[i], text);
        return true;
      });
      metrics_.stored.fetch_add(1, std::memory_order_relaxed);
    }
  }
  // What was posted while down and has left level 1 since (deleted or evicted here) is not
  // stored: the client was told it was not.
  std::lock_guard lock(unstored_mutex_);
  for (auto it = unstored_.begin(); it != unstored_.end();)
    it = cache_.entry_stats(it->first) ? std::next(it) : unstored_.erase(it);
}

void GeometryRegistry::touch_used() {
  std::vector<std::string> ids;
  {
    std::lock_guard lock(used_mutex_);
    ids.assign(used_.begin(), used_.end());
    used_.clear();
  }
  for (std::size_t begin = 0; begin < ids.size(); begin += kBatch) {
    const std::size_t end = std::min(ids.size(), begin + kBatch);
    run(RegistryMetrics::Command::touch, [&](redis::Connection& c, Clock::time_point deadline) {
      for (std::size_t i = begin; i < end; ++i) {
        const std::string k = key(ids[i]);
        if (options_.ttl.count() > 0)
          c.append({"EXPIRE", k, ttl_text_});
        else
          c.append({"TOUCH", k});
      }
      return c.exchange(deadline);
    });
  }
}

void GeometryRegistry::monitor() {
  redis::Connection subscriber;
  const milliseconds refresh = refresh_interval(options_.ttl);
  auto next_refresh = Clock::now() + refresh;
  auto next_heartbeat = Clock::now() + kHeartbeatInterval;
  bool awaiting_pong = false;  // a heartbeat PING sent at ping_sent is not answered yet
  Clock::time_point ping_sent{};
  auto stopping = [&] {
    std::lock_guard lock(state_mutex_);
    return stopping_;
  };
  auto attempt_done = [&] {
    {
      std::lock_guard lock(state_mutex_);
      first_attempt_done_ = true;
    }
    state_changed_.notify_all();
  };
  while (!stopping()) {
    try {
      if (!subscriber.is_open()) {
        subscribe(subscriber);
        awaiting_pong = false;
        next_heartbeat = Clock::now() + kHeartbeatInterval;
        recover();
        attempt_done();
      } else if (!metrics_.up.load()) {
        // The subscription held, but a request's command failed: try the pool again.
        recover();
      }
      const auto now = Clock::now();
      if (awaiting_pong && now - ping_sent > options_.timeout)
        throw redis::Error(redis::Error::Kind::timeout,
                           "registry: no answer to the heartbeat within the timeout");
      if (!awaiting_pong && now >= next_heartbeat) {
        subscriber.append({"PING"});
        subscriber.send(now + options_.timeout);
        ping_sent = now;
        awaiting_pong = true;
      }
      if (now >= next_refresh) {
        touch_used();
        next_refresh = now + refresh;
      }
      auto wake = std::min(next_refresh, awaiting_pong ? ping_sent + options_.timeout : next_heartbeat);
      if (!metrics_.up.load()) wake = std::min(wake, now + kRetryInterval);
      const auto wait = std::max<std::int64_t>(
          0, std::chrono::duration_cast<milliseconds>(wake - Clock::now()).count() + 1);
      pollfd fds[2] = {{subscriber.fd(), POLLIN, 0}, {wake_pipe_[0], POLLIN, 0}};
      if (::poll(fds, 2, static_cast<int>(wait)) > 0 && (fds[0].revents & (POLLIN | POLLHUP | POLLERR))) {
        for (const auto& r : subscriber.read_available()) {
          if (r.type != redis::Reply::Type::array || r.elements.empty()) continue;
          const std::string& kind = r.elements[0].str;
          if (kind == "message" && r.elements.size() == 3) {
            on_deleted(r.elements[2].str);
          } else if (kind == "pong") {
            awaiting_pong = false;
            next_heartbeat = Clock::now() + kHeartbeatInterval;
          }
        }
      }
    } catch (const std::exception& e) {
      subscriber.close();
      if (const auto* re = dynamic_cast<const redis::Error*>(&e)) metrics_.count_error(re->kind);
      mark_down(e.what());
      attempt_done();
      sleep_for(kRetryInterval);
    }
  }
}

}  // namespace footpoint::server
