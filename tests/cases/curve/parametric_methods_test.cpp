// The local methods of parametric curves: `newton` and `curvature_circle` ([GSA]
// Section 3, Hu-Wallner). From the nearest sample they converge to the nearest point for the
// reference points of tests/data/curve_parametric_cases.json that are interior minima; from a
// given start to the stationary point of that start's basin (or outside_domain).
#include <doctest/doctest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "compiled/parametric_curve_geometry.hpp"

using namespace footpoint;
using nlohmann::json;

namespace {

std::shared_ptr<const CompiledGeometry> parametric_curve(const char* x, const char* y, const char* z,
                                                         double t0, double t1) {
  GeometryDefinition def;
  def.type = GeometryType::parametric_curve;
  def.formulas = {{"x", x}, {"y", y}};
  if (z) def.formulas.push_back({"z", z});
  def.domain = {{"t", {t0, t1}}};
  return compile_parametric_curve(def, {});
}

}  // namespace

TEST_CASE("newton and curvature_circle reach the oracle's interior nearest points from the nearest sample") {
  std::ifstream in(std::string(FOOTPOINT_TESTS_DIR) + "/data/curve_parametric_cases.json");
  REQUIRE(in.good());
  const json data = json::parse(in);
  for (const json& c : data["cases"]) {
    const json& f = c["formulas"];
    const std::string z = f.contains("z") ? f["z"].get<std::string>() : "";
    const auto g =
        parametric_curve(f["x"].get<std::string>().c_str(), f["y"].get<std::string>().c_str(),
                         z.empty() ? nullptr : z.c_str(), c["domain"]["t"][0], c["domain"]["t"][1]);
    int k = 0;
    for (const json& pt : c["points"]) {
      CAPTURE(c["id"].get<std::string>());
      CAPTURE(k++);
      if (pt["type"] != "interior" || pt["ambiguous"].get<bool>()) continue;
      double p[3] = {0.0, 0.0, 0.0};
      for (int i = 0; i < g->point_dim(); ++i) p[i] = pt["p"][i];
      for (const char* method : {"newton", "curvature_circle"}) {
        CAPTURE(method);
        const ProjectionResult r = g->project(p, method, {}).value();
        CHECK(r.summary.status == Status::converged);
        CHECK(r.summary.orthogonality[0] <= 1e-12);
        CHECK(std::fabs(r.distance - pt["distance"].get<double>()) <= 1e-12 * pt["distance"].get<double>());
        CHECK(std::fabs(r.params[0] - pt["params"][0].get<double>()) <= 1e-9);
      }
    }
  }
}

TEST_CASE("newton and curvature_circle from a given start") {
  // The planar ellipse (3 cos t, 2 sin t): from p = (0.5, 0.3) the distance has minima near
  // t = 1.30 (the nearest, d = 1.655) and t = -1.84 + 2 pi; starting at t = 4.5 both methods go to
  // the far one, an orthogonal point that is not the nearest.
  const auto g = parametric_curve("3*cos(t)", "2*sin(t)", nullptr, 0.0, 6.283185307179586);
  const double p[2] = {0.5, 0.3};
  Options o;
  o.initial = std::array<double, 3>{4.5, 0.0, 0.0};
  const ProjectionResult nearest = g->project(p, "auto", {}).value();
  for (const char* method : {"newton", "curvature_circle"}) {
    CAPTURE(method);
    const ProjectionResult r = g->project(p, method, o).value();
    REQUIRE(r.summary.status == Status::converged);
    CHECK(r.summary.orthogonality[0] <= 1e-12);
    CHECK(r.params[0] > 4.0);
    CHECK(r.distance > nearest.distance + 0.1);
    CHECK(r.dim == 2);
    CHECK(r.num_params == 1);
  }
  // Newton from a start beyond the end of an arc converges outside [tmin, tmax] and says so.
  const auto arc = parametric_curve("t", "t^2", nullptr, -1.0, 2.0);
  const double q[2] = {3.0, 9.5};  // nearest on the full parabola near t = 3.06, beyond tmax = 2
  o.initial = std::array<double, 3>{3.0, 0.0, 0.0};
  const ProjectionResult r = arc->project(q, "newton", o).value();
  CHECK(r.summary.status == Status::outside_domain);
  CHECK(r.params[0] > 2.0);
  // auto answers the endpoint c(2) = (2, 4) with the first-order condition there.
  const ProjectionResult a = arc->project(q, "auto", {}).value();
  CHECK(a.summary.status == Status::converged);
  CHECK(a.summary.location == Location::endpoint);
  CHECK(a.summary.on_boundary);
  CHECK(a.params[0] == 2.0);
}

TEST_CASE("curvature_circle and newton agree on the helix and trace their increments") {
  // [GSA] Remark 2 expects order 1 when p is off the curve; on the helix the osculating
  // circle fits so well that the increments still fall fast (4.0e-1, 4.6e-3, 7.7e-7, 2.2e-14).
  const auto g = parametric_curve("cos(t)", "sin(t)", "0.2*t", 0.0, 12.566370614359172);
  const double p[3] = {1.5, 0.3, 0.7};
  Options o;
  o.initial = std::array<double, 3>{6.0, 0.0, 0.0};
  o.trace = true;
  const ProjectionResult n = g->project(p, "newton", o).value();
  const ProjectionResult c = g->project(p, "curvature_circle", o).value();
  REQUIRE(n.summary.status == Status::converged);
  REQUIRE(c.summary.status == Status::converged);
  CHECK(std::fabs(n.params[0] - c.params[0]) <= 1e-12);
  CHECK(n.trace.size() == static_cast<std::size_t>(n.summary.iterations));
  CHECK(c.trace.size() == static_cast<std::size_t>(c.summary.iterations));
  CHECK(n.summary.iterations <= 8);
  CHECK(c.summary.iterations <= 8);
  CHECK(std::fabs(c.trace[1][0]) <= 1e-2);
  CHECK(std::fabs(c.trace[2][0]) <= 1e-5);
}
