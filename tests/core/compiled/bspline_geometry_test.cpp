// compiled/bspline_geometry: B-spline and NURBS surfaces and curves projected with `auto` (the
// branch and bound over their Bézier pieces) against closed forms computed here, not by the
// engine: the rational sphere (the distance | |p| - 1 |, the foot p / |p|), a bicubic B-spline
// whose control points lie on a plane at the Greville abscissae (linear precision: the surface is
// the plane z = a u + b v + c over the domain exactly), a roof of two planes meeting in a C0 ridge
// (the foot on the ridge is a kink), the NURBS circle (closed: its seam is interior); the
// canonical text's round trip and the refusals of bad nets.
#include <doctest/doctest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "compiled/bspline_geometry.hpp"
#include "compiled/compiled_geometry.hpp"
#include "compiled/geometry_definition.hpp"
#include "geometry/geometry_error.hpp"
#include "nurbs_fixtures.hpp"

using namespace footpoint;

namespace {

using test::nurbs_circle;
using test::nurbs_sphere;

// A clamped uniform knot vector for n control points of degree p over [0, length].
std::vector<double> clamped(int n, int p, double length) {
  std::vector<double> U;
  for (int i = 0; i <= p; ++i) U.push_back(0.0);
  for (int i = 1; i < n - p; ++i) U.push_back(length * i / (n - p));
  for (int i = 0; i <= p; ++i) U.push_back(length);
  return U;
}
double greville(const std::vector<double>& U, int i, int p) {
  double s = 0.0;
  for (int k = 1; k <= p; ++k) s += U[static_cast<std::size_t>(i + k)];
  return s / p;
}

// z = a u + b v + c over [0, 4]^2 as a bicubic B-spline of 11 x 11 control points (8 x 8 pieces).
GeometryDefinition planar_bicubic(double a, double b, double c) {
  GeometryDefinition def;
  def.type = GeometryType::bspline_surface;
  def.bspline.degree = {3, 3};
  const std::vector<double> U = clamped(11, 3, 4.0);
  def.bspline.knots = {U, U};
  for (int i = 0; i < 11; ++i) {
    std::vector<std::vector<double>> row;
    for (int j = 0; j < 11; ++j) {
      const double x = greville(U, i, 3), y = greville(U, j, 3);
      row.push_back({x, y, a * x + b * y + c});
    }
    def.bspline.control_points.push_back(row);
  }
  return def;
}

}  // namespace

TEST_CASE("the rational sphere: every answer is | |p| - 1 | at p / |p|, certified") {
  const auto g = compile_geometry(nurbs_sphere());
  const auto& s = dynamic_cast<const BSplineSurface&>(*g);
  CHECK(s.pieces() == 8);
  CHECK(s.closed()[0]);
  CHECK_FALSE(s.closed()[1]);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> coord(-2.0, 2.0);
  int certified = 0, count = 0;
  for (int k = 0; k < 60; ++k) {
    const double p[3] = {coord(rng), coord(rng), coord(rng)};
    const double r = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    if (r < 0.2) continue;
    ++count;
    const ProjectionResult a = g->project(p, "auto", {}).value();
    CAPTURE(p[0]);
    CAPTURE(p[1]);
    CAPTURE(p[2]);
    CHECK(std::abs(a.distance - std::abs(r - 1.0)) <= 1e-12 * (1.0 + r));
    for (int c = 0; c < 3; ++c) CHECK(std::abs(a.foot[c] - p[c] / r) <= 1e-12);
    CHECK(a.summary.location != Location::edge);  // the seam is interior, the poles are poles
    certified += a.summary.certificate.certified;
    // The signed distance: outward normal.
    CHECK(std::abs(a.signed_distance - (r - 1.0)) <= 1e-12 * (1.0 + r));
  }
  CHECK(certified == count);
}

TEST_CASE("the rational sphere's poles: p on the axis is certified at the pole, the centre a continuum") {
  const auto g = compile_geometry(nurbs_sphere());
  for (const double z : {-3.0, -1.5, -0.6, -0.2, 0.2, 0.7, 1.001, 2.0}) {
    const double p[3] = {0.0, 0.0, z};
    CAPTURE(z);
    const ProjectionResult a = g->project(p, "auto", {}).value();
    CHECK(std::abs(a.distance - std::abs(std::abs(z) - 1.0)) <= 1e-14);
    CHECK(std::abs(a.foot[2] - (z > 0.0 ? 1.0 : -1.0)) <= 1e-14);
    CHECK(a.summary.location == Location::pole);
    CHECK(a.summary.certificate.certified);
    CHECK(a.summary.multiplicity.kind == Multiplicity::unique);
  }
  // Every point is a foot of the centre: its distance is certified, its multiplicity a continuum.
  const double centre[3] = {0.0, 0.0, 0.0};
  const ProjectionResult c = g->project(centre, "auto", {}).value();
  CHECK(std::abs(c.distance - 1.0) <= 1e-14);
  CHECK(c.summary.multiplicity.kind == Multiplicity::continuum);
}

TEST_CASE("a bicubic B-spline on a plane is the plane: closed-form feet over 64 pieces") {
  const double a = 0.3, b = -0.2, c = 0.5;
  const auto g = compile_geometry(planar_bicubic(a, b, c));
  CHECK(dynamic_cast<const BSplineSurface&>(*g).pieces() == 64);
  const double n_len = std::sqrt(a * a + b * b + 1.0);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> inside(0.3, 3.7), height(-0.5, 0.5);
  for (int k = 0; k < 40; ++k) {
    // p = q + h n for q on the plane inside the domain: its foot is q, at distance |h|.
    const double u = inside(rng), v = inside(rng), h = height(rng) * (k % 2 ? 0.02 : 1.0);
    const double n[3] = {-a / n_len, -b / n_len, 1.0 / n_len};
    const double p[3] = {u + h * n[0], v + h * n[1], a * u + b * v + c + h * n[2]};
    const ProjectionResult r = g->project(p, "auto", {}).value();
    CAPTURE(u);
    CAPTURE(v);
    CAPTURE(h);
    CHECK(std::abs(r.distance - std::abs(h)) <= 1e-12);
    CHECK(std::abs(r.params[0] - u) <= 1e-9);
    CHECK(std::abs(r.params[1] - v) <= 1e-9);
    CHECK(r.summary.location == Location::interior);
    CHECK(r.summary.certificate.certified);
  }
  // Beyond a corner: the corner.
  const double p[3] = {-1.0, -1.0, 0.0};
  const ProjectionResult r = g->project(p, "auto", {}).value();
  CHECK(r.summary.location == Location::corner);
  CHECK(std::abs(r.foot[2] - c) <= 1e-12);
  CHECK(r.summary.certificate.certified);
}

TEST_CASE("a roof's ridge is a kink; the two faces give one foot") {
  const auto g = compile_geometry(test::nurbs_roof());
  const double p[3] = {1.0, 0.5, 2.0};
  const ProjectionResult r = g->project(p, "auto", {}).value();
  CHECK(std::abs(r.distance - 1.0) <= 1e-12);
  CHECK(r.summary.location == Location::kink);
  CHECK(r.summary.multiplicity.kind == Multiplicity::unique);
  CHECK(r.summary.certificate.certified);
  CHECK_FALSE(r.has_normal());
  // Above a face: interior, on that face's plane z = x.
  const double q[3] = {0.5, 0.5, 1.0};
  const ProjectionResult f = g->project(q, "auto", {}).value();
  CHECK(std::abs(f.distance - 0.5 / std::sqrt(2.0)) <= 1e-12);
  CHECK(f.summary.location == Location::interior);
}

TEST_CASE("the NURBS circle is closed: its seam is interior, the distance | |p| - 2 |") {
  const auto g = compile_geometry(nurbs_circle(2.0));
  const auto& curve = dynamic_cast<const BSplineCurve&>(*g);
  CHECK(curve.closed());
  CHECK(curve.pieces() == 4);
  CHECK(g->point_dim() == 2);
  for (int k = 0; k < 24; ++k) {
    const double angle = 0.1 + k * 0.27, radius = 0.5 + 0.2 * k;
    const double p[2] = {radius * std::cos(angle), radius * std::sin(angle)};
    const ProjectionResult r = g->project(p, "auto", {}).value();
    CAPTURE(angle);
    CAPTURE(radius);
    CHECK(std::abs(r.distance - std::abs(radius - 2.0)) <= 1e-12 * (1.0 + radius));
    CHECK(std::abs(r.foot[0] - 2.0 * std::cos(angle)) <= 1e-12);
    CHECK(std::abs(r.foot[1] - 2.0 * std::sin(angle)) <= 1e-12);
    CHECK(r.summary.location == Location::interior);
    CHECK(r.summary.certificate.certified);
  }
  // At the seam (t = 0 and t = 1 are the point (2, 0)): one foot, interior.
  const double p[2] = {3.0, 0.0};
  const ProjectionResult r = g->project(p, "auto", {}).value();
  CHECK(std::abs(r.distance - 1.0) <= 1e-12);
  CHECK(r.summary.location == Location::interior);
  CHECK(r.summary.multiplicity.kind == Multiplicity::unique);
  // The normal of a planar curve is c' turned by +90 degrees: inward on a counterclockwise circle.
  CHECK(std::abs(r.signed_distance + 1.0) <= 1e-12);
}

TEST_CASE("B-spline definitions: canonical text round trip, ids, refusals naming the field") {
  for (const GeometryDefinition& def : {nurbs_sphere(), nurbs_circle(2.0), planar_bicubic(0.1, 0.2, 0.3)}) {
    const std::string text = def.canonical();
    CHECK(parse_canonical(text).canonical() == text);
    CHECK(parse_canonical(text).id() == def.id());
  }
  CHECK(nurbs_circle(2.0).id() != nurbs_circle(2.5).id());
  CHECK_THROWS_AS(
      parse_canonical("footpoint/1;type=bspline_curve;degree=2;knots.u=[0,1];control_points=[[0,0],"),
      GeometryError);

  GeometryDefinition bad = nurbs_circle(1.0);
  bad.bspline.weights[0][3] = -1.0;
  try {
    compile_geometry(bad);
    FAIL("a negative weight was accepted");
  } catch (const GeometryError& e) {
    CHECK(std::string(e.code) == "bad_bspline");
    CHECK(e.field == "weights[3]");
  }
  bad = nurbs_circle(1.0);
  bad.bspline.knots[0].pop_back();
  CHECK_THROWS_AS(compile_geometry(bad), GeometryError);
}

TEST_CASE("the papers' methods run from piece to piece: from a start on one piece to a foot on another") {
  const auto g = compile_geometry(nurbs_sphere());
  std::vector<std::string> names;
  for (const MethodInfo& m : g->methods()) names.emplace_back(m.name);
  CHECK(names == std::vector<std::string>{"auto", "gsa", "first_order", "hybrid", "newton"});
  // p near the sphere at longitude 200 degrees, latitude 30; start at longitude 170 (another
  // quarter's piece), latitude 25 (u in [0, 1] is the longitude / 360, v the latitude's share).
  const double lon = 200.0 * M_PI / 180.0, lat = 30.0 * M_PI / 180.0, r = 1.3;
  const double p[3] = {r * std::cos(lat) * std::cos(lon), r * std::cos(lat) * std::sin(lon),
                       r * std::sin(lat)};
  for (const std::string method : {"hybrid", "newton", "gsa", "first_order"}) {
    CAPTURE(method);
    Options o;
    o.initial = std::array<double, 3>{170.0 / 360.0, 0.5 + 25.0 / 180.0, 0.0};
    o.certify = true;
    const auto answer = g->project(p, method, o);
    if (!answer) FAIL(answer.error().message);
    const ProjectionResult a = answer.value();
    CHECK(a.summary.status == Status::converged);
    CHECK(std::abs(a.distance - 0.3) <= 1e-12);
    for (int c = 0; c < 3; ++c) CHECK(std::abs(a.foot[c] - p[c] / r) <= 1e-12);
    CHECK(a.summary.certificate.certified);
    CHECK(a.params[0] > 0.5);  // on the third quarter's piece, not the start's
    CHECK(a.params[0] < 0.75);
  }
  // The circle's curve methods: newton from the nearest sample, curvature_circle from a start.
  const auto circle = compile_geometry(nurbs_circle(2.0));
  const double q[2] = {-1.0, -3.0};
  for (const std::string method : {"newton", "curvature_circle"}) {
    CAPTURE(method);
    Options o;
    if (method == "curvature_circle") o.initial = std::array<double, 3>{0.1, 0.0, 0.0};
    const auto answer = circle->project(q, method, o);
    if (!answer) FAIL(answer.error().message);
    const ProjectionResult a = answer.value();
    CHECK(a.summary.status == Status::converged);
    CHECK(std::abs(a.distance - (std::sqrt(10.0) - 2.0)) <= 1e-12);
    CHECK(a.summary.location == Location::interior);
  }
}
