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
  // The pool sizes grains by time (batch/thread_pool.hpp); this caps them so that a batch still
  // splits into several grains per worker (balance at its end) when its points are cheap.
  const std::size_t max_grain = std::clamp<std::size_t>(request.count / (8 * pool.size() + 1), 16, 1024);
  JobOptions job;
  job.tenant = request.tenant;
  job.cancelled = request.cancelled;
  const auto project_grain = [&](std::size_t begin, std::size_t end) {
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
  };
  const std::size_t done = pool.parallel_for(request.count, max_grain, project_grain, job);
  if (done < request.count) throw BatchCancelled(done, request.count - done);
  return results;
}

}  // namespace footpoint
