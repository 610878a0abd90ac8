// The planar iteration of [Curve]'s introduction, eq. (2) + foot point (4)
// (`tangent_foot`), on the planar ellipse of tests/data/curve_planar_implicit_cases.json: a
// first-order method that converges to an orthogonal point (the nearest one from these starts).
#include <doctest/doctest.h>

#include <cmath>

#include "compiled/implicit_curve_geometry.hpp"

using namespace footpoint;

namespace {

std::shared_ptr<const CompiledGeometry> ellipse() {
  GeometryDefinition def;
  def.type = GeometryType::implicit_curve;
  def.formulas = {{"equations[0]", "x^2/9+y^2/4-1"}};
  def.domain = {{"x", {-4.0, 4.0}}, {"y", {-4.0, 4.0}}};
  return compile_implicit_curve(def, {});
}

}  // namespace

TEST_CASE("tangent_foot on the ellipse x^2/9 + y^2/4 = 1") {
  const auto g = ellipse();
  // Points and global distances from the oracle (curve_planar_implicit_cases.json, "ellipse").
  const struct {
    double p[2];
    double distance;
  } cases[] = {
      {{4.0, 1.0}, 1.2028406746358147}, {{-1.0, -2.5}, 0.6000998933398485}, {{3.5, -3.5}, 2.500242320321499}};
  for (const auto& c : cases) {
    CAPTURE(c.p[0]);
    Options o;
    o.trace = true;
    const ProjectionResult r = g->project(c.p, "tangent_foot", o).value();
    CHECK(r.summary.status == Status::converged);
    CHECK(r.dim == 2);
    CHECK(r.foot[2] == 0.0);
    CHECK(r.summary.equation_residual[0] <= 1e-12);
    CHECK(r.summary.orthogonality[0] <= 1e-12);
    CHECK(std::fabs(r.distance - c.distance) <= 1e-12 * c.distance);
    CHECK(r.trace.size() == static_cast<std::size_t>(r.summary.iterations));
    // First order: more than a handful of rounds, each increment a fraction of the last.
    CHECK(r.summary.iterations > 5);
  }
}
