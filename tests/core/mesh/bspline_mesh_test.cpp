// Meshes of B-spline and NURBS curves and surfaces (core/mesh/bspline_mesh.hpp), checked against
// the geometry evaluated here independently of the engine: the rational circle and sphere in
// closed form (each quarter of the circle a rational quadratic Bézier arc, the sphere the product
// of the circle in u and the half circle in v), and a non-uniform B-spline curve by the Cox-de Boor
// recursion ([PieglTiller] eqs. (2.5) and (3.4)). What the header promises: every knot is a grid
// line (a C0 ridge is an edge of the mesh), each span gets its share of the resolution and at
// least one cell, a closed direction shares its first and last line, pole triangles of zero area
// are left out, normals and tangents are the geometry's, triangles turn counter-clockwise about
// the normals.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <set>
#include <vector>

#include "compiled/bspline_geometry.hpp"
#include "mesh/bspline_mesh.hpp"
#include "nurbs_fixtures.hpp"

using namespace footpoint;

namespace bspline_mesh_test {

// The rational quadratic Bézier arc with end points a, c, middle point b of weight w, at s in
// [0, 1].
std::array<double, 2> rational_arc(std::array<double, 2> a, std::array<double, 2> b, std::array<double, 2> c,
                                   double w, double s) {
  const double b0 = (1 - s) * (1 - s), b1 = 2 * s * (1 - s) * w, b2 = s * s, d = b0 + b1 + b2;
  return {(b0 * a[0] + b1 * b[0] + b2 * c[0]) / d, (b0 * a[1] + b1 * b[1] + b2 * c[1]) / d};
}

// The unit NURBS circle of test::circle_points at t in [0, 1]: quarter k on [k/4, (k+1)/4].
std::array<double, 2> circle_at(double t) {
  const double xs[9][2] = {{1, 0}, {1, 1}, {0, 1}, {-1, 1}, {-1, 0}, {-1, -1}, {0, -1}, {1, -1}, {1, 0}};
  const int k = std::min(3, static_cast<int>(t * 4));
  const auto at = [&](int i) { return std::array<double, 2>{xs[i][0], xs[i][1]}; };
  return rational_arc(at(2 * k), at(2 * k + 1), at(2 * k + 2), test::kHalfRoot2, 4 * t - k);
}

// The half circle (rho, z) of test::nurbs_sphere from the south pole (v = 0) to the north (v = 1).
std::array<double, 2> half_circle_at(double v) {
  return v <= 0.5 ? rational_arc({0, -1}, {1, -1}, {1, 0}, test::kHalfRoot2, 2 * v)
                  : rational_arc({1, 0}, {1, 1}, {0, 1}, test::kHalfRoot2, 2 * v - 1);
}

// The B-spline basis function N_{i,p} on the knots U at t (Cox-de Boor), the last span closed.
double basis(const std::vector<double>& U, int i, int p, double t) {
  const auto u = [&](int k) { return U[static_cast<std::size_t>(k)]; };
  if (p == 0) {
    if (u(i) <= t && t < u(i + 1)) return 1.0;
    return t == U.back() && u(i) < u(i + 1) && u(i + 1) == U.back() ? 1.0 : 0.0;
  }
  double sum = 0.0;
  if (u(i + p) > u(i)) sum += (t - u(i)) / (u(i + p) - u(i)) * basis(U, i, p - 1, t);
  if (u(i + p + 1) > u(i + 1))
    sum += (u(i + p + 1) - t) / (u(i + p + 1) - u(i + 1)) * basis(U, i + 1, p - 1, t);
  return sum;
}

void check_close(const Vec3& got, const Vec3& want, double tolerance) {
  CHECK(std::abs(got.x - want.x) <= tolerance);
  CHECK(std::abs(got.y - want.y) <= tolerance);
  CHECK(std::abs(got.z - want.z) <= tolerance);
}

// Every triangle has positive area and turns counter-clockwise about its first vertex's normal.
void check_triangles(const Mesh& m) {
  for (const auto& t : m.triangles) {
    const Vec3 a = m.vertices[static_cast<std::size_t>(t[0])], b = m.vertices[static_cast<std::size_t>(t[1])],
               c = m.vertices[static_cast<std::size_t>(t[2])];
    const Vec3 n = cross(b - a, c - a);
    CHECK(norm(n) > 0.0);
    CHECK(dot(n, m.normals[static_cast<std::size_t>(t[0])]) > 0.0);
  }
}

}  // namespace bspline_mesh_test

TEST_CASE("bspline mesh: the NURBS circle is a closed polyline on the circle, knots among its vertices") {
  const auto g = compile_geometry(test::nurbs_circle(2.0));
  const auto& curve = dynamic_cast<const BSplineCurve&>(*g);
  // 16 segments over four equal spans: 4 each, t = k / 16; the last vertex (t = 1) is the first.
  const Mesh m = mesh_bspline_curve(curve, 16);
  CHECK(m.num_params == 1);
  REQUIRE(m.vertices.size() == 16);
  REQUIRE(m.polylines.size() == 1);
  CHECK(m.polylines[0].closed);
  REQUIRE(m.polylines[0].vertices.size() == 16);
  REQUIRE(m.tangents.size() == 16);
  REQUIRE(m.parameters.size() == 16);
  for (std::size_t k = 0; k < 16; ++k) {
    CAPTURE(k);
    const double t = static_cast<double>(k) / 16.0;
    CHECK(m.parameters[k] == t);
    CHECK(m.polylines[0].vertices[k] == static_cast<std::int32_t>(k));
    const auto c = bspline_mesh_test::circle_at(t);
    const Vec3 v = m.vertices[k];
    bspline_mesh_test::check_close(v, {2 * c[0], 2 * c[1], 0.0}, 1e-14);
    // The circle's unit tangent is its radius turned by +90 degrees (the circle runs
    // counter-clockwise).
    bspline_mesh_test::check_close(m.tangents[k], {-v.y / 2, v.x / 2, 0.0}, 1e-13);
  }
  // A resolution below the spans still gives one segment per span: the knots alone.
  const Mesh coarse = mesh_bspline_curve(curve, 2);
  REQUIRE(coarse.vertices.size() == 4);
  for (std::size_t k = 0; k < 4; ++k) CHECK(coarse.parameters[k] == 0.25 * static_cast<double>(k));
  bspline_mesh_test::check_close(coarse.vertices[1], {0.0, 2.0, 0.0}, 1e-14);
}

TEST_CASE(
    "bspline mesh: a non-uniform B-spline curve's vertices are its de Boor points, spans shared by length") {
  GeometryDefinition def;
  def.type = GeometryType::bspline_curve;
  def.bspline.degree = {2};
  const std::vector<double> U = {0, 0, 0, 1, 3, 3, 3};
  def.bspline.knots = {U};
  const std::vector<Vec3> P = {{0, 0, 0}, {1, 2, 0}, {3, -1, 1}, {4, 1, 2}};
  def.bspline.control_points = {{{0, 0, 0}, {1, 2, 0}, {3, -1, 1}, {4, 1, 2}}};
  const auto g = compile_geometry(def);
  const Mesh m = mesh_bspline_curve(dynamic_cast<const BSplineCurve&>(*g), 6);
  // Spans [0, 1] and [1, 3] get 6 * 1/3 = 2 and 6 * 2/3 = 4 segments: t = 0, 0.5, ..., 3.
  REQUIRE(m.vertices.size() == 7);
  REQUIRE(m.polylines.size() == 1);
  CHECK_FALSE(m.polylines[0].closed);
  for (std::size_t k = 0; k < 7; ++k) {
    const double t = 0.5 * static_cast<double>(k);
    CAPTURE(t);
    CHECK(m.parameters[k] == t);
    Vec3 c{}, d{};
    for (int i = 0; i < 4; ++i) c = c + bspline_mesh_test::basis(U, i, 2, t) * P[static_cast<std::size_t>(i)];
    // C'(t) = sum N_{i+1,1}(t) 2 (P_{i+1} - P_i) / (U_{i+3} - U_{i+1}) ([PieglTiller] eq. (3.4)).
    for (int i = 0; i < 3; ++i)
      d = d + bspline_mesh_test::basis(U, i + 1, 1, t) * 2.0 /
                  (U[static_cast<std::size_t>(i + 3)] - U[static_cast<std::size_t>(i + 1)]) *
                  (P[static_cast<std::size_t>(i + 1)] - P[static_cast<std::size_t>(i)]);
    bspline_mesh_test::check_close(m.vertices[k], c, 1e-14);
    bspline_mesh_test::check_close(m.tangents[k], d / norm(d), 1e-14);
  }
}

TEST_CASE(
    "bspline mesh: the NURBS sphere's vertices and normals, its seam shared, its poles' slivers dropped") {
  const auto g = compile_geometry(test::nurbs_sphere());
  const auto& sphere = dynamic_cast<const BSplineSurface&>(*g);
  // 8 cells a direction: u's four spans get 2 each (u = k / 8, u = 1 the seam u = 0), v's two
  // spans 4 each (v = k / 8, the poles at v = 0 and 1).
  const Mesh m = mesh_bspline_surface(sphere, 8);
  CHECK(m.num_params == 2);
  REQUIRE(m.normals.size() == m.vertices.size());
  REQUIRE(m.parameters.size() == 2 * m.vertices.size());
  std::set<double> us, vs;
  int below_poles = 0;
  for (std::size_t k = 0; k < m.vertices.size(); ++k) {
    const double u = m.parameters[2 * k], v = m.parameters[2 * k + 1];
    CAPTURE(u);
    CAPTURE(v);
    us.insert(u);
    vs.insert(v);
    CHECK(u * 8 == std::round(u * 8));
    CHECK(v * 8 == std::round(v * 8));
    const auto c = bspline_mesh_test::circle_at(u);
    const auto h = bspline_mesh_test::half_circle_at(v);
    const Vec3 want{c[0] * h[0], c[1] * h[0], h[1]};
    bspline_mesh_test::check_close(m.vertices[k], want, 1e-14);
    // The outward normal of the unit sphere is the point itself. A pole has none of its own
    // (s_u = 0 there): its vertex gets the mean of its triangles' normals, checked below.
    const bool pole = v == 0.0 || v == 1.0;
    if (!pole) {
      bspline_mesh_test::check_close(m.normals[k], want, 1e-13);
      ++below_poles;
    }
  }
  // A pole vertex's normal: the sum of its triangles' (area-weighted) normals, normalized; those
  // triangles lie within 22.5 degrees of the pole (v within 1/8 of it), so it is within 22.5
  // degrees of the pole's outward direction.
  std::vector<Vec3> fan(m.vertices.size(), Vec3{});
  for (const auto& t : m.triangles) {
    const Vec3 a = m.vertices[static_cast<std::size_t>(t[0])];
    const Vec3 n =
        cross(m.vertices[static_cast<std::size_t>(t[1])] - a, m.vertices[static_cast<std::size_t>(t[2])] - a);
    for (const auto v : t) fan[static_cast<std::size_t>(v)] = fan[static_cast<std::size_t>(v)] + n;
  }
  int poles = 0;
  for (std::size_t k = 0; k < m.vertices.size(); ++k) {
    const double v = m.parameters[2 * k + 1];
    if (v != 0.0 && v != 1.0) continue;
    ++poles;
    bspline_mesh_test::check_close(m.normals[k], fan[k] / norm(fan[k]), 1e-12);
    CHECK(dot(m.normals[k], {0.0, 0.0, v == 0.0 ? -1.0 : 1.0}) >= std::cos(std::numbers::pi / 8));
  }
  CHECK(poles >= 2);
  CHECK(us.size() == 8);
  CHECK(*us.rbegin() == 0.875);
  CHECK(vs.size() == 9);
  CHECK(vs.count(0.5) == 1);
  CHECK(below_poles == 8 * 7);
  // 8 x 8 quads of two triangles; each of the 16 quads at a pole has two corners at the pole,
  // one of its triangles has no area.
  CHECK(m.triangles.size() == 2 * 64 - 16);
  bspline_mesh_test::check_triangles(m);

  // Resolution 1: one cell per span, the knots alone: 4 x 2 quads, all at a pole.
  const Mesh coarse = mesh_bspline_surface(sphere, 1);
  CHECK(coarse.triangles.size() == 8);
  bspline_mesh_test::check_triangles(coarse);
}

TEST_CASE("bspline mesh: a C0 ridge is a line of the mesh, no triangle straddles it") {
  // The roof z = 1 - |x - 1| over [0, 2] x [0, 1]: degree 1, the ridge at the knot u = 1.
  const auto g = compile_geometry(test::nurbs_roof());
  // Resolution 3: each u span gets round(1.5) = 2 cells (u = 0, 0.5, ..., 2; a uniform grid of 3
  // would miss the ridge), v gets 3.
  const Mesh m = mesh_bspline_surface(dynamic_cast<const BSplineSurface&>(*g), 3);
  REQUIRE(m.vertices.size() == 5 * 4);
  CHECK(m.triangles.size() == 4 * 3 * 2);
  int on_ridge = 0;
  for (std::size_t k = 0; k < m.vertices.size(); ++k) {
    const double u = m.parameters[2 * k], v = m.parameters[2 * k + 1];
    const Vec3 p = m.vertices[k];
    CHECK(p.x == u);
    CHECK(p.y == doctest::Approx(v).epsilon(1e-15));
    CHECK(p.z == doctest::Approx(1.0 - std::abs(u - 1.0)).epsilon(1e-15));
    if (u == 1.0) ++on_ridge;
    // Each face's normal: (-1, 0, 1) / sqrt(2) on z = x, (1, 0, 1) / sqrt(2) on z = 2 - x.
    if (u != 1.0)
      bspline_mesh_test::check_close(
          m.normals[k], {u < 1.0 ? -test::kHalfRoot2 : test::kHalfRoot2, 0.0, test::kHalfRoot2}, 1e-15);
  }
  CHECK(on_ridge == 4);
  for (const auto& t : m.triangles) {
    double lo = 2.0, hi = 0.0;
    for (const auto v : t) {
      lo = std::min(lo, m.parameters[2 * static_cast<std::size_t>(v)]);
      hi = std::max(hi, m.parameters[2 * static_cast<std::size_t>(v)]);
    }
    CHECK((hi <= 1.0 || lo >= 1.0));
  }
}
