#include "project_stream.hpp"

#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include "api_error.hpp"
#include "batch/batch.hpp"
#include "batch/deviation.hpp"
#include "request_log.hpp"
#include "result_json.hpp"

namespace footpoint::server {

AnswerFormat answer_format(std::string_view accept) {
  while (!accept.empty()) {
    const auto comma = accept.find(',');
    std::string_view item = accept.substr(0, comma);
    item = item.substr(0, item.find(';'));
    while (!item.empty() && (item.front() == ' ' || item.front() == '\t')) item.remove_prefix(1);
    while (!item.empty() && (item.back() == ' ' || item.back() == '\t')) item.remove_suffix(1);
    if (item == "application/x-ndjson") return AnswerFormat::ndjson;
    if (item == "application/octet-stream") return AnswerFormat::binary;
    if (!item.empty()) return AnswerFormat::json;
    accept = comma == std::string_view::npos ? std::string_view() : accept.substr(comma + 1);
  }
  return AnswerFormat::json;
}

namespace {

// Answers one window of points: the results as NDJSON lines or binary records appended to out.
void answer_window(const ProjectStream& stream, const BatchRequest& batch, BatchStats& stats,
                   DeviationAccumulator& deviation, std::string& out) {
  const std::vector<ProjectionResult> results = project_batch(*stream.pool, batch);
  std::array<std::uint64_t, Metrics::kStatusCount> by_status{};
  for (const ProjectionResult& r : results) {
    Status status;
    if (stream.format == AnswerFormat::binary) {
      status = append_record(out, r, stream.layout);
    } else {
      status = append_result(out, r, stream.request.fields);
      out += '\n';
      deviation.add(r);
    }
    ++by_status[static_cast<std::size_t>(status)];
    ++stats.by_status[static_cast<std::size_t>(status)];
  }
  if (stream.metrics) stream.metrics->add_projections(by_status);
}

}  // namespace

bool run_stream(const ProjectStream& stream, const std::function<bool(std::string_view)>& write) {
  const auto start = std::chrono::steady_clock::now();
  const ProjectRequest& request = stream.request;
  const int dim = stream.geometry->point_dim();
  StreamedBody* body = stream.body.get();
  if (body) body->open();
  // the reader is done before the HTTP layer goes on with the connection
  struct StopReader {
    StreamedBody* body;
    ~StopReader() {
      if (body) body->stop();
    }
  } stop_reader{body};
  // the body's reader knows when the answer is being written, in pieces (streamed_body.hpp)
  auto send = [&](std::string_view piece) {
    if (!body) return write(piece);
    for (std::size_t at = 0; at < piece.size(); at += StreamedBody::kWritePiece) {
      body->writing(true);
      const bool sent = write(piece.substr(at, StreamedBody::kWritePiece));
      body->writing(false);
      if (!sent) return false;
    }
    return true;
  };
  // A window's answer that could not be written: where the client has closed its connection (it
  // left while the answer was on its way rather than between grains), the points after the window
  // are cancelled as when its leaving is seen between grains.
  auto window_unsent = [&](std::size_t done) {
    if (stream.client_gone && stream.client_gone()) {
      const std::size_t dropped = request.count - done;
      if (stream.metrics) stream.metrics->add_cancelled(dropped);
      log_event(spdlog::level::info, "stream cancelled: the client closed the connection",
                {{"points", request.count}, {"done", done}, {"dropped", dropped}});
    }
    return false;
  };
  std::vector<double> window_points;
  std::string raw;
  BatchStats stats;
  stats.points = request.count;
  DeviationAccumulator deviation(request.deviation);
  std::string out;
  std::size_t window = kFirstStreamWindow;
  for (std::size_t begin = 0; begin < request.count;
       begin += window, window = std::min(2 * window, kStreamWindow)) {
    std::size_t count = std::min(request.count, begin + window) - begin;
    BatchRequest batch{stream.method};
    batch.options = request.options;
    std::optional<ApiError> bad;
    if (body) {
      const std::size_t taken = body->take(count, raw);
      window_points.resize(taken * static_cast<std::size_t>(dim));
      decode_points(request, raw.data(), taken, window_points.data());
      const std::size_t finite = first_not_finite(request, window_points.data(), taken);
      if (finite < taken) {
        try {
          check_finite(request, begin, window_points.data(), taken);
        } catch (const ApiError& e) {
          bad = e;
        }
      } else if (taken < count) {
        // the body ended short: answer what arrived, then cut
        bad = body_incomplete(body->bytes_read(), request.count * binary_record_bytes(request, dim));
      }
      count = finite;
      batch.points = window_points.data();
    } else {
      batch.points = request.coords.data() + begin * static_cast<std::size_t>(dim);
    }
    batch.count = count;
    if (!request.initials.empty())
      batch.initials.assign(request.initials.begin() + static_cast<std::ptrdiff_t>(begin),
                            request.initials.begin() + static_cast<std::ptrdiff_t>(begin + count));
    batch.deadline = stream.deadline;
    batch.tenant = stream.tenant;
    batch.cancelled = stream.client_gone;
    out.clear();
    try {
      if (stream.client_gone && stream.client_gone()) throw BatchCancelled(0, count);
      if (count > 0) answer_window(stream, batch, stats, deviation, out);
    } catch (const BatchCancelled& cancelled) {
      const std::size_t dropped = request.count - begin - cancelled.done();
      if (stream.metrics) stream.metrics->add_cancelled(dropped);
      log_event(spdlog::level::info, "stream cancelled: the client closed the connection",
                {{"points", request.count}, {"done", begin + cancelled.done()}, {"dropped", dropped}});
      return false;
    }
    if (!out.empty() && !send(out)) return window_unsent(begin + count);
    if (bad) {
      if (bad->code == "body_incomplete") return false;
      // NDJSON has a line for the error, binary records none: cut. The rest of the body is read
      // and dropped either way: the connection then carries the next request, or closes with
      // nothing unread (which would reset it, and could lose the answer's last bytes on their way).
      if (stream.format == AnswerFormat::binary) {
        body->drain();
        return false;
      }
      if (!send(error_body(*bad) + "\n")) return false;
      return body->drain();
    }
  }
  if (stream.format == AnswerFormat::ndjson) {
    stats.elapsed_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    stats.deviation = deviation.stats();
    out = "{\"geometry_id\":\"" + stream.geometry->id() + "\",\"stats\":";
    append_stats(out, stats, request.deviation);
    out += "}\n";
    if (!send(out)) return false;
  }
  return true;
}

}  // namespace footpoint::server
