// Meshes of implicit surfaces (mesh/implicit_surface_mesh): every vertex lies on the surface (on
// the unit sphere to rounding) and in the box, normals are the unit radial ones, the winding
// follows them, no triangle is degenerate, and the triangles' area approaches the sphere's 4 pi
// from below (inscribed), the clipped half sphere's 2 pi.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

#include "compiled/implicit_surface_geometry.hpp"
#include "mesh/mesh.hpp"

using namespace footpoint;

namespace {

Mesh implicit_sphere_mesh(double zlo, int resolution) {
  GeometryDefinition def;
  def.type = GeometryType::implicit_surface;
  def.formulas = {{"equation", "x^2+y^2+z^2-1"}};
  def.domain = {{"x", {-1.5, 1.5}}, {"y", {-1.5, 1.5}}, {"z", {zlo, 1.5}}};
  return mesh_geometry(*compile_geometry(def), {resolution});
}

double implicit_mesh_area(const Mesh& m) {
  double area = 0.0;
  for (const auto& t : m.triangles) {
    const Vec3 a = m.vertices[static_cast<std::size_t>(t[0])], b = m.vertices[static_cast<std::size_t>(t[1])],
               c = m.vertices[static_cast<std::size_t>(t[2])];
    area += 0.5 * norm(cross(b - a, c - a));
  }
  return area;
}

}  // namespace

TEST_CASE("implicit surface mesh: the unit sphere, its vertices on it, radial normals, area to 4 pi") {
  double previous = 0.0;
  for (const int resolution : {8, 16, 32}) {
    CAPTURE(resolution);
    const Mesh m = implicit_sphere_mesh(-1.5, resolution);
    REQUIRE(!m.triangles.empty());
    REQUIRE(m.normals.size() == m.vertices.size());
    CHECK(m.num_params == 0);
    for (std::size_t i = 0; i < m.vertices.size(); ++i) {
      CHECK(std::fabs(norm(m.vertices[i]) - 1.0) <= 1e-14);
      CHECK(norm(m.normals[i] - m.vertices[i] / norm(m.vertices[i])) <= 1e-14);
    }
    for (const auto& t : m.triangles) {
      const Vec3 a = m.vertices[static_cast<std::size_t>(t[0])],
                 b = m.vertices[static_cast<std::size_t>(t[1])],
                 c = m.vertices[static_cast<std::size_t>(t[2])];
      const Vec3 n = cross(b - a, c - a);
      CHECK(norm(n) > 0.0);
      CHECK(dot(n, a + b + c) > 0.0);  // counter-clockwise about the outward normals
    }
    const double area = implicit_mesh_area(m);
    CHECK(area < 4.0 * std::numbers::pi);
    CHECK(area > previous);
    previous = area;
  }
  CHECK(previous > 0.98 * 4.0 * std::numbers::pi);
}

TEST_CASE("implicit surface mesh: clipped by the box at z = 0, the upper half sphere") {
  const Mesh m = implicit_sphere_mesh(0.0, 32);
  for (const Vec3& v : m.vertices) CHECK(v.z >= 0.0);
  const double area = implicit_mesh_area(m);
  CHECK(area < 2.0 * std::numbers::pi);
  CHECK(area > 0.97 * 2.0 * std::numbers::pi);
}
