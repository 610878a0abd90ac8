// The shared geometry registry: level 2 under the in-process cache (level 1, core/cache), in
// Redis, so that an id posted to one replica is answered by every replica until it is deleted.
//
// - Redis holds a record under footpoint:v1:geometry:<id>, never compiled state: the line
//   "posted_by=NAME\n" (the API key that posted it first; no line without keys) and then the
//   canonical definition text (GeometryDefinition::canonical()), whose hash is the id. A record
//   without the line (written before posted_by was kept) is read as posted by nobody. A POST
//   writes it when it is not there (SET ... NX EX ttl); a rewrite of the same id keeps the record
//   and its first poster, refreshes the TTL, and replaces a damaged record.
// - A level-1 hit never waits for Redis: it only notes the id, and the monitor thread refreshes
//   the TTL (or the LRU clock) of the ids used in batches, off the request path, so that a
//   geometry in use on any replica does not expire or get evicted in Redis.
// - A level-1 miss reads the entry (GETEX refreshes the TTL), recomputes the id from the bytes and
//   refuses an entry whose hash differs or that is not canonical (logged, counted, never
//   compiled), then compiles it through the cache, which applies the posted definitions' limits
//   and compiles once per id. Concurrent misses on one id share one read.
// - DELETE removes the entry and publishes the id on footpoint:v1:db<N>:deleted in one
//   transaction; every replica's monitor drops the id from its cache on the message. After a
//   reconnection (messages may have been missed) the monitor revalidates level 1: ids Redis no
//   longer holds are dropped, ids posted here while Redis was unreachable are stored then.
// - Every Redis operation of a request ends before the configured timeout. A failure marks the
//   registry down: until the monitor reconnects, requests do not wait for Redis at all (a miss
//   is RegistryUnavailable, a POST is answered unstored).
#pragma once
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <future>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <thread>
#include <unordered_map>
#include <unordered_set>

#include "cache/geometry_cache.hpp"
#include "redis/redis_client.hpp"
#include "registry_metrics.hpp"

namespace footpoint::server {

struct RegistryOptions {
  redis::Endpoint endpoint;
  // Bound on every Redis operation of a request (connecting, waiting for a pool connection,
  // the command): a request never waits longer for the registry.
  std::chrono::milliseconds timeout{250};
  std::size_t pool_size = 4;
  // Lifetime of an unused entry; 0: none (then bound Redis with maxmemory and allkeys-lru).
  std::chrono::seconds ttl{604800};
  // An entry longer than this is refused unread (the request body limit bounds a posted one).
  std::size_t max_entry_bytes = std::size_t{16} << 20;
};

// The registry could not be asked (down, unreachable, slow, refusing AUTH): the API answers 503
// registry_unavailable with Retry-After.
struct RegistryUnavailable : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class GeometryRegistry {
 public:
  // Starts the monitor and waits (at most about twice the timeout) for its first connection, so
  // that a server starts with the registry up when Redis is there. Redis being away is no error:
  // the monitor keeps trying.
  GeometryRegistry(RegistryOptions options, GeometryCache& cache);
  ~GeometryRegistry();
  GeometryRegistry(const GeometryRegistry&) = delete;
  GeometryRegistry& operator=(const GeometryRegistry&) = delete;

  // A level-1 hit on `id` (cheap: the TTL is refreshed later by the monitor).
  void note_use(const std::string& id);

  // Level 2: the geometry Redis holds under `id`, compiled into the cache (geometry nullptr when
  // Redis holds no valid entry). Throws RegistryUnavailable, or GeometryError when the stored
  // definition does not compile under `limits`.
  GeometryCache::Lookup load(const std::string& id, const formula::CompileLimits& limits);

  // Stores a posted geometry, posted by the key `posted_by` ("" without keys). false: not stored
  // now (the registry is unavailable); it is stored when the registry is back, unless it was
  // deleted or evicted from level 1 meanwhile.
  bool store(const CompiledGeometry& geometry, std::string_view posted_by = {});

  // Deletes `id` from Redis and, through the published message, from every replica's level 1.
  // Throws RegistryUnavailable (nothing is deleted then).
  struct Erased {
    bool held = false;      // whether Redis held it
    std::string posted_by;  // its record's poster ("" when none is recorded)
  };
  Erased erase(const std::string& id);

  // A record's text, and the record read back (nullopt: its posted_by line is malformed).
  struct Record {
    std::string posted_by;  // "" when the record names none
    std::string_view canonical;
  };
  static std::string record_text(std::string_view canonical, std::string_view posted_by);
  static std::optional<Record> parse_record(std::string_view text);

  bool up() const { return metrics_.up.load(); }
  const RegistryMetrics& metrics() const { return metrics_; }
  std::string channel() const;
  static std::string key(std::string_view id);

 private:
  struct Loading {
    std::promise<std::shared_ptr<const CompiledGeometry>> promise;
    std::shared_future<std::shared_ptr<const CompiledGeometry>> result = promise.get_future().share();
    bool deleted = false;  // a deletion of the id arrived while it was being loaded
  };

  // Runs f on a pool connection within the timeout, timing it as `command`; a connection-level
  // failure marks the registry down. Throws RegistryUnavailable (at once while down, unless
  // `probe`).
  template <class F>
  auto run(RegistryMetrics::Command command, F&& f, bool probe = false);
  void mark_down(const std::string& why);
  // Writes `record` for `id` at key k unless a valid record of the id is there (whose TTL is then
  // refreshed and whose poster is kept).
  void write_record(redis::Connection& c, std::chrono::steady_clock::time_point deadline,
                    const std::string& k, const std::string& id, const std::string& record) const;
  GeometryCache::Lookup fetch_and_compile(const std::string& id, const formula::CompileLimits& limits);
  void on_deleted(const std::string& id);

  void monitor();
  void subscribe(redis::Connection& subscriber);
  void recover();
  void touch_used();
  void sleep_for(std::chrono::milliseconds d);

  const RegistryOptions options_;
  GeometryCache& cache_;
  redis::Pool pool_;
  RegistryMetrics metrics_;
  const std::string ttl_text_;

  std::mutex loading_mutex_;
  std::unordered_map<std::string, std::shared_ptr<Loading>> loading_;
  std::mutex used_mutex_;
  std::unordered_set<std::string> used_;  // ids hit in level 1 since the last TTL refresh
  std::mutex unstored_mutex_;
  std::map<std::string, std::string> unstored_;  // id -> record text, posted while down

  std::mutex state_mutex_;
  std::condition_variable state_changed_;
  bool stopping_ = false;
  bool first_attempt_done_ = false;
  std::string last_failure_;
  int wake_pipe_[2] = {-1, -1};
  std::thread monitor_;
};

}  // namespace footpoint::server
