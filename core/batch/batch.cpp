#include "batch/batch.hpp"

#include <algorithm>

namespace footpoint {

namespace {
// Points between two reads of the clock: a read costs a few hundredths of the fastest projections,
// so it is read every kClockStride points; up to kClockStride - 1 more points of a chunk may start
// after the deadline.
constexpr std::size_t kClockStride = 4;
}  // namespace

std::vector<ProjectionResult> project_batch(ThreadPool& pool, const BatchRequest& request) {
  std::vector<ProjectionResult> results(request.count);
  const CompiledGeometry& geometry = request.method.geometry();
  const int dim = geometry.point_dim();
  // Chunks small enough to balance the pool and to check the deadline often, large enough that
  // the per-task overhead stays negligible next to the solves.
  const std::size_t chunk = std::clamp<std::size_t>(request.count / (8 * pool.size() + 1), 16, 1024);
  pool.parallel_for(request.count, chunk, [&](std::size_t begin, std::size_t end) {
    Options options = request.options;
    bool late = false;
    for (std::size_t i = begin; i < end; ++i) {
      ProjectionResult& r = results[i];
      // the clock is read before every kClockStride-th point of a chunk
      if ((i - begin) % kClockStride == 0) late = std::chrono::steady_clock::now() >= request.deadline;
      if (late) {
        r.dim = dim;
        r.num_params = geometry.num_params();
        r.summary.method = request.method.info().name;
        r.summary.status = Status::deadline_exceeded;
        r.summary.starts = 0;
        continue;
      }
      if (!request.initials.empty()) options.initial = request.initials[i];
      r = request.method.project(request.points + i * dim, options);
    }
  });
  return results;
}

}  // namespace footpoint
