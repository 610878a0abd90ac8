// Structured logs: one JSON object per line on stdout,
//   {"ts":"2024-01-01T12:00:00.123456Z","level":"info","msg":"request","request_id":"…",…}
// written by an asynchronous spdlog logger (the request threads only enqueue), and the request
// ids that tie a log line to a client's request (X-Request-Id, honoured or generated).
#pragma once
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

// One log line with the given message and string fields.
void log_event(spdlog::level::level_enum level, std::string_view msg,
               std::initializer_list<std::pair<std::string_view, std::string_view>> fields = {});

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
  std::size_t points = 0;
  std::size_t body_bytes = 0;
  double duration_ms = 0.0;
};
// The one line logged per request.
void log_request(const RequestRecord& record);

}  // namespace footpoint::server
