// `auto` against reference answers computed independently (tests/tools/gen_reference.py, 50 digits):
// parametric curves (helix, trefoil, planar ellipse, a parabola arc with endpoint answers), planar
// implicit curves (ellipse, cusp and lemniscate singular points, two components, a clipped
// parabola, two circles touching at a tacnode) and spatial curves (Viviani's curve with its double point,
// three circles, Example 1's curve clipped by the box, a helix leaving through the box's z faces), and
// the classes of certified answers (curve_*_certified_cases.json: tiny ovals at a grid corner, on a
// cell's edge and at a cell's centre, tiny loops in 2-D and 3-D, a tacnode y^2 = x^4, an offset
// cusp, circles 1e-3 apart, nearly tangent spheres).
#include <doctest/doctest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "compiled/implicit_curve_geometry.hpp"
#include "compiled/parametric_curve_geometry.hpp"
#include "curve_cases.hpp"

using namespace footpoint;
using nlohmann::json;

namespace {

json load(const std::string& name) {
  std::ifstream in(std::string(FOOTPOINT_TESTS_DIR) + "/data/" + name);
  REQUIRE(in.good());
  return json::parse(in);
}

Location expected_location(const std::string& type) {
  if (type.rfind("endpoint", 0) == 0) return Location::endpoint;
  if (type.rfind("box-face", 0) == 0) return Location::box_face;
  if (type == "singular-point") return Location::singular_point;
  return Location::interior;
}

double dist(const std::array<double, 3>& a, const json& b, int dim) {
  double s = 0.0;
  for (int k = 0; k < dim; ++k)
    s += (a[static_cast<std::size_t>(k)] - b[k].get<double>()) *
         (a[static_cast<std::size_t>(k)] - b[k].get<double>());
  return std::sqrt(s);
}

// `residual`: the orthogonality residual required of the answers (the formulas' rounding sets its
// floor: 1e-12 relative, more for steep ones).
void check_file(const std::string& name, double residual = 1e-12) {
  const json data = load(name);
  for (const json& c : data["cases"]) {
    const std::string id = c["id"];
    const auto g = test::compile_curve_case(c);
    const int dim = g->point_dim();
    int k = 0;
    for (const json& pt : c["points"]) {
      CAPTURE(id);
      CAPTURE(k++);
      double p[3] = {0.0, 0.0, 0.0};
      for (int i = 0; i < dim; ++i) p[i] = pt["p"][i];
      const ProjectionResult r = g->project(p, "auto", {}).value();
      const double ref = pt["distance"];
      CHECK(r.summary.status == Status::converged);
      // The global distance to 1e-12 relative.
      CHECK(std::fabs(r.distance - ref) <= 1e-12 * ref + 1e-15);
      // |p - foot| is the distance.
      double s = 0.0;
      for (int i = 0; i < dim; ++i)
        s += (p[i] - r.foot[static_cast<std::size_t>(i)]) * (p[i] - r.foot[static_cast<std::size_t>(i)]);
      CHECK(std::fabs(std::sqrt(s) - r.distance) <= 1e-14 * (1.0 + r.distance));
      // The foot lies on the curve: residuals, and for parametric curves c(t) = foot with t inside.
      CHECK(r.summary.equation_residual[0] <= 1e-12);
      CHECK(r.summary.equation_residual[1] <= 1e-12);
      CHECK(r.summary.orthogonality[0] <= residual);
      if (g->num_params() == 1) {
        // parametric curves: the certificate holds against the reference and meets the gap
        const Certificate& cert = r.summary.certificate;
        CHECK(cert.computed);
        CHECK(cert.lower_bound <= ref * (1.0 + 0x1p-51));
        CHECK(cert.certified);
        CHECK(r.distance - cert.lower_bound <= std::max(1e-9 * r.distance, cert.absolute_gap));
        const auto* pc = dynamic_cast<const ParametricCurve*>(g.get());
        const double t = r.params[0];
        CHECK(pc->domain().contains(t));
        const Vec3 c_t = pc->formulas().point(t);
        CHECK(norm(c_t - Vec3{r.foot[0], r.foot[1], r.foot[2]}) <= 1e-14 * (1.0 + norm(c_t)));
      }
      if (!pt["ambiguous"].get<bool>()) {
        CHECK(dist(r.foot, pt["foot"], dim) <= 1e-7 * (1.0 + ref));
        // A foot at one of the oracle's singular points is one (the oracle may call the touching
        // point of two branches, a tacnode, regular: it is a regular point of either branch).
        bool at_singular = false;
        if (c.contains("curve_info"))
          for (const json& sp : c["curve_info"]["singular_points"])
            at_singular = at_singular || dist(r.foot, sp, dim) <= 1e-6;
        if (at_singular)
          CHECK(r.summary.location == Location::singular_point);
        else
          CHECK(r.summary.location == expected_location(pt["type"]));
      }
    }
  }
}

// Every local minimum the oracle lists is among those all_minima returns, best first.
void check_all_minima(const std::string& name) {
  const json data = load(name);
  for (const json& c : data["cases"]) {
    const std::string id = c["id"];
    const auto g = test::compile_curve_case(c);
    const int dim = g->point_dim();
    Options o;
    o.all_minima = true;
    int k = 0;
    for (const json& pt : c["points"]) {
      CAPTURE(id);
      CAPTURE(k++);
      if (pt["ambiguous"].get<bool>()) continue;
      double p[3] = {0.0, 0.0, 0.0};
      for (int i = 0; i < dim; ++i) p[i] = pt["p"][i];
      const ProjectionResult r = g->project(p, "auto", o).value();
      REQUIRE(!r.minima.empty());
      CHECK(std::fabs(r.minima.front().distance - pt["distance"].get<double>()) <=
            1e-12 * r.distance + 1e-15);
      for (std::size_t i = 1; i < r.minima.size(); ++i)
        CHECK(r.minima[i - 1].distance <= r.minima[i].distance);
      for (const json& m : pt["local_minima"]) {
        const double d = m["distance"];
        bool found = false;
        for (const Minimum& mine : r.minima)
          found = found || std::fabs(mine.distance - d) <= 1e-9 * (1.0 + d);
        CHECK_MESSAGE(found, "local minimum at distance ", d, " not returned");
      }
    }
  }
}

}  // namespace

TEST_CASE("auto: parametric curves against the oracle (helix, trefoil, ellipse, parabola arc)") {
  check_file("curve_parametric_cases.json");
}

// Curves built against sampled searches (classes 2 and 3 of the certified-answers issue): cusps
// (t^2, t^3), (t^2, t^5), (t^3, t^5) with points a hair from the cusp on the curve (the nearest
// sample is the cusp itself, where c' = 0), a spike 0.002 wide and loops 0.02 wide, shorter in t
// than the samples' gap.
TEST_CASE("auto: parametric curves with cusps, a spike and small loops against the oracle") {
  // the spike exp(-((t - 0.123)/0.001)^2) magnifies the rounding of t a thousandfold: its residuals
  // stand at ~1e-12 when t is converged to the last bit
  check_file("curve_parametric_hard_cases.json", 1e-11);
}

TEST_CASE("auto: planar implicit curves against the oracle (singular points, components, box edges)") {
  check_file("curve_planar_implicit_cases.json");
}

TEST_CASE("auto: spatial curves against the oracle (Viviani, three circles, box faces)") {
  check_file("curve_spatial_cases.json");
}

TEST_CASE(
    "auto: the certified classes against the oracle (tiny ovals and loops, tacnode, cusp, close circles)") {
  check_file("curve_planar_certified_cases.json");
  check_file("curve_spatial_certified_cases.json");
}

TEST_CASE("auto with all_minima returns the oracle's local minima, best first") {
  check_all_minima("curve_parametric_cases.json");
  check_all_minima("curve_planar_implicit_cases.json");
  check_all_minima("curve_spatial_cases.json");
  check_all_minima("curve_planar_certified_cases.json");
  check_all_minima("curve_spatial_certified_cases.json");
}
