// Meshes of curves (mesh/curve_mesh): parametric curves as equidistributed polylines of points
// c(t_i) (against the closed forms evaluated here), closed ones as closed polylines, implicit curves as the
// traced pieces with every vertex on both equations, loops closed, box-face ends on the face, branches joined
// at singular points, and the resolution bounding the segments.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

#include "compiled/implicit_curve_geometry.hpp"
#include "compiled/parametric_curve_geometry.hpp"
#include "implicit_fixtures.hpp"
#include "mesh/mesh.hpp"

using namespace footpoint;

namespace {

constexpr double kPi = std::numbers::pi;

std::shared_ptr<const CompiledGeometry> parametric(std::vector<formula::NamedFormula> xyz,
                                                   std::array<double, 2> t) {
  GeometryDefinition def;
  def.type = GeometryType::parametric_curve;
  def.formulas = std::move(xyz);
  def.domain = {{"t", t}};
  return compile_geometry(def);
}

double length(const Mesh& m) {
  double sum = 0.0;
  for (const Polyline& l : m.polylines) {
    for (std::size_t k = 0; k + 1 < l.vertices.size(); ++k)
      sum += norm(m.vertices[static_cast<std::size_t>(l.vertices[k + 1])] -
                  m.vertices[static_cast<std::size_t>(l.vertices[k])]);
    if (l.closed)
      sum += norm(m.vertices[static_cast<std::size_t>(l.vertices.front())] -
                  m.vertices[static_cast<std::size_t>(l.vertices.back())]);
  }
  return sum;
}

std::size_t segments(const Mesh& m) {
  std::size_t n = 0;
  for (const Polyline& l : m.polylines) n += l.vertices.size() - (l.closed ? 0 : 1);
  return n;
}

// Indices in range, at least two vertices a polyline, tangents unit (0 only at singular points).
void check_well_formed_polylines(const Mesh& m) {
  REQUIRE(m.tangents.size() == m.vertices.size());
  REQUIRE(m.triangles.empty());
  REQUIRE(!m.polylines.empty());
  for (const Polyline& l : m.polylines) {
    CHECK(l.vertices.size() >= 2);
    for (std::int32_t v : l.vertices) {
      REQUIRE(v >= 0);
      REQUIRE(static_cast<std::size_t>(v) < m.vertices.size());
    }
  }
  std::vector<bool> singular(m.vertices.size(), false);
  for (std::int32_t v : m.singular_points) singular[static_cast<std::size_t>(v)] = true;
  for (std::size_t k = 0; k < m.vertices.size(); ++k) {
    CHECK(is_finite(m.vertices[k]));
    if (singular[k])
      CHECK(norm(m.tangents[k]) == 0.0);
    else
      CHECK(std::abs(norm(m.tangents[k]) - 1.0) <= 1e-14);
  }
}

}  // namespace

TEST_CASE("helix: c(t_i) at its parameters, exact tangents, uniform lines (constant speed and curvature)") {
  const auto g = parametric({{"x", "cos(t)"}, {"y", "sin(t)"}, {"z", "t/4"}}, {0, 4 * kPi});
  const int n = 200;
  const Mesh m = mesh_geometry(*g, MeshOptions{n});
  check_well_formed_polylines(m);
  REQUIRE(m.polylines.size() == 1);
  CHECK_FALSE(m.polylines[0].closed);
  REQUIRE(m.vertices.size() == static_cast<std::size_t>(n + 1));
  REQUIRE(m.parameters.size() == m.vertices.size());
  for (std::size_t k = 0; k < m.vertices.size(); ++k) {
    const double t = m.parameters[k];
    CHECK(norm(m.vertices[k] - Vec3{std::cos(t), std::sin(t), t / 4}) <= 1e-15 * (1 + t));
    const Vec3 tangent = Vec3{-std::sin(t), std::cos(t), 0.25} / std::sqrt(1.0625);
    CHECK(norm(m.tangents[k] - tangent) <= 1e-15);
    CHECK(t == doctest::Approx(4 * kPi * static_cast<double>(k) / n).epsilon(1e-9));
  }
  CHECK(m.parameters.front() == 0.0);
  CHECK(m.parameters.back() == 4 * kPi);
  const double exact = 4 * kPi * std::sqrt(1.0625);
  CHECK(std::abs(length(m) - exact) <= 1e-3 * exact);
}

TEST_CASE("closed parametric curves give closed polylines without a second vertex at the seam") {
  struct Case {
    std::vector<formula::NamedFormula> xyz;
    double exact_length;
  };
  const Case cases[] = {
      {{{"x", "cos(t)"}, {"y", "sin(t)"}}, 2 * kPi},
      {{{"x", "sin(t)+2*sin(2*t)"}, {"y", "cos(t)-2*cos(2*t)"}, {"z", "-sin(3*t)"}}, 0.0},  // trefoil
      // Finite only for cos(t) >= -0.9 besides: two runs joined across t = 0 = 2 pi.
      {{{"x", "cos(t)+0*sqrt(cos(t)+0.9)"}, {"y", "sin(t)"}}, 0.0},
  };
  for (const Case& c : cases) {
    CAPTURE(c.xyz[0].expression);
    const auto g = parametric(c.xyz, {0, 2 * kPi});
    REQUIRE(dynamic_cast<const ParametricCurve&>(*g).closure().closed);
    const int n = 120;
    const Mesh m = mesh_geometry(*g, MeshOptions{n});
    check_well_formed_polylines(m);
    REQUIRE(m.polylines.size() == 1);
    // No two vertices at one point: c(2 pi) is not repeated.
    for (std::size_t a = 0; a < m.vertices.size(); ++a)
      for (std::size_t b = a + 1; b < m.vertices.size(); ++b)
        CHECK(norm(m.vertices[a] - m.vertices[b]) > 1e-9);
    if (c.exact_length > 0.0) {
      CHECK(m.polylines[0].closed);
      CHECK(m.vertices.size() == static_cast<std::size_t>(n));
      CHECK(segments(m) == static_cast<std::size_t>(n));
      CHECK(std::abs(length(m) - c.exact_length) <= 1e-3 * c.exact_length);
    } else if (c.xyz.size() == 3) {
      CHECK(m.polylines[0].closed);
    } else {
      // One open run from past the gap around through t = 0 to the gap's other side.
      CHECK_FALSE(m.polylines[0].closed);
      const auto& l = m.polylines[0].vertices;
      CHECK(m.parameters[static_cast<std::size_t>(l.front())] > kPi);
      CHECK(m.parameters[static_cast<std::size_t>(l.back())] < kPi);
    }
  }
}

TEST_CASE("planar parametric curve: z = 0, the part where the formula is not finite left out") {
  const auto g = parametric({{"x", "t"}, {"y", "sqrt(t)"}}, {-1, 1});
  const Mesh m = mesh_geometry(*g, MeshOptions{64});
  check_well_formed_polylines(m);
  REQUIRE(m.polylines.size() == 1);
  for (std::size_t k = 0; k < m.vertices.size(); ++k) {
    const double t = m.parameters[k];
    CHECK(t >= 0.0);
    CHECK(m.vertices[k].x == t);
    CHECK(m.vertices[k].y == std::sqrt(t));
    CHECK(m.vertices[k].z == 0.0);
  }
}

TEST_CASE("planar implicit ellipse: one closed polyline on the curve, tangents orthogonal to the gradient") {
  const auto g = test::implicit_curve({"x^2/4+y^2-1"}, {{-3, 3}, {-2, 2}});
  const Mesh m = mesh_geometry(*g, MeshOptions{4096});
  check_well_formed_polylines(m);
  REQUIRE(m.polylines.size() == 1);
  CHECK(m.polylines[0].closed);
  CHECK(m.singular_points.empty());
  CHECK(m.parameters.empty());
  for (std::size_t k = 0; k < m.vertices.size(); ++k) {
    const Vec3 x = m.vertices[k];
    const Vec3 grad{x.x / 2, 2 * x.y, 0};
    CHECK(std::abs(x.x * x.x / 4 + x.y * x.y - 1) / norm(grad) <= 1e-12);
    CHECK(x.z == 0.0);
    CHECK(std::abs(dot(m.tangents[k], grad)) <= 1e-12 * norm(grad));
  }
  // The perimeter of the ellipse with semi-axes 2 and 1 (mpmath: 4 a E(1 - b^2/a^2)).
  const double perimeter = 9.6884482205476761;
  CHECK(std::abs(length(m) - perimeter) <= 1e-3 * perimeter);
  // The resolution bounds the segments; coarser meshes keep the vertices on the curve.
  const Mesh coarse = mesh_geometry(*g, MeshOptions{24});
  check_well_formed_polylines(coarse);
  CHECK(segments(coarse) <= 24 + 2);
  CHECK(std::abs(length(coarse) - perimeter) <= 0.02 * perimeter);
}

TEST_CASE("implicit circle cut by the box: an open piece ending on the face") {
  const auto g = test::implicit_curve({"x^2+y^2-1"}, {{-0.5, 2}, {-2, 2}});
  const Mesh m = mesh_geometry(*g, MeshOptions{512});
  check_well_formed_polylines(m);
  REQUIRE(m.polylines.size() == 1);
  const Polyline& l = m.polylines[0];
  CHECK_FALSE(l.closed);
  for (std::int32_t end : {l.vertices.front(), l.vertices.back()}) {
    const Vec3 x = m.vertices[static_cast<std::size_t>(end)];
    CHECK(x.x == doctest::Approx(-0.5).epsilon(1e-14));
    CHECK(std::abs(std::hypot(x.x, x.y) - 1) <= 1e-13);
  }
  // The arc from angle -2pi/3 to 2pi/3 the long way round: 4 pi / 3.
  CHECK(std::abs(length(m) - 4 * kPi / 3) <= 1e-3 * 4 * kPi / 3);
}

// How often the polylines pass vertex v.
int passes(const Mesh& m, std::int32_t v) {
  int count = 0;
  for (const Polyline& l : m.polylines)
    for (std::int32_t w : l.vertices) count += w == v;
  return count;
}

TEST_CASE("lemniscate of Bernoulli: one loop through the crossing twice, the crossing one vertex") {
  const auto g = test::implicit_curve({"(x^2+y^2)^2-2*(x^2-y^2)"}, {{-2, 2}, {-1.5, 1.5}});
  const Mesh m = mesh_geometry(*g, MeshOptions{2048});
  check_well_formed_polylines(m);
  REQUIRE(m.singular_points.size() == 1);
  const std::int32_t origin = m.singular_points[0];
  CHECK(norm(m.vertices[static_cast<std::size_t>(origin)]) <= 1e-6);
  REQUIRE(m.polylines.size() == 1);
  CHECK(m.polylines[0].closed);
  CHECK(passes(m, origin) == 2);
  for (const Vec3& x : m.vertices) {
    const double r2 = x.x * x.x + x.y * x.y;
    CHECK(std::abs(r2 * r2 - 2 * (x.x * x.x - x.y * x.y)) <= 1e-12);
  }
  // Its length (mpmath: 4 * quad(sqrt(r^2 + r'^2), [0, pi/4]) for r^2 = 2 cos 2θ).
  const double exact = 7.4162987092054860;
  CHECK(std::abs(length(m) - exact) <= 1e-3 * exact);
}

TEST_CASE("two crossing lines: both pieces pass the singular point") {
  const auto g = test::implicit_curve({"x*y"}, {{-1, 1.2}, {-1, 1.1}});
  const Mesh m = mesh_geometry(*g, MeshOptions{2048});
  check_well_formed_polylines(m);
  REQUIRE(m.singular_points.size() == 1);
  const std::int32_t origin = m.singular_points[0];
  CHECK(norm(m.vertices[static_cast<std::size_t>(origin)]) <= 1e-9);
  REQUIRE(m.polylines.size() == 2);
  for (const Polyline& l : m.polylines) {
    CHECK_FALSE(l.closed);
    int through = 0;
    for (std::int32_t v : l.vertices) through += v == origin;
    CHECK(through == 1);
  }
  CHECK(std::abs(length(m) - (2.2 + 2.1)) <= 1e-12);  // straight: the chords are the lines
}

TEST_CASE("Viviani's curve: every vertex on the sphere and the cylinder, the crossing passed twice") {
  const auto g =
      test::implicit_curve({"x^2+y^2+z^2-4", "(x-1)^2+y^2-1"}, {{-2.5, 2.5}, {-2.5, 2.5}, {-2.5, 2.5}});
  const Mesh m = mesh_geometry(*g, MeshOptions{1024});
  check_well_formed_polylines(m);
  for (const Vec3& x : m.vertices) {
    CHECK(std::abs(norm2(x) - 4) / (2 * norm(x)) <= 1e-12);
    const double r = std::hypot(x.x - 1, x.y);
    CHECK(std::abs(r * r - 1) / (2 * r) <= 1e-12);
  }
  REQUIRE(m.singular_points.size() == 1);
  const std::int32_t crossing = m.singular_points[0];
  CHECK(norm(m.vertices[static_cast<std::size_t>(crossing)] - Vec3{2, 0, 0}) <= 1e-6);
  CHECK(passes(m, crossing) == 2);
  // Its length (mpmath: quad of |c'(t)| for c = (1 + cos t, sin t, 2 sin(t/2)), t in [0, 4 pi]).
  const double exact = 15.280791156110848;
  CHECK(std::abs(length(m) - exact) <= 1e-3 * exact);
}
