// parametric/geometry/nurbs: points and derivatives to second order of NURBS curves and surfaces
// against exact rational references of an independent method (tests/tools/gen_nurbs_refs.py:
// the basis functions as polynomials on the span from Cox-de Boor's recurrence, the quotient rule
// written out), to 1e-12 of the magnitudes involved; the basis functions' partition of unity and
// their derivatives' sums; and every refusal of a definition with the field at fault.
#include <doctest/doctest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "parametric/geometry/nurbs.hpp"

using footpoint::Vec3;
using json = nlohmann::json;
namespace nurbs = footpoint::nurbs;

namespace {

json nurbs_refs() {
  std::ifstream in(std::string(FOOTPOINT_TESTS_DIR) + "/data/geometry_nurbs_refs.json");
  REQUIRE(in.good());
  return json::parse(in);
}

Vec3 ref_vec(const json& a) {
  return {std::stod(a[0].get<std::string>()), std::stod(a[1].get<std::string>()),
          std::stod(a[2].get<std::string>())};
}

// |got - want| within 1e-12 of the scale (the largest magnitude among the case's references of
// that order, at least 1): the derivatives of a rational patch span orders of magnitude.
void check_close(const Vec3& got, const Vec3& want, double scale, const std::string& what) {
  CAPTURE(what);
  CAPTURE(got.x);
  CAPTURE(got.y);
  CAPTURE(got.z);
  CAPTURE(want.x);
  CAPTURE(want.y);
  CAPTURE(want.z);
  CHECK(footpoint::norm(got - want) <= 1e-12 * scale);
}

std::vector<std::vector<double>> points_of(const json& a) {
  return a.get<std::vector<std::vector<double>>>();
}

}  // namespace

TEST_CASE("NURBS curves: points and derivatives against exact references") {
  const json refs = nurbs_refs();
  REQUIRE(refs["curves"].size() >= 4);
  for (const json& c : refs["curves"]) {
    CAPTURE(c["name"].get<std::string>());
    const auto made =
        nurbs::make_curve(c["degree"].get<int>(), c["knots"].get<std::vector<double>>(),
                          points_of(c["control_points"]), c["weights"].get<std::vector<double>>(), 1000);
    REQUIRE(made.curve.has_value());
    double scale[3] = {1.0, 1.0, 1.0};
    for (const json& p : c["points"]) {
      scale[0] = std::max(scale[0], footpoint::norm(ref_vec(p["c"])));
      scale[1] = std::max(scale[1], footpoint::norm(ref_vec(p["d1"])));
      scale[2] = std::max(scale[2], footpoint::norm(ref_vec(p["d2"])));
    }
    for (const json& p : c["points"]) {
      const double t = p["t"].get<double>();
      CAPTURE(t);
      const footpoint::CurveJet j = nurbs::evaluate(*made.curve, t);
      check_close(j.c, ref_vec(p["c"]), scale[0], "C");
      check_close(j.d1, ref_vec(p["d1"]), scale[1], "C'");
      check_close(j.d2, ref_vec(p["d2"]), scale[2], "C''");
    }
  }
}

TEST_CASE("NURBS surfaces: points and partial derivatives against exact references") {
  const json refs = nurbs_refs();
  REQUIRE(refs["surfaces"].size() >= 3);
  for (const json& s : refs["surfaces"]) {
    CAPTURE(s["name"].get<std::string>());
    std::vector<std::vector<std::vector<double>>> net;
    for (const json& row : s["control_points"]) net.push_back(points_of(row));
    const auto made = nurbs::make_surface({s["degree"][0].get<int>(), s["degree"][1].get<int>()},
                                          s["knots"]["u"].get<std::vector<double>>(),
                                          s["knots"]["v"].get<std::vector<double>>(), net,
                                          s["weights"].get<std::vector<std::vector<double>>>(), 1000);
    REQUIRE(made.surface.has_value());
    const char* names[6] = {"s", "su", "sv", "suu", "suv", "svv"};
    double scale[6] = {1, 1, 1, 1, 1, 1};
    for (const json& p : s["points"])
      for (int k = 0; k < 6; ++k) scale[k] = std::max(scale[k], footpoint::norm(ref_vec(p[names[k]])));
    for (const json& p : s["points"]) {
      const double u = p["u"].get<double>(), v = p["v"].get<double>();
      CAPTURE(u);
      CAPTURE(v);
      const footpoint::SurfaceJet j = nurbs::evaluate(*made.surface, u, v);
      const Vec3 got[6] = {j.s, j.su, j.sv, j.suu, j.suv, j.svv};
      for (int k = 0; k < 6; ++k) check_close(got[k], ref_vec(p[names[k]]), scale[k], names[k]);
    }
  }
}

TEST_CASE("NURBS basis functions: a partition of unity whose derivatives sum to 0") {
  // a clamped cubic knot vector with a double and a triple interior knot
  const std::vector<double> U{0, 0, 0, 0, 0.5, 1, 1, 2, 2, 2, 3, 3, 3, 3};
  const int p = 3, n = static_cast<int>(U.size()) - p - 1;
  for (double u = 0.0; u <= 3.0; u += 0.0625) {
    CAPTURE(u);
    const int i = nurbs::find_span(n, p, u, U);
    REQUIRE(i >= p);
    REQUIRE(i <= n - 1);
    CHECK(U[static_cast<std::size_t>(i)] < U[static_cast<std::size_t>(i) + 1]);
    if (u < 3.0) {
      CHECK(U[static_cast<std::size_t>(i)] <= u);
      CHECK(u < U[static_cast<std::size_t>(i) + 1]);
    }
    double ders[3 * (p + 1)];
    nurbs::basis_derivatives(i, u, p, 2, U, ders);
    double sum[3] = {0, 0, 0};
    for (int k = 0; k < 3; ++k)
      for (int j = 0; j <= p; ++j) {
        sum[k] += ders[k * (p + 1) + j];
        if (k == 0) CHECK(ders[j] >= -1e-15);
      }
    CHECK(sum[0] == doctest::Approx(1.0).epsilon(1e-14));
    CHECK(std::abs(sum[1]) <= 1e-12);
    CHECK(std::abs(sum[2]) <= 1e-11);
  }
}

TEST_CASE("NURBS definitions refused with the field at fault") {
  const std::vector<std::vector<double>> square{{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  const std::vector<double> clamped{0, 0, 0, 1, 2, 2, 2};  // degree 2, 4 points
  auto curve_error = [&](int degree, const std::vector<double>& knots,
                         const std::vector<std::vector<double>>& pts, const std::vector<double>& w,
                         std::size_t limit = 1000) {
    const auto made = nurbs::make_curve(degree, knots, pts, w, limit);
    CHECK_FALSE(made.curve.has_value());
    return made.error.field;
  };
  CHECK(nurbs::make_curve(2, clamped, square, {}, 1000).curve.has_value());
  CHECK(curve_error(0, clamped, square, {}) == "degree");
  CHECK(curve_error(nurbs::kMaxDegree + 1, clamped, square, {}) == "degree");
  CHECK(curve_error(4, {0, 0, 0, 0, 0, 1, 1, 1, 1}, square, {}) ==
        "control_points");                                                   // fewer than degree + 1
  CHECK(curve_error(2, clamped, square, {}, 3) == "control_points");         // over the limit
  CHECK(curve_error(2, {0, 0, 0, 1, 2, 2}, square, {}) == "knots");          // wrong length
  CHECK(curve_error(2, {0, 0, 0, 2, 1, 2, 2}, square, {}) == "knots[4]");    // decreasing
  CHECK(curve_error(2, {0, 0, 0, NAN, 2, 2, 2}, square, {}) == "knots[3]");  // not finite
  CHECK(curve_error(2, {0, 0, 1, 1, 1, 2, 2}, square, {}) == "knots");       // [U_2, U_4] = [1, 1] is empty
  CHECK(curve_error(2, clamped, square, {1, 1, 1}) == "weights");
  CHECK(curve_error(2, clamped, square, {1, 0, 1, 1}) == "weights[1]");
  CHECK(curve_error(2, clamped, square, {1, 1, -2, 1}) == "weights[2]");
  CHECK(curve_error(2, clamped, square, {1, 1, 1, INFINITY}) == "weights[3]");
  CHECK(curve_error(2, clamped, {{0, 0}, {1, 0, 0}, {1, 1}, {0, 1}}, {}) == "control_points[1]");
  CHECK(curve_error(2, clamped, {{0, 0}, {1, 0}, {1, NAN}, {0, 1}}, {}) == "control_points[2]");
  CHECK(curve_error(2, clamped, {{0}, {1}, {2}, {3}}, {}) == "control_points[0]");

  const std::vector<double> ku{0, 0, 1, 1}, kv{0, 0, 0, 1, 1, 1};  // degrees 1 and 2: 2 x 3 points
  const std::vector<std::vector<std::vector<double>>> net{{{0, 0, 0}, {0, 1, 0}, {0, 2, 0}},
                                                          {{1, 0, 0}, {1, 1, 1}, {1, 2, 0}}};
  auto surface_error = [&](const std::vector<std::vector<std::vector<double>>>& n,
                           const std::vector<std::vector<double>>& w) {
    const auto made = nurbs::make_surface({1, 2}, ku, kv, n, w, 1000);
    CHECK_FALSE(made.surface.has_value());
    return made.error.field;
  };
  CHECK(nurbs::make_surface({1, 2}, ku, kv, net, {}, 1000).surface.has_value());
  CHECK(surface_error({{{0, 0, 0}, {0, 1, 0}, {0, 2, 0}}, {{1, 0, 0}, {1, 1, 1}}}, {}) ==
        "control_points[1]");
  CHECK(surface_error(net, {{1, 1, 1}, {1, 1}}) == "weights[1]");
  CHECK(surface_error(net, {{1, 1, 1}, {1, 0, 1}}) == "weights[1][1]");
  CHECK(surface_error({{{0, 0, 0}, {0, 1}, {0, 2, 0}}, {{1, 0, 0}, {1, 1, 1}, {1, 2, 0}}}, {}) ==
        "control_points[0][1]");
  CHECK(nurbs::make_surface({1, 2}, {0, 0, 1}, kv, net, {}, 1000).error.field == "knots.u");
  CHECK(nurbs::make_surface({1, 2}, ku, kv, net, {}, 5).error.field == "control_points");
}
