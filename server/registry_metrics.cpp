#include "registry_metrics.hpp"

namespace footpoint::server {

namespace {

const char* command_name(int c) {
  static const char* const names[RegistryMetrics::kCommands] = {"get",    "set",   "delete",
                                                                "exists", "touch", "ping"};
  return names[c];
}

double value(const std::atomic<std::uint64_t>& a) {
  return static_cast<double>(a.load(std::memory_order_relaxed));
}

}  // namespace

void RegistryMetrics::render(std::string& out) const {
  header(out, "footpoint_registry_up", "gauge", "1 while the shared geometry registry (Redis) answers.");
  line(out, "footpoint_registry_up", "", up.load() ? 1.0 : 0.0);
  header(out, "footpoint_registry_lookups_total", "counter",
         "Registry lookups of ids not held in this replica's cache, by result.");
  line(out, "footpoint_registry_lookups_total", "result=\"hit\"", value(hits));
  line(out, "footpoint_registry_lookups_total", "result=\"miss\"", value(misses));
  header(
      out, "footpoint_registry_rejected_entries_total", "counter",
      "Registry entries refused: their content hash is not their id, or they are no canonical definition.");
  line(out, "footpoint_registry_rejected_entries_total", "", value(rejected));
  header(out, "footpoint_registry_writes_total", "counter",
         "Posted geometries the registry stored, or could not store (kept by this replica only).");
  line(out, "footpoint_registry_writes_total", "result=\"stored\"", value(stored));
  line(out, "footpoint_registry_writes_total", "result=\"not_stored\"", value(not_stored));
  header(out, "footpoint_registry_errors_total", "counter", "Failed registry operations, by kind.");
  for (int k = 0; k < redis::Error::kKinds; ++k)
    line(out, "footpoint_registry_errors_total",
         std::string("kind=\"") + redis::to_string(static_cast<redis::Error::Kind>(k)) + "\"",
         value(errors[k]));
  header(out, "footpoint_registry_invalidations_total", "counter",
         "Geometries dropped from this replica's cache because they were deleted elsewhere.");
  line(out, "footpoint_registry_invalidations_total", "source=\"message\"", value(invalidated_by_message));
  line(out, "footpoint_registry_invalidations_total", "source=\"revalidation\"",
       value(invalidated_by_revalidation));
  header(out, "footpoint_registry_command_duration_seconds", "histogram",
         "Time of registry round trips, by command (connecting included).");
  for (int c = 0; c < kCommands; ++c) {
    if (durations[c].count.load(std::memory_order_relaxed) == 0) continue;
    histogram_lines(out, "footpoint_registry_command_duration_seconds",
                    std::string("command=\"") + command_name(c) + "\"", durations[c], kBuckets);
  }
}

}  // namespace footpoint::server
