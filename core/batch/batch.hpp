// The one entry point for projecting many points: used by the server, the tests and the
// benchmarks alike. Order is kept; points not started before the deadline get deadline_exceeded
// (the clock is read before every fourth point of a chunk, so up to three more points of each
// chunk may start after it).
//
// The points run on the pool as one job (batch/thread_pool.hpp): `tenant` names the queue it waits
// in, and `cancelled`, asked between its grains, stops it (the caller's client went away): the
// points not started are dropped and project_batch throws BatchCancelled.
#pragma once
#include <array>
#include <chrono>
#include <cstddef>
#include <functional>
#include <stdexcept>
#include <string>
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
  std::string tenant;               // the pool's fair queue the points wait in (JobOptions::tenant)
  std::function<bool()> cancelled;  // empty: never (JobOptions::cancelled)
};

// Thrown by project_batch when the request's `cancelled` answered true: no results are returned.
class BatchCancelled : public std::runtime_error {
 public:
  BatchCancelled(std::size_t done, std::size_t dropped)
      : std::runtime_error("batch cancelled"), done_(done), dropped_(dropped) {}
  std::size_t done() const { return done_; }        // points projected before the cancellation
  std::size_t dropped() const { return dropped_; }  // points never started
 private:
  std::size_t done_, dropped_;
};

// Throws BatchCancelled (see above).
std::vector<ProjectionResult> project_batch(ThreadPool& pool, const BatchRequest& request);

}  // namespace footpoint
