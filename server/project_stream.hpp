// Streamed answers of a projection (Accept: application/x-ndjson or application/octet-stream):
// the points are projected a window at a time on the core's thread pool (project_batch, the
// deadline of the request for every window), and each window's answers are written before the
// next is started, so the memory held is one window's, whatever the number of points. NDJSON:
// one result per line, in order, then a last line {"geometry_id", "stats"}; binary: one
// fixed-size record per point (result_binary.hpp), no statistics. A write that fails (the
// client is gone) stops the work.
#pragma once
#include <chrono>
#include <functional>
#include <memory>
#include <string>
#include <string_view>

#include "batch/thread_pool.hpp"
#include "compiled/compiled_geometry.hpp"
#include "metrics.hpp"
#include "project_request.hpp"
#include "result_binary.hpp"

namespace footpoint::server {

enum class AnswerFormat { json, ndjson, binary };
// The answer's format by the Accept header: the first of application/x-ndjson,
// application/octet-stream and anything else (JSON) it lists.
AnswerFormat answer_format(std::string_view accept);

struct ProjectStream {
  ProjectStream(std::shared_ptr<const CompiledGeometry> g, GeometryMethod m)
      : geometry(std::move(g)), method(m) {}
  std::shared_ptr<const CompiledGeometry> geometry;  // keeps `method` valid
  GeometryMethod method;
  ProjectRequest request;
  AnswerFormat format = AnswerFormat::ndjson;
  BinaryLayout layout;  // binary
  std::chrono::steady_clock::time_point deadline;
  ThreadPool* pool = nullptr;
  std::string tenant;  // the pool's fair queue (BatchRequest::tenant): the API key's name
  Metrics* metrics = nullptr;
};

// The most points a stream holds at once, and its first window (small, for the first answers to
// leave soon; the windows then double up to the most).
inline constexpr std::size_t kStreamWindow = 8192, kFirstStreamWindow = 256;

// Projects and writes every point of the stream with `write` (false: the client is gone); false
// when it stopped early.
bool run_stream(const ProjectStream& stream, const std::function<bool(std::string_view)>& write);

}  // namespace footpoint::server
