// project_batch (core/batch/batch.hpp): the results come back in the points' order, each the one
// the method gives the point alone; per-point starts reach their point; points not started
// before the deadline get deadline_exceeded; a cancelled batch throws BatchCancelled with the
// points done and dropped; an empty batch is an empty answer. The truth is the circle's closed
// form (the nearest point of the circle |x| = R to p != 0 is R p / |p|, at distance ||p| - R|)
// and the ellipse's two feet on its minor axis.
#include <doctest/doctest.h>

#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <vector>

#include "batch/batch.hpp"
#include "compile_definition.hpp"

using namespace footpoint;

namespace batch_test {

constexpr double kRadius = 2.0;

// The circle of radius 2 as a planar parametric curve, one full turn.
std::shared_ptr<const CompiledGeometry> circle() {
  return test::compile_definition(GeometryType::parametric_curve, {{"x", "2*cos(t)"}, {"y", "2*sin(t)"}},
                                  {{"t", {-3.0, 3.5}}});
}

// n planar points at distinct radii and angles, none at the centre.
std::vector<double> points(std::size_t n) {
  std::vector<double> xy;
  for (std::size_t i = 0; i < n; ++i) {
    const double r = 0.5 + 0.01 * static_cast<double>(i), a = 0.37 * static_cast<double>(i);
    xy.push_back(r * std::cos(a));
    xy.push_back(r * std::sin(a));
  }
  return xy;
}

// n points around the circle, and requests to project them.
struct CircleBatch {
  std::shared_ptr<const CompiledGeometry> geometry = circle();
  std::vector<double> xy;
  explicit CircleBatch(std::size_t n) : xy(points(n)) {}
  BatchRequest request(const char* method) const {
    BatchRequest r(geometry->method(method).value());
    r.points = xy.data();
    r.count = xy.size() / 2;
    return r;
  }
};

}  // namespace batch_test

TEST_CASE("batch: results in the points' order, each the circle's closed-form foot") {
  const std::size_t n = 300;
  const batch_test::CircleBatch batch(n);
  const std::vector<double>& xy = batch.xy;
  for (const unsigned threads : {1u, 2u}) {
    ThreadPool pool(threads);
    const std::vector<ProjectionResult> results = project_batch(pool, batch.request("auto"));
    REQUIRE(results.size() == n);
    for (std::size_t i = 0; i < n; ++i) {
      CAPTURE(i);
      const double x = xy[2 * i], y = xy[2 * i + 1], r = std::hypot(x, y);
      const ProjectionResult& result = results[i];
      CHECK(result.summary.status == Status::converged);
      CHECK(result.dim == 2);
      CHECK(result.distance == doctest::Approx(std::abs(r - batch_test::kRadius)).epsilon(1e-12));
      CHECK(result.foot[0] == doctest::Approx(batch_test::kRadius * x / r).epsilon(1e-12));
      CHECK(result.foot[1] == doctest::Approx(batch_test::kRadius * y / r).epsilon(1e-12));
    }
  }
}

TEST_CASE("batch: each result is the one the method gives the point alone, bit for bit") {
  const std::size_t n = 64;
  const batch_test::CircleBatch circle(n);
  const std::vector<double>& xy = circle.xy;
  ThreadPool pool(2);
  for (const char* name : {"auto", "newton", "curvature_circle"}) {
    CAPTURE(name);
    BatchRequest request = circle.request(name);
    request.options.all_minima = true;
    const GeometryMethod& method = request.method;
    const std::vector<ProjectionResult> batch = project_batch(pool, request);
    REQUIRE(batch.size() == n);
    for (std::size_t i = 0; i < n; ++i) {
      CAPTURE(i);
      const ProjectionResult alone = method.project(&xy[2 * i], request.options);
      CHECK(batch[i].summary.method == name);
      CHECK(batch[i].summary.status == alone.summary.status);
      CHECK(batch[i].summary.iterations == alone.summary.iterations);
      CHECK(batch[i].distance == alone.distance);
      CHECK(batch[i].params[0] == alone.params[0]);
      CHECK(batch[i].foot == alone.foot);
      CHECK(batch[i].minima.size() == alone.minima.size());
    }
  }
}

TEST_CASE("batch: per-point starts lead each local solve to its own foot") {
  // The ellipse (2 cos t, sin t) seen from p = (0, 0.1) has two local minima of the distance on
  // its minor axis: (0, 1) at t = pi/2, distance 0.9, and (0, -1) at t = -pi/2, distance 1.1
  // (d^2(t) = 4 cos^2 t + (sin t - 0.1)^2 has d^2'' = 8 - 2.2 > 0 at -pi/2). Newton from
  // t = 1.4 lands on the first, from t = -1.4 on the second.
  const auto ellipse = test::compile_definition(GeometryType::parametric_curve,
                                                {{"x", "2*cos(t)"}, {"y", "sin(t)"}}, {{"t", {-3.0, 3.0}}});
  const std::size_t n = 40;
  std::vector<double> xy;
  BatchRequest request(ellipse->method("newton").value());
  for (std::size_t i = 0; i < n; ++i) {
    xy.insert(xy.end(), {0.0, 0.1});
    request.initials.push_back({i % 2 == 0 ? 1.4 : -1.4, 0.0, 0.0});
  }
  request.points = xy.data();
  request.count = n;
  ThreadPool pool(2);
  const std::vector<ProjectionResult> results = project_batch(pool, request);
  REQUIRE(results.size() == n);
  for (std::size_t i = 0; i < n; ++i) {
    CAPTURE(i);
    const double side = i % 2 == 0 ? 1.0 : -1.0;
    CHECK(results[i].summary.status == Status::converged);
    CHECK(results[i].params[0] == doctest::Approx(side * std::numbers::pi / 2).epsilon(1e-12));
    CHECK(std::abs(results[i].foot[0]) <= 1e-12);
    CHECK(results[i].foot[1] == doctest::Approx(side).epsilon(1e-12));
    CHECK(results[i].distance == doctest::Approx(i % 2 == 0 ? 0.9 : 1.1).epsilon(1e-12));
  }
}

TEST_CASE("batch: a deadline already passed gives every point deadline_exceeded, unsolved") {
  const std::size_t n = 50;
  const batch_test::CircleBatch circle(n);
  ThreadPool pool(2);
  BatchRequest request = circle.request("newton");
  request.deadline = std::chrono::steady_clock::now() - std::chrono::seconds(1);
  const std::vector<ProjectionResult> late = project_batch(pool, request);
  REQUIRE(late.size() == n);
  for (const ProjectionResult& r : late) {
    CHECK(r.summary.status == Status::deadline_exceeded);
    CHECK(r.summary.method == "newton");
    CHECK(r.summary.starts == 0);
    CHECK(r.dim == 2);
    CHECK(r.num_params == 1);
    CHECK(std::isnan(r.distance));
  }
  // A deadline far ahead stops nothing.
  request.deadline = std::chrono::steady_clock::now() + std::chrono::hours(1);
  for (const ProjectionResult& r : project_batch(pool, request)) CHECK(r.summary.status == Status::converged);
}

TEST_CASE("batch: a cancelled batch throws BatchCancelled with the points done and dropped") {
  const std::size_t n = 200;
  const batch_test::CircleBatch circle(n);
  ThreadPool pool(1);
  BatchRequest request = circle.request("auto");
  std::atomic<int> asked{0};
  request.cancelled = [&] {
    ++asked;
    return true;
  };
  // The pool asks before each grain after the first (batch/thread_pool.hpp): the first grain,
  // kFirstGrain points, runs; the rest are dropped.
  try {
    project_batch(pool, request);
    FAIL("a cancelled batch returned");
  } catch (const BatchCancelled& e) {
    CHECK(e.done() == ThreadPool::kFirstGrain);
    CHECK(e.dropped() == n - ThreadPool::kFirstGrain);
  }
  CHECK(asked >= 1);
  // A batch of one grain is never asked: it completes.
  request.count = ThreadPool::kFirstGrain;
  CHECK(project_batch(pool, request).size() == ThreadPool::kFirstGrain);
  // Never cancelled: every point.
  request.count = n;
  request.cancelled = [] { return false; };
  CHECK(project_batch(pool, request).size() == n);
}

TEST_CASE("batch: an empty batch is an empty answer") {
  const batch_test::CircleBatch circle(0);
  ThreadPool pool(2);
  BatchRequest request = circle.request("auto");
  CHECK(request.count == 0);
  CHECK(project_batch(pool, request).empty());
  request.deadline = std::chrono::steady_clock::now() - std::chrono::seconds(1);
  request.cancelled = [] { return true; };
  CHECK(project_batch(pool, request).empty());
}
