// Everything an operator can set, with its default. Each field is read from a command-line flag
// and an environment variable; the flag wins over the variable, the variable over the default.
#pragma once
#include <algorithm>
#include <chrono>
#include <cstddef>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "formula/program.hpp"

namespace footpoint::server {

struct ServerConfig {
  // --host / FOOTPOINT_HOST: the address to listen on.
  std::string host = "0.0.0.0";
  // --port / FOOTPOINT_PORT: the TCP port; 0 picks a free one (tests).
  int port = 8080;
  // --threads / FOOTPOINT_THREADS: workers of the numerical pool; 0 = the CPUs of the cgroup's
  // quota, else the hardware threads (default_threads(), batch/thread_pool.hpp).
  unsigned threads = 0;
  // --connection-threads / FOOTPOINT_CONNECTION_THREADS: HTTP connections served at once (one
  // thread each; further connections wait in the accept queue). Well above the expected number
  // of client connections: the threads only wait while the numerical pool works.
  unsigned connection_threads = 128;
  // --max-inflight / FOOTPOINT_MAX_INFLIGHT: API requests being answered at once; beyond it a
  // request gets 503 "overloaded" at once instead of queueing behind the others. 0 = 7/8 of
  // connection_threads, so that health checks and metrics always find a free thread.
  unsigned max_inflight = 0;
  unsigned effective_max_inflight() const {
    return max_inflight ? max_inflight : (connection_threads * 7 + 7) / 8;
  }
  // --max-inflight-points / FOOTPOINT_MAX_INFLIGHT_POINTS: points of the requests being
  // projected at once. Bounds the memory of results and responses (~0.6 kB per point); a
  // request that would exceed it gets 503 "overloaded", unless nothing else is in flight.
  std::size_t max_inflight_points = 500000;
  // --max-inflight-bytes / FOOTPOINT_MAX_INFLIGHT_BYTES: one memory budget for every request that
  // holds much memory while it runs: a batch or evaluation (kBytesPerPoint a point), a stream's
  // window (and the binary body it reads ahead), a mesh (kMeshBytesPerVertex a vertex). Each
  // reserves its estimate before it runs; over the budget it gets 503 "overloaded" with
  // Retry-After (footpoint_memory_refusals_total), unless nothing else is in flight or it is
  // under kAlwaysAdmittedBytes (single points are always answered). 0: the container's memory
  // limit (cgroup, read by configure_from_command_line) less the cache, one geometry's compile
  // and kBaselineBytes, at least kMinInflightBytes; without a limit kDefaultInflightBytes.
  std::size_t max_inflight_bytes = 0;
  static constexpr std::size_t kBytesPerPoint = 1321;      // a 100,000-point batch peaks at 126 MiB
  static constexpr std::size_t kMeshBytesPerVertex = 412;  // a 263,169-vertex mesh: 108 MB
  static constexpr std::size_t kAlwaysAdmittedBytes = std::size_t{1} << 20;
  static constexpr std::size_t kBaselineBytes = std::size_t{128} << 20;  // the process at rest
  static constexpr std::size_t kMinInflightBytes = std::size_t{64} << 20;
  static constexpr std::size_t kDefaultInflightBytes = std::size_t{1} << 30;
  // `memory_limit`: the container's (cgroup_memory_limit()), 0 when none.
  std::size_t effective_max_inflight_bytes(std::size_t memory_limit) const;
  // --max-body-bytes / FOOTPOINT_MAX_BODY_BYTES: request body limit (413 above it): 16 MiB holds
  // a 100,000-point batch at full precision.
  std::size_t max_body_bytes = std::size_t{16} << 20;
  // --max-points / FOOTPOINT_MAX_POINTS: points per request (413 above it).
  std::size_t max_points = 100000;
  // --max-formula-length / FOOTPOINT_MAX_FORMULA_LENGTH: characters per formula (422 above it),
  // at most what the formula compiler reads (formula::kLongestFormula, also the default).
  std::size_t max_formula_length = formula::kLongestFormula;
  // --deadline-ms / FOOTPOINT_DEADLINE_MS: per-request deadline; points not started by then
  // get the status deadline_exceeded.
  std::chrono::milliseconds deadline{30000};
  // --compile-deadline-ms / FOOTPOINT_COMPILE_DEADLINE_MS: how long compiling a geometry (with what
  // `auto` precomputes) may take before the request gets 422 compile_timeout; 0 = the request deadline.
  std::chrono::milliseconds compile_deadline{0};
  // --max-mesh-resolution / FOOTPOINT_MAX_MESH_RESOLUTION: the largest `resolution` of
  // GET /v1/geometries/{id}/mesh (400 above it): cells along a surface's larger direction, a
  // curve's segments. 512 bounds a surface's mesh at 263,169 vertices (a sphere: 46 MB of JSON).
  int max_mesh_resolution = 512;
  // --ui / FOOTPOINT_UI: on serves the browser pages (the playground at /, the API reference at
  // /docs and their files under /ui/); off answers them 404.
  bool ui = true;
  // --cache-entries / FOOTPOINT_CACHE_ENTRIES: compiled geometries kept (LRU).
  std::size_t cache_entries = 1024;
  // --cache-bytes / FOOTPOINT_CACHE_BYTES: memory the kept geometries may hold (LRU): 256 MiB.
  std::size_t cache_bytes = std::size_t{256} << 20;
  // --max-geometry-bytes / FOOTPOINT_MAX_GEOMETRY_BYTES: memory one compiled geometry may hold; a
  // larger one is refused (422 geometry_too_large, with the size reached) and not cached, so that
  // one post cannot evict every other client's geometries. 0: a quarter of cache_bytes.
  std::size_t max_geometry_bytes = 0;
  std::size_t effective_max_geometry_bytes() const {
    return max_geometry_bytes ? max_geometry_bytes : std::max<std::size_t>(cache_bytes / 4, 1);
  }
  // --cache-share / FOOTPOINT_CACHE_SHARE: the fraction of --cache-bytes (and --cache-entries)
  // one API key's geometries may hold once the cache is full and other keys hold geometries:
  // beyond it a key's post evicts its own least recently used geometries, not another key's, and
  // a geometry that could only be kept by evicting others' beyond the share is refused (507
  // cache_share_exceeded). A key alone in the cache may fill it. 1: plain LRU across keys.
  double cache_share = 0.5;
  // --keep-alive-timeout-s / FOOTPOINT_KEEP_ALIVE_TIMEOUT_S: an idle connection is closed after
  // this long (a graceful shutdown closes the idle ones at once).
  int keep_alive_timeout_s = 5;
  // --keep-alive-max / FOOTPOINT_KEEP_ALIVE_MAX: requests served per connection before it closes.
  std::size_t keep_alive_max = 100000;
  // --probe-port / FOOTPOINT_PROBE_PORT: a second listener, plain HTTP on two threads of its own,
  // answering only /healthz and /readyz, so that the platform's probes are answered whatever the
  // API's connections do (slow clients holding every connection thread); 0: none.
  int probe_port = 0;
  // --read-timeout-s / FOOTPOINT_READ_TIMEOUT_S: a request (line, headers and body) must arrive
  // whole within this long of its first byte, or its connection is closed (slow-loris clients;
  // ReadDeadline, connections.hpp); 0: no bound but the per-read --io-timeout-s.
  int read_timeout_s = 30;
  // --io-timeout-s / FOOTPOINT_IO_TIMEOUT_S: socket read/write timeout for a stalled peer.
  int io_timeout_s = 30;
  // --backlog / FOOTPOINT_BACKLOG: the listen queue of not yet accepted connections.
  int backlog = 1024;
  // --log-level / FOOTPOINT_LOG_LEVEL: trace, debug, info, warn, error, critical or off.
  std::string log_level = "info";
  // --cors-origins / FOOTPOINT_CORS_ORIGINS: the origins (scheme://host[:port]) whose browser pages
  // may call the API from another origin, comma-separated, or "*" for any; empty: none (CORS off,
  // OPTIONS answers 405).
  std::vector<std::string> cors_origins;

  // The shared geometry registry (server/geometry_registry.hpp), off when the URL is empty.
  // --registry-url / FOOTPOINT_REGISTRY_URL: redis://[user@]host[:port][/db].
  std::string registry_url;
  // FOOTPOINT_REGISTRY_PASSWORD (no flag: a flag would show in process lists), or the file named
  // by --registry-password-file / FOOTPOINT_REGISTRY_PASSWORD_FILE (a mounted Secret; one
  // trailing newline is dropped). Never logged.
  std::string registry_password;
  std::string registry_password_file;
  // --registry-timeout-ms / FOOTPOINT_REGISTRY_TIMEOUT_MS: bound on each Redis operation of a
  // request (connecting included); beyond it the request goes on without the registry.
  std::chrono::milliseconds registry_timeout{250};
  // --registry-pool-size / FOOTPOINT_REGISTRY_POOL_SIZE: Redis connections for requests.
  std::size_t registry_pool_size = 4;
  // --registry-ttl-s / FOOTPOINT_REGISTRY_TTL_S: an entry unused on every replica for this long
  // expires; 0: never (bound Redis by maxmemory with allkeys-lru instead).
  std::chrono::seconds registry_ttl{604800};

  // Exposure (docs/security.md). --tls-cert / FOOTPOINT_TLS_CERT and --tls-key /
  // FOOTPOINT_TLS_KEY: PEM files (the certificate, then any intermediates; the private key). Both
  // given: HTTPS only, TLS 1.2 and 1.3, the files read again on SIGHUP. Neither: plain HTTP.
  std::string tls_cert;
  std::string tls_key;
  // --api-keys / FOOTPOINT_API_KEYS: the keys file (server/access.hpp: NAME SCOPES SHA256HEX per
  // line), read again on SIGHUP. Empty: no authentication.
  std::string api_keys;
  // --metrics-key-free / FOOTPOINT_METRICS_KEY_FREE: /metrics answers without a key (else it
  // needs the admin scope when keys are on).
  bool metrics_key_free = false;
  // --rate-limit / FOOTPOINT_RATE_LIMIT: points a second each key may have projected or
  // evaluated (any other API request counts one point); 0: no limit. Without keys every client
  // shares one bucket.
  std::size_t rate_limit = 0;
  // --rate-burst / FOOTPOINT_RATE_BURST: the bucket's size in points; 0: the larger of
  // --rate-limit and --max-points, so that every admissible request can pass.
  std::size_t rate_burst = 0;
  std::size_t effective_rate_burst() const {
    return rate_burst ? rate_burst : std::max(rate_limit, max_points);
  }
};

struct ConfigError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Reads flags (--name value or --name=value) and environment variables (through `env`, which
// returns nullptr for an unset variable). Throws ConfigError for an unknown flag or a bad value.
// Sets `help` when --help is given (the caller prints usage()).
ServerConfig load_config(int argc, const char* const* argv,
                         const std::function<const char*(const char*)>& env, bool& help);

// The FOOTPOINT_* variables of `environment` ("NAME=value" entries, null-terminated, as environ)
// that are no setting's: a misspelled one would otherwise be ignored in silence.
std::vector<std::string> unknown_environment(const char* const* environment);

// The memory limit of the cgroup under `root` (v2 memory.max, else v1
// memory/memory.limit_in_bytes), 0 when there is none or it cannot be read.
std::size_t cgroup_memory_limit(const std::string& root = "/sys/fs/cgroup");

// The flags, their variables and defaults, one per line.
std::string usage();

// The settings in effect, as a JSON object keyed by flag name, numbers as numbers: what a
// setting's 0 stands for resolved (threads, max-inflight, compile-deadline-ms), the password
// left out. The start-up log line carries it.
std::string effective_settings_json(const ServerConfig& config);

// A server executable's start: the configuration from argv and the process environment into
// `config`, or the exit code to end with: 0 after printing usage() for --help or the version for
// --version, 2 after naming the bad flag or value on stderr (prefixed with `program`). -1: go on.
int configure_from_command_line(int argc, const char* const* argv, const char* program, ServerConfig& config);

}  // namespace footpoint::server
