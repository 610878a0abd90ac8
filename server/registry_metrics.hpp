// What the shared geometry registry (server/geometry_registry.hpp) records for /metrics:
//   footpoint_registry_up                                   gauge (1: connected and answering)
//   footpoint_registry_lookups_total{result}                counter (hit, miss)
//   footpoint_registry_rejected_entries_total               counter (failed the hash or form check)
//   footpoint_registry_writes_total{result}                 counter (stored, not_stored)
//   footpoint_registry_errors_total{kind}                   counter (connect, timeout, auth, io, reply)
//   footpoint_registry_invalidations_total{source}          counter (message, revalidation)
//   footpoint_registry_command_duration_seconds{command}    histogram (get, set, delete, ...)
#pragma once
#include <array>
#include <atomic>
#include <cstdint>
#include <string>

#include "prometheus_text.hpp"
#include "redis/redis_client.hpp"

namespace footpoint::server {

struct RegistryMetrics {
  enum class Command { get, set, del, exists, touch, ping };
  static constexpr int kCommands = 6;
  static constexpr std::array<double, 11> kBuckets{0.00005, 0.0001, 0.00025, 0.0005, 0.001, 0.0025,
                                                   0.005,   0.01,   0.025,   0.1,    1.0};

  std::atomic<bool> up{false};
  std::atomic<std::uint64_t> hits{0}, misses{0}, rejected{0};
  std::atomic<std::uint64_t> stored{0}, not_stored{0};
  std::atomic<std::uint64_t> invalidated_by_message{0}, invalidated_by_revalidation{0};
  std::array<std::atomic<std::uint64_t>, redis::Error::kKinds> errors{};
  std::array<Histogram<kBuckets.size()>, kCommands> durations{};

  void observe(Command c, double seconds) { durations[static_cast<int>(c)].observe(kBuckets, seconds); }
  void count_error(redis::Error::Kind kind) {
    errors[static_cast<int>(kind)].fetch_add(1, std::memory_order_relaxed);
  }

  // Appends the registry's series to a /metrics body.
  void render(std::string& out) const;
};

}  // namespace footpoint::server
