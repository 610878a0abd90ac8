#include "cache/geometry_cache.hpp"

#include <algorithm>
#include <cstddef>
#include <string>
#include <utility>

#include "geometry/geometry_error.hpp"

namespace footpoint {

GeometryCache::GeometryCache(GeometryCacheOptions options) : options_(options) {}

GeometryCache::Lookup GeometryCache::get_or_compile(const GeometryDefinition& def,
                                                    const formula::CompileLimits& limits,
                                                    std::string_view owner, bool refuse_over_share) {
  const std::string id = def.id();
  std::shared_ptr<Pending> pending;
  {
    std::unique_lock lock(mutex_);
    if (auto it = entries_.find(id); it != entries_.end()) {
      ++stats_.hits;
      ++it->second.hits;
      recency_.splice(recency_.begin(), recency_, it->second.recency);
      return {it->second.geometry, false, {}};
    }
    if (auto it = pending_.find(id); it != pending_.end()) {
      // Someone is compiling this id right now: wait for that one compilation.
      ++stats_.hits;
      std::shared_ptr<Pending> other = it->second;
      done_.wait(lock, [&] { return other->finished; });
      if (other->error) std::rethrow_exception(other->error);
      return {other->geometry, false, {}};
    }
    ++stats_.misses;
    pending = std::make_shared<Pending>();
    pending_.emplace(id, pending);
  }

  // Compile outside the lock: other ids stay available meanwhile.
  const auto start = std::chrono::steady_clock::now();
  std::shared_ptr<const CompiledGeometry> geometry;
  std::exception_ptr error;
  try {
    formula::CompileLimits bounded = limits;
    if (options_.max_geometry_bytes > 0) bounded.max_geometry_bytes = options_.max_geometry_bytes;
    geometry = compile_geometry(def, bounded);
    if (const std::size_t bytes = geometry->memory_bytes();
        options_.max_geometry_bytes > 0 && bytes > options_.max_geometry_bytes) {
      geometry.reset();
      throw GeometryError("geometry_too_large", "", -1,
                          "the compiled geometry holds " + std::to_string(bytes) +
                              " bytes of search structure, over the limit of " +
                              std::to_string(options_.max_geometry_bytes) +
                              " per geometry: narrow the domain or simplify the formulas");
    }
  } catch (...) {
    error = std::current_exception();
  }
  const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;

  {
    std::lock_guard lock(mutex_);
    pending_.erase(id);
    if (!error) {
      try {
        insert_locked(id, geometry, owner, refuse_over_share);
      } catch (...) {
        error = std::current_exception();
        geometry.reset();
      }
    }
    pending->finished = true;
    pending->geometry = geometry;
    pending->error = error;
    if (error)
      ++stats_.failed_compilations;
    else
      ++stats_.compilations;
  }
  done_.notify_all();
  if (error) std::rethrow_exception(error);
  return {std::move(geometry), true, elapsed};
}

void GeometryCache::insert_locked(const std::string& id, std::shared_ptr<const CompiledGeometry> geometry,
                                  std::string_view owner, bool refuse_over_share) {
  const std::size_t bytes = geometry->memory_bytes();
  if (bytes > options_.max_bytes || options_.max_entries == 0) return;  // too large to keep
  const std::string who(owner);
  if (!make_room_locked(bytes, who)) {
    if (!refuse_over_share) return;  // answered, not kept
    throw GeometryError("cache_share_exceeded", "", -1,
                        "the compiled geometry holds " + std::to_string(bytes) +
                            " bytes; keeping it would evict other clients' geometries beyond this client's "
                            "share of the cache (" +
                            std::to_string(static_cast<std::size_t>(
                                options_.share * static_cast<double>(options_.max_bytes))) +
                            " bytes): retry later, delete some of your geometries, or narrow the domain");
  }
  recency_.push_front(id);
  entries_[id] = Entry{std::move(geometry), bytes, 0, who, recency_.begin()};
  stats_.bytes += bytes;
  OwnerUse& use = owners_[who];
  use.bytes += bytes;
  ++use.entries;
  stats_.size = entries_.size();
}

bool GeometryCache::make_room_locked(std::size_t bytes, const std::string& owner) {
  const bool shared = options_.share < 1.0;
  const auto share_bytes = static_cast<std::size_t>(options_.share * static_cast<double>(options_.max_bytes));
  const auto share_entries = std::max<std::size_t>(
      1, static_cast<std::size_t>(options_.share * static_cast<double>(options_.max_entries)));
  const auto mine = [&] {
    const auto it = owners_.find(owner);
    return it == owners_.end() ? OwnerUse{} : it->second;
  };
  const auto over_share = [&](const OwnerUse& use) {
    return shared && (use.bytes + bytes > share_bytes || use.entries + 1 > share_entries);
  };
  const auto full = [&] {
    return stats_.bytes + bytes > options_.max_bytes || entries_.size() + 1 > options_.max_entries;
  };
  // With all of its own entries gone, would the owner still have to evict others' beyond its share?
  {
    const OwnerUse use = mine();
    const std::size_t others_bytes = stats_.bytes - use.bytes, others_entries = entries_.size() - use.entries;
    if (over_share(OwnerUse{}) &&
        (others_bytes + bytes > options_.max_bytes || others_entries + 1 > options_.max_entries))
      return false;
  }
  while (full()) {
    const OwnerUse use = mine();
    auto victim = recency_.end();
    if (use.entries > 0 && (use.entries == entries_.size() || over_share(use))) {
      // alone, or over its share: its own least recently used entry
      for (auto r = recency_.rbegin(); r != recency_.rend(); ++r)
        if (entries_.find(*r)->second.owner == owner) {
          victim = std::prev(r.base());
          break;
        }
    } else {
      victim = std::prev(recency_.end());
    }
    drop_locked(entries_.find(*victim));
    ++stats_.evictions;
  }
  return true;
}

void GeometryCache::drop_locked(std::unordered_map<std::string, Entry>::iterator it) {
  stats_.bytes -= it->second.bytes;
  if (auto use = owners_.find(it->second.owner); use != owners_.end()) {
    use->second.bytes -= it->second.bytes;
    if (--use->second.entries == 0) owners_.erase(use);
  }
  recency_.erase(it->second.recency);
  entries_.erase(it);
  stats_.size = entries_.size();
}

std::shared_ptr<const CompiledGeometry> GeometryCache::find(const std::string& id) {
  std::lock_guard lock(mutex_);
  auto it = entries_.find(id);
  if (it == entries_.end()) {
    ++stats_.misses;
    return nullptr;
  }
  ++stats_.hits;
  ++it->second.hits;
  recency_.splice(recency_.begin(), recency_, it->second.recency);
  return it->second.geometry;
}

bool GeometryCache::erase(const std::string& id) {
  std::lock_guard lock(mutex_);
  auto it = entries_.find(id);
  if (it == entries_.end()) return false;
  drop_locked(it);
  return true;
}

std::vector<std::string> GeometryCache::ids() const {
  std::lock_guard lock(mutex_);
  return {recency_.begin(), recency_.end()};
}

std::optional<GeometryCache::EntryStats> GeometryCache::entry_stats(const std::string& id) const {
  std::lock_guard lock(mutex_);
  auto it = entries_.find(id);
  if (it == entries_.end()) return std::nullopt;
  return EntryStats{it->second.hits, it->second.bytes, it->second.owner};
}

GeometryCache::Page GeometryCache::page(const std::string& after, std::size_t limit) const {
  std::lock_guard lock(mutex_);
  std::vector<const std::pair<const std::string, Entry>*> later;
  for (const auto& e : entries_)
    if (e.first > after) later.push_back(&e);
  const auto by_id = [](const auto* a, const auto* b) { return a->first < b->first; };
  const std::size_t n = std::min(limit, later.size());
  std::partial_sort(later.begin(), later.begin() + static_cast<std::ptrdiff_t>(n), later.end(), by_id);
  Page page;
  page.more = later.size() > n;
  for (std::size_t i = 0; i < n; ++i)
    page.held.push_back({later[i]->second.geometry,
                         EntryStats{later[i]->second.hits, later[i]->second.bytes, later[i]->second.owner}});
  return page;
}

GeometryCacheStats GeometryCache::stats() const {
  std::lock_guard lock(mutex_);
  return stats_;
}

}  // namespace footpoint
