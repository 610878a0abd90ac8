#include "config.hpp"

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <string_view>
#include <thread>
#include <vector>

#include "batch/thread_pool.hpp"
#include "json_writer.hpp"
#include "redis/redis_client.hpp"
#include "version.hpp"

namespace footpoint::server {

namespace {

template <class T>
T parse_integer(const std::string& name, const std::string& text, T min, T max) {
  T value{};
  const auto r = std::from_chars(text.data(), text.data() + text.size(), value);
  if (r.ec != std::errc() || r.ptr != text.data() + text.size() || value < min || value > max)
    throw ConfigError(name + ": expected an integer in [" + std::to_string(min) + ", " + std::to_string(max) +
                      "], got '" + text + "'");
  return value;
}

// A fraction in (0, 1].
double parse_fraction(const std::string& name, const std::string& text) {
  double value = 0.0;
  const auto r = std::from_chars(text.data(), text.data() + text.size(), value);
  if (r.ec != std::errc() || r.ptr != text.data() + text.size() || !(value > 0.0 && value <= 1.0))
    throw ConfigError(name + ": expected a fraction in (0, 1], got '" + text + "'");
  return value;
}

// A number as the settings show it: the shortest text that reads back the same.
std::string show_number(double value) {
  char text[32];
  const auto r = std::to_chars(text, text + sizeof text, value);
  return std::string(text, r.ptr);
}

struct Setting {
  const char* flag;  // without the leading "--"; nullptr: environment only
  const char* env;
  const char* help;
  void (*set)(ServerConfig&, const std::string& name, const std::string& value);
  std::string (*show)(const ServerConfig&);
  bool switch_flag = false;  // given alone (--name) it means "on"
};

constexpr std::size_t kMaxSize = std::size_t{1} << 40;

const std::vector<Setting>& settings() {
  static const std::vector<Setting> table = {
      {"host", "FOOTPOINT_HOST", "address to listen on",
       [](ServerConfig& c, const std::string& n, const std::string& v) {
         if (v.empty()) throw ConfigError(n + ": empty host");
         c.host = v;
       },
       [](const ServerConfig& c) { return c.host; }},
      {"port", "FOOTPOINT_PORT", "TCP port (0: any free port)",
       [](ServerConfig& c, const std::string& n, const std::string& v) {
         c.port = parse_integer<int>(n, v, 0, 65535);
       },
       [](const ServerConfig& c) { return std::to_string(c.port); }},
      {"threads", "FOOTPOINT_THREADS",
       "numerical worker threads (0: the cgroup's CPU quota, else hardware threads)",
       [](ServerConfig& c, const std::string& n, const std::string& v) {
         c.threads = parse_integer<unsigned>(n, v, 0, 1024);
       },
       [](const ServerConfig& c) { return std::to_string(c.threads); }},
      {"connection-threads", "FOOTPOINT_CONNECTION_THREADS", "HTTP connections served at once",
       [](ServerConfig& c, const std::string& n, const std::string& v) {
         c.connection_threads = parse_integer<unsigned>(n, v, 2, 16384);
       },
       [](const ServerConfig& c) { return std::to_string(c.connection_threads); }},
      {"max-inflight", "FOOTPOINT_MAX_INFLIGHT",
       "API requests answered at once before 503 overloaded (0: 7/8 of connection threads)",
       [](ServerConfig& c, const std::string& n, const std::string& v) {
         c.max_inflight = parse_integer<unsigned>(n, v, 0, 1u << 20);
       },
       [](const ServerConfig& c) { return std::to_string(c.max_inflight); }},
      {"max-inflight-points", "FOOTPOINT_MAX_INFLIGHT_POINTS",
       "points being projected at once before 503 overloaded",
       [](ServerConfig& c, const std::string& n, const std::string& v) {
         c.max_inflight_points = parse_integer<std::size_t>(n, v, 1, std::size_t{1} << 40);
       },
       [](const ServerConfig& c) { return std::to_string(c.max_inflight_points); }},
      {"max-inflight-bytes", "FOOTPOINT_MAX_INFLIGHT_BYTES",
       "memory the requests in flight may reserve before 503 overloaded (0: from the cgroup's memory limit)",
       [](ServerConfig& c, const std::string& n, const std::string& v) {
         c.max_inflight_bytes = parse_integer<std::size_t>(n, v, 0, kMaxSize);
       },
       [](const ServerConfig& c) { return std::to_string(c.max_inflight_bytes); }},
      {"max-body-bytes", "FOOTPOINT_MAX_BODY_BYTES", "request body limit in bytes",
       [](ServerConfig& c, const std::string& n, const std::string& v) {
         c.max_body_bytes = parse_integer<std::size_t>(n, v, 1024, kMaxSize);
       },
       [](const ServerConfig& c) { return std::to_string(c.max_body_bytes); }},
      {"max-points", "FOOTPOINT_MAX_POINTS", "points per request",
       [](ServerConfig& c, const std::string& n, const std::string& v) {
         c.max_points = parse_integer<std::size_t>(n, v, 1, std::size_t{1} << 32);
       },
       [](const ServerConfig& c) { return std::to_string(c.max_points); }},
      {"max-formula-length", "FOOTPOINT_MAX_FORMULA_LENGTH", "characters per formula",
       [](ServerConfig& c, const std::string& n, const std::string& v) {
         c.max_formula_length = parse_integer<std::size_t>(n, v, 1, formula::kLongestFormula);
       },
       [](const ServerConfig& c) { return std::to_string(c.max_formula_length); }},
      {"deadline-ms", "FOOTPOINT_DEADLINE_MS", "per-request deadline in milliseconds",
       [](ServerConfig& c, const std::string& n, const std::string& v) {
         c.deadline = std::chrono::milliseconds(parse_integer<long>(n, v, 1, 86400000));
       },
       [](const ServerConfig& c) { return std::to_string(c.deadline.count()); }},
      {"compile-deadline-ms", "FOOTPOINT_COMPILE_DEADLINE_MS",
       "time a geometry's compilation may take in milliseconds (0 = the request deadline)",
       [](ServerConfig& c, const std::string& n, const std::string& v) {
         c.compile_deadline = std::chrono::milliseconds(parse_integer<long>(n, v, 0, 86400000));
       },
       [](const ServerConfig& c) { return std::to_string(c.compile_deadline.count()); }},
      {"max-mesh-resolution", "FOOTPOINT_MAX_MESH_RESOLUTION",
       "largest resolution of a mesh (a surface's cells along its larger direction, a curve's segments)",
       [](ServerConfig& c, const std::string& n, const std::string& v) {
         c.max_mesh_resolution = parse_integer<int>(n, v, 2, 4096);
       },
       [](const ServerConfig& c) { return std::to_string(c.max_mesh_resolution); }},
      {"ui", "FOOTPOINT_UI", "on: serve the playground at / and the API reference at /docs; off: 404",
       [](ServerConfig& c, const std::string& n, const std::string& v) {
         if (v != "on" && v != "off") throw ConfigError(n + ": expected on or off, got '" + v + "'");
         c.ui = v == "on";
       },
       [](const ServerConfig& c) { return std::string(c.ui ? "on" : "off"); }},
      {"cache-entries", "FOOTPOINT_CACHE_ENTRIES", "compiled geometries kept (LRU)",
       [](ServerConfig& c, const std::string& n, const std::string& v) {
         c.cache_entries = parse_integer<std::size_t>(n, v, 1, std::size_t{1} << 24);
       },
       [](const ServerConfig& c) { return std::to_string(c.cache_entries); }},
      {"cache-bytes", "FOOTPOINT_CACHE_BYTES", "memory the kept geometries may hold, in bytes",
       [](ServerConfig& c, const std::string& n, const std::string& v) {
         c.cache_bytes = parse_integer<std::size_t>(n, v, 1, kMaxSize);
       },
       [](const ServerConfig& c) { return std::to_string(c.cache_bytes); }},
      {"max-geometry-bytes", "FOOTPOINT_MAX_GEOMETRY_BYTES",
       "memory one compiled geometry may hold, in bytes (0: a quarter of cache-bytes)",
       [](ServerConfig& c, const std::string& n, const std::string& v) {
         c.max_geometry_bytes = parse_integer<std::size_t>(n, v, 0, kMaxSize);
       },
       [](const ServerConfig& c) { return std::to_string(c.max_geometry_bytes); }},
      {"cache-share", "FOOTPOINT_CACHE_SHARE",
       "fraction of the cache one API key's geometries may hold when others hold some (1: plain LRU)",
       [](ServerConfig& c, const std::string& n, const std::string& v) {
         c.cache_share = parse_fraction(n, v);
       },
       [](const ServerConfig& c) { return show_number(c.cache_share); }},
      {"keep-alive-timeout-s", "FOOTPOINT_KEEP_ALIVE_TIMEOUT_S", "idle connection timeout in seconds",
       [](ServerConfig& c, const std::string& n, const std::string& v) {
         c.keep_alive_timeout_s = parse_integer<int>(n, v, 1, 3600);
       },
       [](const ServerConfig& c) { return std::to_string(c.keep_alive_timeout_s); }},
      {"keep-alive-max", "FOOTPOINT_KEEP_ALIVE_MAX", "requests per connection",
       [](ServerConfig& c, const std::string& n, const std::string& v) {
         c.keep_alive_max = parse_integer<std::size_t>(n, v, 1, std::size_t{1} << 40);
       },
       [](const ServerConfig& c) { return std::to_string(c.keep_alive_max); }},
      {"probe-port", "FOOTPOINT_PROBE_PORT",
       "a port of its own for /healthz and /readyz (plain HTTP, two threads; 0: none)",
       [](ServerConfig& c, const std::string& n, const std::string& v) {
         c.probe_port = parse_integer<int>(n, v, 0, 65535);
       },
       [](const ServerConfig& c) { return std::to_string(c.probe_port); }},
      {"read-timeout-s", "FOOTPOINT_READ_TIMEOUT_S",
       "seconds a request (headers and body) may take to arrive from its first byte, else its connection "
       "closes (0: no bound)",
       [](ServerConfig& c, const std::string& n, const std::string& v) {
         c.read_timeout_s = parse_integer<int>(n, v, 0, 3600);
       },
       [](const ServerConfig& c) { return std::to_string(c.read_timeout_s); }},
      {"io-timeout-s", "FOOTPOINT_IO_TIMEOUT_S", "socket read/write timeout in seconds",
       [](ServerConfig& c, const std::string& n, const std::string& v) {
         c.io_timeout_s = parse_integer<int>(n, v, 1, 3600);
       },
       [](const ServerConfig& c) { return std::to_string(c.io_timeout_s); }},
      {"backlog", "FOOTPOINT_BACKLOG", "listen queue length",
       [](ServerConfig& c, const std::string& n, const std::string& v) {
         c.backlog = parse_integer<int>(n, v, 1, 65535);
       },
       [](const ServerConfig& c) { return std::to_string(c.backlog); }},
      {"log-level", "FOOTPOINT_LOG_LEVEL", "trace, debug, info, warn, error, critical or off",
       [](ServerConfig& c, const std::string& n, const std::string& v) {
         static const char* const levels[] = {"trace", "debug", "info", "warn", "error", "critical", "off"};
         for (const char* l : levels)
           if (v == l) {
             c.log_level = v;
             return;
           }
         throw ConfigError(n + ": unknown log level '" + v + "'");
       },
       [](const ServerConfig& c) { return c.log_level; }},
      {"cors-origins", "FOOTPOINT_CORS_ORIGINS",
       "origins (scheme://host[:port]) whose pages may call the API, comma-separated, or * (\"\": none)",
       [](ServerConfig& c, const std::string& n, const std::string& v) {
         c.cors_origins.clear();
         std::size_t start = 0;
         while (start <= v.size()) {
           const auto comma = std::min(v.find(',', start), v.size());
           std::string origin = v.substr(start, comma - start);
           origin.erase(0, origin.find_first_not_of(' '));
           origin.erase(origin.find_last_not_of(' ') + 1);
           start = comma + 1;
           if (origin.empty()) continue;
           const auto scheme = origin.find("://");
           const bool web = origin.rfind("http://", 0) == 0 || origin.rfind("https://", 0) == 0;
           if (origin != "*" && (!web || origin.size() == scheme + 3 ||
                                 origin.find_first_of("/?# ", scheme + 3) != std::string::npos))
             throw ConfigError(n + ": '" + origin +
                               "' is not an origin: scheme://host[:port] (http or https, no path), or *");
           c.cors_origins.push_back(origin);
         }
       },
       [](const ServerConfig& c) {
         std::string s;
         for (const auto& o : c.cors_origins) (s += s.empty() ? "" : ",") += o;
         return s.empty() ? std::string("\"\"") : s;
       }},
      {"registry-url", "FOOTPOINT_REGISTRY_URL",
       "shared geometry registry, redis://[user@]host[:port][/db] (\"\": none, one process)",
       [](ServerConfig& c, const std::string& n, const std::string& v) {
         if (!v.empty()) {
           try {
             redis::parse_url(v);
           } catch (const std::invalid_argument& e) {
             throw ConfigError(n + ": " + e.what());
           }
         }
         c.registry_url = v;
       },
       [](const ServerConfig& c) { return c.registry_url.empty() ? std::string("\"\"") : c.registry_url; }},
      {nullptr, "FOOTPOINT_REGISTRY_PASSWORD", "the registry's password (environment only, never logged)",
       [](ServerConfig& c, const std::string&, const std::string& v) { c.registry_password = v; },
       [](const ServerConfig&) { return std::string("none"); }},
      {"registry-password-file", "FOOTPOINT_REGISTRY_PASSWORD_FILE",
       "file holding the registry's password (a mounted Secret)",
       [](ServerConfig& c, const std::string&, const std::string& v) { c.registry_password_file = v; },
       [](const ServerConfig& c) {
         return c.registry_password_file.empty() ? std::string("\"\"") : c.registry_password_file;
       }},
      {"registry-timeout-ms", "FOOTPOINT_REGISTRY_TIMEOUT_MS",
       "bound on each registry operation of a request, in milliseconds",
       [](ServerConfig& c, const std::string& n, const std::string& v) {
         c.registry_timeout = std::chrono::milliseconds(parse_integer<long>(n, v, 1, 60000));
       },
       [](const ServerConfig& c) { return std::to_string(c.registry_timeout.count()); }},
      {"registry-pool-size", "FOOTPOINT_REGISTRY_POOL_SIZE", "registry connections for requests",
       [](ServerConfig& c, const std::string& n, const std::string& v) {
         c.registry_pool_size = parse_integer<std::size_t>(n, v, 1, 1024);
       },
       [](const ServerConfig& c) { return std::to_string(c.registry_pool_size); }},
      {"registry-ttl-s", "FOOTPOINT_REGISTRY_TTL_S",
       "seconds an entry unused on every replica stays in the registry (0: no expiry)",
       [](ServerConfig& c, const std::string& n, const std::string& v) {
         c.registry_ttl = std::chrono::seconds(parse_integer<long>(n, v, 0, 10L * 365 * 86400));
       },
       [](const ServerConfig& c) { return std::to_string(c.registry_ttl.count()); }},
      {"tls-cert", "FOOTPOINT_TLS_CERT", "PEM certificate (chain) to serve HTTPS with (with --tls-key)",
       [](ServerConfig& c, const std::string&, const std::string& v) { c.tls_cert = v; },
       [](const ServerConfig& c) { return c.tls_cert.empty() ? std::string("\"\"") : c.tls_cert; }},
      {"tls-key", "FOOTPOINT_TLS_KEY", "PEM private key of --tls-cert",
       [](ServerConfig& c, const std::string&, const std::string& v) { c.tls_key = v; },
       [](const ServerConfig& c) { return c.tls_key.empty() ? std::string("\"\"") : c.tls_key; }},
      {"api-keys", "FOOTPOINT_API_KEYS",
       "API keys file, NAME SCOPES SHA256HEX per line (\"\": no authentication)",
       [](ServerConfig& c, const std::string&, const std::string& v) { c.api_keys = v; },
       [](const ServerConfig& c) { return c.api_keys.empty() ? std::string("\"\"") : c.api_keys; }},
      {"metrics-key-free", "FOOTPOINT_METRICS_KEY_FREE", "on: /metrics needs no key (off: the admin scope)",
       [](ServerConfig& c, const std::string& n, const std::string& v) {
         if (v != "on" && v != "off") throw ConfigError(n + ": expected on or off, got '" + v + "'");
         c.metrics_key_free = v == "on";
       },
       [](const ServerConfig& c) { return std::string(c.metrics_key_free ? "on" : "off"); }, true},
      {"rate-limit", "FOOTPOINT_RATE_LIMIT", "points a second per API key (0: no limit)",
       [](ServerConfig& c, const std::string& n, const std::string& v) {
         c.rate_limit = parse_integer<std::size_t>(n, v, 0, kMaxSize);
       },
       [](const ServerConfig& c) { return std::to_string(c.rate_limit); }},
      {"rate-burst", "FOOTPOINT_RATE_BURST",
       "points a key may use at once above its rate (0: the larger of rate-limit and max-points)",
       [](ServerConfig& c, const std::string& n, const std::string& v) {
         c.rate_burst = parse_integer<std::size_t>(n, v, 0, kMaxSize);
       },
       [](const ServerConfig& c) { return std::to_string(c.rate_burst); }},
  };
  return table;
}

const Setting* find_flag(const std::string& flag) {
  for (const auto& s : settings())
    if (s.flag && flag == s.flag) return &s;
  return nullptr;
}

}  // namespace

ServerConfig load_config(int argc, const char* const* argv,
                         const std::function<const char*(const char*)>& env, bool& help) {
  ServerConfig config;
  help = false;
  for (const auto& s : settings())
    if (const char* value = env ? env(s.env) : nullptr) s.set(config, s.env, value);
  for (int i = 1; i < argc; ++i) {
    std::string arg = argv[i];
    if (arg == "--help" || arg == "-h") {
      help = true;
      continue;
    }
    if (arg.rfind("--", 0) != 0) throw ConfigError("unexpected argument '" + arg + "'");
    std::string name = arg.substr(2), value;
    bool has_value = false;
    if (const auto eq = name.find('='); eq != std::string::npos) {
      value = name.substr(eq + 1);
      name.resize(eq);
      has_value = true;
    }
    const Setting* s = find_flag(name);
    if (!s) throw ConfigError("unknown flag --" + name + " (see --help)");
    if (!has_value && s->switch_flag) {
      value = "on";
    } else if (!has_value) {
      if (i + 1 >= argc) throw ConfigError("--" + name + " needs a value");
      value = argv[++i];
    }
    s->set(config, "--" + name, value);
  }
  if (config.effective_max_inflight() > config.connection_threads)
    throw ConfigError("--max-inflight must not exceed --connection-threads");
  if (config.probe_port != 0 && config.probe_port == config.port)
    throw ConfigError("--probe-port must differ from --port");
  if (config.tls_cert.empty() != config.tls_key.empty())
    throw ConfigError("--tls-cert and --tls-key go together (HTTPS), or neither (plain HTTP)");
  if (!config.registry_password_file.empty()) {
    if (!config.registry_password.empty())
      throw ConfigError("set FOOTPOINT_REGISTRY_PASSWORD or --registry-password-file, not both");
    std::ifstream in(config.registry_password_file, std::ios::binary);
    if (!in) throw ConfigError("--registry-password-file: cannot read " + config.registry_password_file);
    std::getline(in, config.registry_password, '\0');
    if (!config.registry_password.empty() && config.registry_password.back() == '\n')
      config.registry_password.pop_back();
    if (!config.registry_password.empty() && config.registry_password.back() == '\r')
      config.registry_password.pop_back();
  }
  return config;
}

std::vector<std::string> unknown_environment(const char* const* environment) {
  std::vector<std::string> unknown;
  for (const char* const* e = environment; e && *e; ++e) {
    const std::string_view entry(*e);
    if (entry.rfind("FOOTPOINT_", 0) != 0) continue;
    const std::string name(entry.substr(0, entry.find('=')));
    const auto& all = settings();
    if (std::none_of(all.begin(), all.end(), [&](const Setting& s) { return name == s.env; }))
      unknown.push_back(name);
  }
  return unknown;
}

std::size_t ServerConfig::effective_max_inflight_bytes(std::size_t memory_limit) const {
  if (max_inflight_bytes) return max_inflight_bytes;
  if (memory_limit == 0) return kDefaultInflightBytes;
  const std::size_t held = cache_bytes + effective_max_geometry_bytes() + kBaselineBytes;
  return std::max(memory_limit > held ? memory_limit - held : 0, kMinInflightBytes);
}

std::size_t cgroup_memory_limit(const std::string& root) {
  for (const char* file : {"/memory.max", "/memory/memory.limit_in_bytes"}) {
    std::ifstream in(root + file);
    std::string text;
    if (!(in >> text)) continue;
    if (text == "max") return 0;
    std::size_t value = 0;
    const auto r = std::from_chars(text.data(), text.data() + text.size(), value);
    // cgroup v1 writes a huge page-rounded number for "no limit"
    if (r.ec == std::errc() && value < (std::size_t{1} << 60)) return value;
    return 0;
  }
  return 0;
}

std::string usage() {
  const ServerConfig defaults;
  std::string text =
      "usage: footpoint-server [--flag value | --flag=value]...\n"
      "       footpoint-server --version | --help\n\n";
  for (const auto& s : settings()) {
    std::string line = s.flag ? std::string("  --") + s.flag : std::string("  (no flag)");
    line.resize(std::max<std::size_t>(line.size() + 1, 24), ' ');
    line += std::string(s.env);
    line.resize(std::max<std::size_t>(line.size() + 1, 56), ' ');
    line += std::string(s.help) + " (default " + s.show(defaults) + ")\n";
    text += line;
  }
  return text;
}

std::string effective_settings_json(const ServerConfig& config) {
  ServerConfig effective = config;
  if (effective.threads == 0) effective.threads = default_threads();
  effective.max_inflight = config.effective_max_inflight();
  effective.max_geometry_bytes = config.effective_max_geometry_bytes();
  effective.max_inflight_bytes = config.effective_max_inflight_bytes(0);
  if (effective.rate_limit > 0) effective.rate_burst = config.effective_rate_burst();
  if (effective.compile_deadline.count() == 0) effective.compile_deadline = effective.deadline;
  JsonWriter w;
  w.begin_object();
  for (const auto& s : settings()) {
    if (!s.flag) continue;  // the password
    w.key(s.flag);
    const std::string value = s.show(effective);
    const bool number = !value.empty() && value.find_first_not_of("0123456789.") == std::string::npos &&
                        std::count(value.begin(), value.end(), '.') <= 1 && value.front() != '.' &&
                        value.back() != '.';
    if (number)
      w.raw(value);
    else
      w.string(value == "\"\"" ? std::string() : value);
  }
  w.end_object();
  return w.take();
}

int configure_from_command_line(int argc, const char* const* argv, const char* program,
                                ServerConfig& config) {
  for (int i = 1; i < argc; ++i)
    if (std::string_view(argv[i]) == "--version") {
      std::printf("footpoint-server %.*s\n", static_cast<int>(kVersion.size()), kVersion.data());
      return 0;
    }
  try {
    bool help = false;
    config = load_config(
        argc, argv, [](const char* name) { return std::getenv(name); }, help);
    if (help) {
      std::fputs(usage().c_str(), stdout);
      return 0;
    }
    // The server process reads its container's memory limit once, here.
    config.max_inflight_bytes = config.effective_max_inflight_bytes(cgroup_memory_limit());
  } catch (const ConfigError& e) {
    std::fprintf(stderr, "%s: %s\n", program, e.what());
    return 2;
  }
  return -1;
}

}  // namespace footpoint::server
