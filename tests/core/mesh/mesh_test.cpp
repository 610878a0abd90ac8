// mesh/mesh: mesh_geometry picks the mesh of each kind of geometry. On shapes whose points are
// known in closed form - the unit circle as a parametric curve and as an implicit one, the unit
// sphere as a parametric surface - each mesh is of its kind (parameters per vertex, triangles or
// polylines, normals or tangents) and every vertex lies on the shape; a resolution below 2 is
// refused.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "compile_definition.hpp"
#include "implicit_fixtures.hpp"
#include "mesh/mesh.hpp"

using namespace footpoint;

namespace {

constexpr double kMeshPi = std::numbers::pi;

}  // namespace

TEST_CASE("mesh: a parametric circle is a closed polyline on the circle") {
  const auto circle = test::compile_definition(GeometryType::parametric_curve,
                                               {{"x", "cos(t)"}, {"y", "sin(t)"}}, {{"t", {0, 2 * kMeshPi}}});
  const Mesh m = mesh_geometry(*circle, MeshOptions{16});
  CHECK(m.num_params == 1);
  CHECK(m.triangles.empty());
  CHECK(m.normals.empty());
  REQUIRE(m.polylines.size() == 1);
  CHECK(m.polylines[0].closed);
  REQUIRE(m.parameters.size() == m.vertices.size());
  REQUIRE(m.tangents.size() == m.vertices.size());
  for (std::size_t k = 0; k < m.vertices.size(); ++k) {
    const double t = m.parameters[k];
    CHECK(m.vertices[k].x == doctest::Approx(std::cos(t)).epsilon(1e-15));
    CHECK(m.vertices[k].y == doctest::Approx(std::sin(t)).epsilon(1e-15));
    CHECK(norm(m.tangents[k]) == doctest::Approx(1.0).epsilon(1e-14));
  }
}

TEST_CASE("mesh: a parametric sphere is triangles with unit normals on the sphere") {
  const auto sphere = test::compile_definition(
      GeometryType::parametric_surface, {{"x", "cos(u)*cos(v)"}, {"y", "sin(u)*cos(v)"}, {"z", "sin(v)"}},
      {{"u", {0, 2 * kMeshPi}}, {"v", {-kMeshPi / 2, kMeshPi / 2}}});
  const Mesh m = mesh_geometry(*sphere, MeshOptions{8});
  CHECK(m.num_params == 2);
  CHECK_FALSE(m.triangles.empty());
  CHECK(m.polylines.empty());
  REQUIRE(m.normals.size() == m.vertices.size());
  for (std::size_t k = 0; k < m.vertices.size(); ++k) {
    CHECK(norm(m.vertices[k]) == doctest::Approx(1.0).epsilon(1e-14));
    // The sphere's unit normal is ± the position itself.
    CHECK(std::fabs(dot(m.normals[k], m.vertices[k])) == doctest::Approx(1.0).epsilon(1e-12));
  }
  for (const auto& tri : m.triangles)
    for (const std::int32_t v : tri) {
      CHECK(v >= 0);
      CHECK(static_cast<std::size_t>(v) < m.vertices.size());
    }
}

TEST_CASE("mesh: an implicit circle is polylines on the circle, without parameters") {
  const auto circle = test::implicit_curve({"x^2+y^2-1"}, {{-2, 2}, {-2, 2}});
  const Mesh m = mesh_geometry(*circle, MeshOptions{32});
  CHECK(m.num_params == 0);
  CHECK(m.parameters.empty());
  REQUIRE_FALSE(m.polylines.empty());
  for (const Vec3& v : m.vertices) CHECK(norm(v) == doctest::Approx(1.0).epsilon(1e-12));
}

TEST_CASE("mesh: a resolution below 2 is refused") {
  const auto circle = test::compile_definition(GeometryType::parametric_curve,
                                               {{"x", "cos(t)"}, {"y", "sin(t)"}}, {{"t", {0, 2 * kMeshPi}}});
  CHECK_THROWS_AS(mesh_geometry(*circle, MeshOptions{1}), std::invalid_argument);
  CHECK_NOTHROW(mesh_geometry(*circle, MeshOptions{2}));
}
