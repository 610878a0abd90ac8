// `auto` on a parametric curve whose nearest point is a kink of its formulas (parametric/solvers/
// kink_minimum.hpp, its curves): converged, location kink, residual 0, the kink's parameter to its last bit.
// References in closed form: (t, |t|) from (0, -1/2) is nearest at its corner t = 0, 1/2 away;
// (t, max(t, -t/2)) from (0, -1) at its corner, 1 away; the curve (t, -|t|) has its corner 1/2
// from (0, -1/2) but its nearest points at t = ±1/4, √2/4 away (a kink that is a maximum of the
// distance is no answer).
#include <doctest/doctest.h>

#include <cmath>

#include "compiled/compiled_geometry.hpp"

using namespace footpoint;

namespace {

std::shared_ptr<const CompiledGeometry> plane_curve(const char* x, const char* y, double tmin, double tmax) {
  GeometryDefinition def;
  def.type = GeometryType::parametric_curve;
  def.formulas = {{"x", x}, {"y", y}};
  def.domain = {{"t", {tmin, tmax}}};
  return compile_geometry(def);
}

ProjectionResult project_point(const CompiledGeometry& g, std::array<double, 3> p) {
  return g.project(p.data(), "auto", Options{}).value();
}

}  // namespace

TEST_CASE("a kink of abs or max that is the nearest point: converged, location kink") {
  struct Case {
    const char *x, *y;
    std::array<double, 3> p;
    double t, distance;
  };
  const Case cases[] = {
      {"t", "abs(t)", {0, -0.5, 0}, 0.0, 0.5},
      {"t", "max(t, -t/2)", {0, -1, 0}, 0.0, 1.0},
      {"t", "abs(t-0.3)", {0.3, -0.25, 0}, 0.3, 0.25},  // the kink at a t with rounding of its own
      {"2*t", "abs(t)+t", {0, -2, 0}, 0.0, 2.0},
  };
  for (const Case& c : cases) {
    INFO(c.x << ", " << c.y);
    const auto g = plane_curve(c.x, c.y, -1, 1);
    REQUIRE(g);
    const ProjectionResult r = project_point(*g, c.p);
    CHECK(r.summary.status == Status::converged);
    CHECK(r.summary.location == Location::kink);
    CHECK(r.summary.residual() == 0.0);
    CHECK(std::abs(r.params[0] - c.t) <= 4e-16);
    CHECK(r.distance == doctest::Approx(c.distance).epsilon(1e-15));
  }
}

TEST_CASE("a kink that is a local maximum of the distance is no answer") {
  const auto g = plane_curve("t", "-abs(t)", -1, 1);
  const ProjectionResult r = project_point(*g, {0, -0.5, 0});
  CHECK(r.summary.status == Status::converged);
  CHECK(r.summary.location == Location::interior);
  CHECK(std::abs(std::abs(r.params[0]) - 0.25) <= 1e-15);
  CHECK(r.distance == doctest::Approx(std::sqrt(2.0) / 4).epsilon(1e-15));
}

TEST_CASE("a smooth minimum stays interior") {
  const auto g = plane_curve("t", "t*t", -1, 1);
  const ProjectionResult r = project_point(*g, {0, -0.5, 0});
  CHECK(r.summary.status == Status::converged);
  CHECK(r.summary.location == Location::interior);
  CHECK(std::abs(r.params[0]) <= 1e-15);
}
