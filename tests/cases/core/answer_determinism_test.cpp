// An answer depends on the geometry, the point and the options only: not on the points projected
// before it, their order, or the threads of a batch. Surface auto keeps sub-boxes its certificates
// bounded for later points (parametric/seeding/surface_refinement.hpp) and picks one parameter copy of a foot
// on a self-covering parametrisation: both must leave every answer as it would be alone. On the
// [GSA] Example 1 surface over [-25,25]^2 (it covers itself ~16 times), in order, in reverse order
// and as a batch on two threads, each on a fresh compile: the same foot, parameters, distance and
// certificate, bit for bit.
#include <doctest/doctest.h>

#include <random>
#include <vector>

#include "batch/batch.hpp"
#include "batch/thread_pool.hpp"
#include "compiled/compiled_geometry.hpp"
#include "sweep_length.hpp"

using namespace footpoint;

namespace {

std::shared_ptr<const CompiledGeometry> self_covering() {
  GeometryDefinition def;
  def.type = GeometryType::parametric_surface;
  def.formulas = {{"x", "u+v"}, {"y", "sin(u)+2*cos(v)"}, {"z", "sin(u+v)"}};
  def.domain = {{"u", {-25, 25}}, {"v", {-25, 25}}};
  return compile_geometry(def);
}

void check_same(const ProjectionResult& a, const ProjectionResult& b) {
  CHECK(a.params == b.params);
  CHECK(a.foot == b.foot);
  CHECK(a.distance == b.distance);
  CHECK(a.summary.status == b.summary.status);
  CHECK(a.summary.certificate.certified == b.summary.certificate.certified);
  CHECK(a.summary.certificate.lower_bound == b.summary.certificate.lower_bound);
}

}  // namespace

TEST_CASE("answers do not depend on the points before them, their order or the batch's threads") {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> x(-20, 20), y(-3, 3), z(-1.5, 1.5);
  std::vector<double> points;
  for (int i = 0; i < test::sweep_length(40); ++i) points.insert(points.end(), {x(rng), y(rng), z(rng)});
  // and points near the surface, where the certificates bisect most
  const auto reference = self_covering();
  for (int i = 0; i < test::sweep_length(20); ++i) {
    const double u = x(rng), v = x(rng);
    const double q[3] = {u + v, std::sin(u) + 2 * std::cos(v) + 0.01, std::sin(u + v) - 0.01};
    points.insert(points.end(), q, q + 3);
  }
  const std::size_t n = points.size() / 3;
  std::vector<ProjectionResult> in_order;
  for (std::size_t i = 0; i < n; ++i)
    in_order.push_back(reference->project(&points[3 * i], "auto", {}).value());

  const auto reversed = self_covering();
  for (std::size_t k = n; k-- > 0;) {
    INFO("point " << k << " in reverse order");
    check_same(reversed->project(&points[3 * k], "auto", {}).value(), in_order[k]);
  }

  const auto batched = self_covering();
  ThreadPool pool(2);
  BatchRequest request(batched->method("auto").value());
  request.points = points.data();
  request.count = n;
  const std::vector<ProjectionResult> batch = project_batch(pool, request);
  REQUIRE(batch.size() == n);
  for (std::size_t k = 0; k < n; ++k) {
    INFO("point " << k << " in a batch");
    check_same(batch[k], in_order[k]);
  }
}
