#include "project_stream.hpp"

#include <algorithm>
#include <string>
#include <vector>

#include "batch/batch.hpp"
#include "batch/deviation.hpp"
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

bool run_stream(const ProjectStream& stream, const std::function<bool(std::string_view)>& write) {
  const auto start = std::chrono::steady_clock::now();
  const ProjectRequest& request = stream.request;
  const int dim = stream.geometry->point_dim();
  const bool raw = request.coords.empty();
  std::vector<double> window_points;
  BatchStats stats;
  stats.points = request.count;
  DeviationAccumulator deviation;
  std::string out;
  std::size_t window = kFirstStreamWindow;
  for (std::size_t begin = 0; begin < request.count;
       begin += window, window = std::min(2 * window, kStreamWindow)) {
    const std::size_t end = std::min(request.count, begin + window);
    BatchRequest batch{stream.method};
    batch.options = request.options;
    if (raw) {
      window_points.resize((end - begin) * static_cast<std::size_t>(dim));
      decode_points(request, begin, end, window_points.data());
      batch.points = window_points.data();
    } else {
      batch.points = request.coords.data() + begin * static_cast<std::size_t>(dim);
    }
    batch.count = end - begin;
    if (!request.initials.empty())
      batch.initials.assign(request.initials.begin() + static_cast<std::ptrdiff_t>(begin),
                            request.initials.begin() + static_cast<std::ptrdiff_t>(end));
    batch.deadline = stream.deadline;
    batch.tenant = stream.tenant;
    const std::vector<ProjectionResult> results = project_batch(*stream.pool, batch);

    out.clear();
    std::array<std::uint64_t, Metrics::kStatusCount> by_status{};
    for (const ProjectionResult& r : results) {
      Status status;
      if (stream.format == AnswerFormat::binary) {
        status = append_record(out, r, stream.layout);
      } else {
        status = append_result(out, r, request.fields);
        out += '\n';
        deviation.add(r);
      }
      ++by_status[static_cast<std::size_t>(status)];
      ++stats.by_status[static_cast<std::size_t>(status)];
    }
    if (stream.metrics) stream.metrics->add_projections(by_status);
    if (!write(out)) return false;
  }
  if (stream.format == AnswerFormat::ndjson) {
    stats.elapsed_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    stats.deviation = deviation.stats(request.deviation);
    out = "{\"geometry_id\":\"" + stream.geometry->id() + "\",\"stats\":";
    append_stats(out, stats, request.deviation);
    out += "}\n";
    if (!write(out)) return false;
  }
  return true;
}

}  // namespace footpoint::server
