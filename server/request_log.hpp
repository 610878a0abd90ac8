// Structured logs: one JSON object per line on stdout,
//   {"ts":"2024-01-01T12:00:00.123456Z","level":"info","msg":"request","request_id":"…",…}
// written by an asynchronous spdlog logger (the request threads only enqueue), and the request
// ids that tie a log line to a client's request (X-Request-Id, honoured or generated).
#pragma once
#include <concepts>
#include <cstddef>
#include <initializer_list>
#include <string>
#include <string_view>
#include <utility>

#include <spdlog/common.h>

namespace footpoint::server {

// Installs the JSON-lines logger as spdlog's default (once per process; later calls only set
// the level). `level`: trace, debug, info, warn, error, critical or off.
void init_logging(const std::string& level);

// A field's value in a log line: a string, a number or a boolean (written as JSON numbers and
// booleans, so that a log query compares them as such), or a JSON text written as it is.
class LogValue {
 public:
  LogValue(std::string_view s) : text_(s), quoted_(true) {}
  LogValue(const char* s) : LogValue(std::string_view(s)) {}
  LogValue(const std::string& s) : LogValue(std::string_view(s)) {}
  template <std::integral T>
  requires(!std::same_as<T, bool>) LogValue(T n) : text_(std::to_string(n)) {}
  LogValue(double x);
  LogValue(bool b) : text_(b ? "true" : "false") {}
  // An already serialized JSON value.
  static LogValue json(std::string text) {
    LogValue v(std::string_view{});
    v.text_ = std::move(text);
    v.quoted_ = false;
    return v;
  }
  void append_to(std::string& out) const;

 private:
  std::string text_;
  bool quoted_ = false;
};

// One log line with the given message and fields.
void log_event(spdlog::level::level_enum level, std::string_view msg,
               std::initializer_list<std::pair<std::string_view, LogValue>> fields = {});

// A client's X-Request-Id is kept when it is 1 to 128 printable ASCII characters.
bool acceptable_request_id(std::string_view id);
// 16 random hex digits.
std::string make_request_id();

struct RequestRecord {
  std::string_view request_id;
  std::string_view method;
  std::string_view path;
  std::string_view route;
  std::string_view remote_addr;
  int status = 0;
  std::string_view code;  // the error's code for a 4xx or 5xx answer ("" otherwise)
  std::size_t points = 0;
  std::size_t body_bytes = 0;
  double duration_ms = 0.0;
  std::string_view key;  // the API key's name ("" without keys: not logged)
};
// The one line logged per request (duration_ms rounded to microseconds; "code" only for errors,
// "key" only for a request that named a known key).
void log_request(const RequestRecord& record);

}  // namespace footpoint::server
