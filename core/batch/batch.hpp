// The one entry point for projecting many points: used by the server, the tests and the
// benchmarks alike. Order is kept; points not started before the deadline get deadline_exceeded
// (the clock is read before every fourth point of a chunk, so up to three more points of each
// chunk may start after it).
#pragma once
#include <array>
#include <chrono>
#include <vector>

#include "batch/thread_pool.hpp"
#include "compiled/compiled_geometry.hpp"

namespace footpoint {

struct BatchRequest {
  explicit BatchRequest(GeometryMethod m) : method(m) {}
  GeometryMethod method;           // the geometry and the method that projects its points
  Options options;                 // shared by all points
  const double* points = nullptr;  // count * method.geometry().point_dim() coordinates
  std::size_t count = 0;
  std::vector<std::array<double, 3>> initials;  // empty, or one start per point
  std::chrono::steady_clock::time_point deadline = std::chrono::steady_clock::time_point::max();
};

std::vector<ProjectionResult> project_batch(ThreadPool& pool, const BatchRequest& request);

}  // namespace footpoint
