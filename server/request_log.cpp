#include "request_log.hpp"

#include <cmath>
#include <cstdint>
#include <mutex>
#include <random>

#include <spdlog/async.h>
#include <spdlog/pattern_formatter.h>
#include <spdlog/sinks/stdout_sinks.h>
#include <spdlog/spdlog.h>

#include "json_writer.hpp"

namespace footpoint::server {

namespace {

// The members after "ts" and "level": the formatter writes `{"ts":…,"level":…,` + message + `}`.
std::string members(std::string_view msg,
                    std::initializer_list<std::pair<std::string_view, LogValue>> fields) {
  std::string s = "\"msg\":";
  append_json_string(s, msg);
  for (const auto& [key, value] : fields) {
    s += ',';
    append_json_string(s, key);
    s += ':';
    value.append_to(s);
  }
  return s;
}

// Milliseconds to the microsecond: what a request's duration means at the clock's resolution
// of the work it measures.
double to_microseconds(double ms) { return std::round(ms * 1e3) / 1e3; }

}  // namespace

void init_logging(const std::string& level) {
  static std::once_flag once;
  std::call_once(once, [] {
    // A bounded queue drained by one thread; a full queue makes the request thread wait rather
    // than drop lines.
    spdlog::init_thread_pool(16384, 1);
    auto sink = std::make_shared<spdlog::sinks::stdout_sink_mt>();
    auto logger = std::make_shared<spdlog::async_logger>("footpoint", sink, spdlog::thread_pool(),
                                                         spdlog::async_overflow_policy::block);
    logger->set_formatter(std::make_unique<spdlog::pattern_formatter>(
        R"({"ts":"%Y-%m-%dT%H:%M:%S.%fZ","level":"%l",%v})", spdlog::pattern_time_type::utc));
    spdlog::set_default_logger(logger);
  });
  spdlog::set_level(spdlog::level::from_str(level));
}

LogValue::LogValue(double x) {
  if (std::isfinite(x))
    append_shortest(text_, x);
  else
    text_ = "null";
}

void LogValue::append_to(std::string& out) const {
  if (quoted_)
    append_json_string(out, text_);
  else
    out += text_;
}

void log_event(spdlog::level::level_enum level, std::string_view msg,
               std::initializer_list<std::pair<std::string_view, LogValue>> fields) {
  if (!spdlog::should_log(level)) return;
  spdlog::log(level, "{}", members(msg, fields));
}

bool acceptable_request_id(std::string_view id) {
  if (id.empty() || id.size() > 128) return false;
  for (char c : id)
    if (c < 0x21 || c > 0x7E) return false;
  return true;
}

std::string make_request_id() {
  thread_local std::mt19937_64 rng{std::random_device{}()};
  static constexpr char hex[] = "0123456789abcdef";
  std::uint64_t x = rng();
  std::string id(16, '0');
  for (auto& c : id) {
    c = hex[x & 15];
    x >>= 4;
  }
  return id;
}

void log_request(const RequestRecord& r) {
  if (!spdlog::should_log(spdlog::level::info)) return;
  std::string s = "\"msg\":\"request\",\"request_id\":";
  append_json_string(s, r.request_id);
  s += ",\"method\":";
  append_json_string(s, r.method);
  s += ",\"path\":";
  append_json_string(s, r.path.substr(0, 256));
  s += ",\"route\":";
  append_json_string(s, r.route);
  s += ",\"status\":" + std::to_string(r.status);
  if (!r.code.empty()) {
    s += ",\"code\":";
    append_json_string(s, r.code);
  }
  s += ",\"points\":" + std::to_string(r.points);
  s += ",\"body_bytes\":" + std::to_string(r.body_bytes);
  s += ",\"duration_ms\":";
  append_shortest(s, to_microseconds(r.duration_ms));
  if (!r.key.empty()) {
    s += ",\"key\":";
    append_json_string(s, r.key);
  }
  s += ",\"remote\":";
  append_json_string(s, r.remote_addr);
  spdlog::info("{}", s);
}

}  // namespace footpoint::server
