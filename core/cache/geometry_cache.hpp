// A bounded LRU cache of compiled geometries, keyed by the definition's content-hash id.
// Bounded both by entry count and by the bytes the compiled objects hold
// (CompiledGeometry::memory_bytes), so a flood of distinct formulas evicts instead of growing.
// Thread-safe: lookups take one short lock; compilation runs outside the lock, and concurrent
// requests for the same new id wait for the one compilation in progress instead of repeating it.
// Entries are shared_ptr<const CompiledGeometry>: an evicted geometry stays alive for the
// requests still using it.
//
// Each entry has an owner (the API key's name that posted it, "" without keys). A full cache
// evicts the least recently used entry, except that an owner whose entries would hold more than
// `share` of the bounds evicts its own least recently used entries first: one owner's flood
// cannot push another owner's geometries out beyond its share, while an owner alone in the cache
// (nobody else's entries to protect) may still fill it. A new entry that could only be kept by
// evicting other owners' entries beyond its owner's share is refused (GeometryError
// cache_share_exceeded) and not kept.
#pragma once
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <list>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "compiled/compiled_geometry.hpp"

namespace footpoint {

struct GeometryCacheOptions {
  // At most this many geometries are kept; beyond it the least recently used is evicted.
  std::size_t max_entries = 1024;
  // At most this many bytes (sum of memory_bytes()) are kept: 256 MiB. A single geometry larger
  // than this is compiled and returned, but not kept.
  std::size_t max_bytes = std::size_t{256} << 20;
  // A compiled geometry whose memory_bytes() exceeds this is refused (GeometryError
  // geometry_too_large, naming the size reached) and not kept, so that one definition cannot take
  // the cache from every other; the compile itself stops as soon as the structure it has built
  // passes it (formula::CompileLimits::max_geometry_bytes). 0 = no bound beyond max_bytes.
  std::size_t max_geometry_bytes = 0;
  // The fraction of max_bytes (and of max_entries) one owner's entries may hold once the cache is
  // full and other owners hold entries (see above); 1: plain LRU across owners.
  double share = 1.0;
};

struct GeometryCacheStats {
  std::size_t size = 0;            // geometries held
  std::size_t bytes = 0;           // sum of their memory_bytes()
  std::uint64_t hits = 0;          // lookups answered by a held (or in-progress) geometry
  std::uint64_t misses = 0;        // lookups that found nothing or had to compile
  std::uint64_t evictions = 0;     // geometries dropped to respect the bounds
  std::uint64_t compilations = 0;  // successful compilations
  std::uint64_t failed_compilations = 0;
};

class GeometryCache {
 public:
  explicit GeometryCache(GeometryCacheOptions options = {});
  GeometryCache(const GeometryCache&) = delete;
  GeometryCache& operator=(const GeometryCache&) = delete;

  struct Lookup {
    std::shared_ptr<const CompiledGeometry> geometry;
    bool compiled = false;  // this call compiled it (the id was not held nor being compiled)
    std::chrono::duration<double> compile_time{0.0};  // time this call spent compiling
  };

  // Returns the geometry with def.id(), compiling it when it is not held. Throws GeometryError
  // when the definition does not compile or its compiled form is over max_geometry_bytes
  // (nothing is inserted then); concurrent callers
  // waiting for that same compilation get the same error.
  // `owner` names who posted it (kept with the entry when this call inserts it; an entry already
  // held keeps its owner). Throws GeometryError cache_share_exceeded (see above; the geometry is
  // not kept, and waiters get the error too), unless `refuse_over_share` is false: then such a
  // geometry is returned and not kept (a definition loaded for a lookup, not posted).
  Lookup get_or_compile(const GeometryDefinition& def, const formula::CompileLimits& limits = {},
                        std::string_view owner = {}, bool refuse_over_share = true);

  // The held geometry with this id (marked most recently used), or nullptr.
  std::shared_ptr<const CompiledGeometry> find(const std::string& id);

  // Drops the geometry with this id; false when it was not held.
  bool erase(const std::string& id);

  // The ids held, most recently used first.
  std::vector<std::string> ids() const;

  struct EntryStats {
    std::uint64_t hits = 0;  // lookups it answered since it was inserted
    std::size_t bytes = 0;   // its memory_bytes()
    std::string owner;       // who posted it ("" without keys)
  };
  // Statistics of one held geometry, without touching its recency or the counters.
  std::optional<EntryStats> entry_stats(const std::string& id) const;

  // A page of what is held, in id order: the geometries whose ids come after `after` ("" from
  // the first), at most `limit` of them, with their statistics, without touching recency or the
  // counters; `more` tells whether further ids follow the page.
  struct Held {
    std::shared_ptr<const CompiledGeometry> geometry;
    EntryStats stats;
  };
  struct Page {
    std::vector<Held> held;
    bool more = false;
  };
  Page page(const std::string& after, std::size_t limit) const;

  GeometryCacheStats stats() const;
  const GeometryCacheOptions& options() const { return options_; }

 private:
  struct Entry {
    std::shared_ptr<const CompiledGeometry> geometry;
    std::size_t bytes = 0;
    std::uint64_t hits = 0;
    std::string owner;
    std::list<std::string>::iterator recency;  // position in recency_ (front = most recent)
  };
  // A compilation in progress: waiters block on `done` until `finished`.
  struct Pending {
    bool finished = false;
    std::shared_ptr<const CompiledGeometry> geometry;
    std::exception_ptr error;
  };

  // Throws GeometryError cache_share_exceeded (nothing changed then).
  void insert_locked(const std::string& id, std::shared_ptr<const CompiledGeometry> geometry,
                     std::string_view owner, bool refuse_over_share);
  // Makes room for `bytes` more of `owner` within the bounds and the owner's share, or returns
  // false when only other owners' entries beyond the share could make it.
  bool make_room_locked(std::size_t bytes, const std::string& owner);
  void drop_locked(std::unordered_map<std::string, Entry>::iterator it);
  // What each owner's entries hold.
  struct OwnerUse {
    std::size_t bytes = 0, entries = 0;
  };

  GeometryCacheOptions options_;
  mutable std::mutex mutex_;
  std::condition_variable done_;
  std::unordered_map<std::string, Entry> entries_;
  std::unordered_map<std::string, std::shared_ptr<Pending>> pending_;
  std::list<std::string> recency_;
  std::unordered_map<std::string, OwnerUse> owners_;
  GeometryCacheStats stats_;
};

}  // namespace footpoint
