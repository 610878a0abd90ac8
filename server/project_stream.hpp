// Streamed answers of a projection (Accept: application/x-ndjson or application/octet-stream):
// the points are projected a window at a time on the core's thread pool (project_batch, the
// deadline of the request for every window), and each window's answers are written before the
// next is started, so the memory held is one window's, whatever the number of points. Points
// sent in binary are read from the connection as they are answered (StreamedBody), JSON ones
// were parsed whole. NDJSON: one result per line, in order, then a last line {"geometry_id",
// "stats"}; binary: one fixed-size record per point (result_binary.hpp), no statistics. A write
// that fails (the client is gone) stops the work.
//
// A binary body found bad once the answer has started (a NaN or infinite coordinate beyond the
// first window, which the handler checks before the status line): the points before it are
// answered; NDJSON then ends with the line {"error": {...}} (400 number_out_of_range naming the
// point) in place of the stats, the rest of the body is read and dropped; binary records have no
// room for an error, so the answer is cut (no last chunk, the connection closes). A body that
// stops before its Content-Length (the client sent nothing for --io-timeout-s) cuts the answer
// after the last whole point that arrived; a client that closes its side is gone: the stream asks
// its connection before each grain (client_gone below) and httplib stops writing to a socket
// whose peer closed, so its answer stops there.
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
#include "streamed_body.hpp"

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
  std::shared_ptr<StreamedBody> body;  // binary points still being read (else request.coords)
  AnswerFormat format = AnswerFormat::ndjson;
  BinaryLayout layout;  // binary
  std::chrono::steady_clock::time_point deadline;
  ThreadPool* pool = nullptr;
  std::string tenant;  // the pool's fair queue (BatchRequest::tenant): the API key's name
  Metrics* metrics = nullptr;
  // Whether the client has closed its connection (Caller::client_gone): asked before each window
  // and between the grains of a window (BatchRequest::cancelled), so that a client gone while no
  // write is due stops the work within a grain; its points not started are counted as cancelled
  // (footpoint_batches_cancelled_total, footpoint_points_cancelled_total). Empty: only a failed
  // write stops the stream.
  std::function<bool()> client_gone;
};

// The most points a stream solves at once, and its first window (small, for the first answers to
// leave soon; the windows then double up to the most). A binary body's first kStreamWindow points
// are read and checked before the answer starts; kStreamAhead windows of it at most wait unread
// for a client that reads as it sends (streamed_body.hpp).
inline constexpr std::size_t kStreamWindow = 8192, kFirstStreamWindow = 256, kStreamAhead = 4;

// Projects and writes every point of the stream with `write` (false: the client is gone); false
// when it stopped early.
bool run_stream(const ProjectStream& stream, const std::function<bool(std::string_view)>& write);

}  // namespace footpoint::server
