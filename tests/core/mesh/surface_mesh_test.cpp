// Meshes of parametric surfaces (mesh/surface_mesh): every vertex is the surface's point at its
// parameters (against the closed forms evaluated here), normals are unit and agree with the
// analytic ones, no triangle is degenerate, the winding follows the normals, a sphere's mesh has
// the sphere's area, seams and poles (found at compile time, or named by a SurfaceClosure) give a
// closed mesh with the surface's Euler characteristic and no vertex twice, and the lines crowd where
// the surface bends.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <utility>

#include "compiled/parametric_surface_geometry.hpp"
#include "mesh/mesh.hpp"
#include "mesh/surface_mesh.hpp"

using namespace footpoint;

namespace {

constexpr double kSurfacePi = std::numbers::pi;

std::shared_ptr<const CompiledGeometry> surface(const char* x, const char* y, const char* z,
                                                std::array<double, 2> u, std::array<double, 2> v,
                                                std::map<std::string, double> constants = {}) {
  GeometryDefinition def;
  def.type = GeometryType::parametric_surface;
  def.formulas = {{"x", x}, {"y", y}, {"z", z}};
  def.domain = {{"u", u}, {"v", v}};
  def.constants = std::move(constants);
  return compile_geometry(def);
}

const ParametricSurface& as_surface(const std::shared_ptr<const CompiledGeometry>& g) {
  return dynamic_cast<const ParametricSurface&>(*g);
}

Vec3 face_normal(const Mesh& m, const std::array<std::int32_t, 3>& t) {
  const Vec3 a = m.vertices[static_cast<std::size_t>(t[0])], b = m.vertices[static_cast<std::size_t>(t[1])],
             c = m.vertices[static_cast<std::size_t>(t[2])];
  return cross(b - a, c - a);
}

double area(const Mesh& m) {
  double sum = 0.0;
  for (const auto& t : m.triangles) sum += 0.5 * norm(face_normal(m, t));
  return sum;
}

// Every triangle: three distinct vertices, area above 1e-9 of its longest edge squared, its
// winding turning about the vertices' normals; every vertex and normal finite, every normal unit.
void check_well_formed_triangles(const Mesh& m) {
  REQUIRE(m.normals.size() == m.vertices.size());
  REQUIRE(m.parameters.size() == 2 * m.vertices.size());
  REQUIRE(!m.triangles.empty());
  std::vector<bool> used(m.vertices.size(), false);
  for (const auto& t : m.triangles) {
    for (std::int32_t k : t) {
      REQUIRE(k >= 0);
      REQUIRE(static_cast<std::size_t>(k) < m.vertices.size());
      used[static_cast<std::size_t>(k)] = true;
    }
    CHECK(t[0] != t[1]);
    CHECK(t[1] != t[2]);
    CHECK(t[0] != t[2]);
    const Vec3 a = m.vertices[static_cast<std::size_t>(t[0])], b = m.vertices[static_cast<std::size_t>(t[1])],
               c = m.vertices[static_cast<std::size_t>(t[2])];
    const double longest = std::max({norm2(b - a), norm2(c - b), norm2(a - c)});
    CHECK(0.5 * norm(face_normal(m, t)) > 1e-9 * longest);
    const Vec3 mean_normal = m.normals[static_cast<std::size_t>(t[0])] +
                             m.normals[static_cast<std::size_t>(t[1])] +
                             m.normals[static_cast<std::size_t>(t[2])];
    CHECK(dot(face_normal(m, t), mean_normal) > 0.0);
  }
  for (std::size_t k = 0; k < m.vertices.size(); ++k) {
    CHECK(used[k]);
    CHECK(is_finite(m.vertices[k]));
    CHECK(std::abs(norm(m.normals[k]) - 1.0) <= 1e-14);
  }
}

// Edges (as vertex pairs) and how many triangles hold each.
std::map<std::pair<std::int32_t, std::int32_t>, int> edge_counts(const Mesh& m) {
  std::map<std::pair<std::int32_t, std::int32_t>, int> edges;
  for (const auto& t : m.triangles)
    for (int k = 0; k < 3; ++k) ++edges[std::minmax(t[k], t[(k + 1) % 3])];
  return edges;
}

}  // namespace

TEST_CASE("sphere mesh: vertices on the sphere, analytic normals, the sphere's area within 1 %") {
  const double R = 2.0;
  const auto g = surface("R*sin(u)*cos(v)", "R*sin(u)*sin(v)", "R*cos(u)", {0, kSurfacePi},
                         {0, 2 * kSurfacePi}, {{"R", R}});
  const Mesh m = mesh_geometry(*g, MeshOptions{64});
  check_well_formed_triangles(m);
  for (std::size_t k = 0; k < m.vertices.size(); ++k) {
    const double u = m.parameters[2 * k], v = m.parameters[2 * k + 1];
    const Vec3 expected{R * std::sin(u) * std::cos(v), R * std::sin(u) * std::sin(v), R * std::cos(u)};
    CHECK(norm(m.vertices[k] - expected) <= 1e-15 * R);
    CHECK(std::abs(norm(m.vertices[k]) - R) <= 1e-15 * R);
    // s_u x s_v points outward; at the poles (no tangent plane) the incident triangles' mean.
    const double radial = dot(m.normals[k], m.vertices[k] / R);
    const bool pole = std::hypot(m.vertices[k].x, m.vertices[k].y) < 1e-9;
    CHECK(radial >= (pole ? 0.99 : 1.0 - 1e-14));
  }
  const double exact = 4.0 * kSurfacePi * R * R;
  INFO("mesh area " << area(m) << ", sphere " << exact);
  CHECK(std::abs(area(m) - exact) <= 0.01 * exact);
  // An inscribed polyhedron lies inside: its area is below the sphere's.
  CHECK(area(m) < exact);
}

TEST_CASE("the resolution bounds the cells along each direction") {
  const auto g = surface("R*sin(u)*cos(v)", "R*sin(u)*sin(v)", "R*cos(u)", {0, kSurfacePi},
                         {0, 2 * kSurfacePi}, {{"R", 1}});
  for (int n : {2, 3, 17, 100}) {
    const Mesh m = mesh_geometry(*g, MeshOptions{n});
    CHECK(m.vertices.size() <= static_cast<std::size_t>((n + 1) * (n + 1)));
    CHECK(m.triangles.size() <= static_cast<std::size_t>(2 * n * n));
    // At 2 cells a direction the grid lines v = 0, pi, 2 pi put every vertex in the plane y = 0:
    // a flat mesh whose triangles stand edge-on to the sphere's normals.
    if (n > 2) check_well_formed_triangles(m);
  }
  CHECK_THROWS_AS(mesh_geometry(*g, MeshOptions{1}), std::invalid_argument);
}

TEST_CASE("the detected closure stitches seams and poles: the sphere and the torus give closed meshes") {
  SUBCASE("sphere: one vertex per pole, every edge in two triangles, V - E + F = 2") {
    const auto g = surface("sin(u)*cos(v)", "sin(u)*sin(v)", "cos(u)", {0, kSurfacePi}, {0, 2 * kSurfacePi});
    const Mesh m = mesh_parametric_surface(as_surface(g), 40);
    check_well_formed_triangles(m);
    int poles = 0;
    for (const Vec3& x : m.vertices) poles += std::hypot(x.x, x.y) < 1e-9;
    CHECK(poles == 2);
    const auto edges = edge_counts(m);
    for (const auto& [edge, count] : edges) CHECK(count == 2);
    CHECK(static_cast<long>(m.vertices.size()) - static_cast<long>(edges.size()) +
              static_cast<long>(m.triangles.size()) ==
          2);
    for (std::size_t k = 0; k < m.vertices.size(); ++k)
      CHECK(dot(m.normals[k], m.vertices[k]) >= 1.0 - 1e-12);  // the pole's fan averages to the axis
    CHECK(std::abs(area(m) - 4 * kSurfacePi) <= 0.01 * 4 * kSurfacePi);
  }
  SUBCASE("torus: both directions closed, V - E + F = 0") {
    const auto g =
        surface("(2+cos(v))*cos(u)", "(2+cos(v))*sin(u)", "sin(v)", {0, 2 * kSurfacePi}, {0, 2 * kSurfacePi});
    const Mesh m = mesh_parametric_surface(as_surface(g), 48);
    check_well_formed_triangles(m);
    const auto edges = edge_counts(m);
    for (const auto& [edge, count] : edges) CHECK(count == 2);
    CHECK(static_cast<long>(m.vertices.size()) - static_cast<long>(edges.size()) +
              static_cast<long>(m.triangles.size()) ==
          0);
    const double exact = 4 * kSurfacePi * kSurfacePi * 2 * 1;  // 4 pi^2 R r
    CHECK(std::abs(area(m) - exact) <= 0.01 * exact);
  }
  SUBCASE("without a closure the torus mesh is a grid with open seams of the same area") {
    const auto g =
        surface("(2+cos(v))*cos(u)", "(2+cos(v))*sin(u)", "sin(v)", {0, 2 * kSurfacePi}, {0, 2 * kSurfacePi});
    const Mesh m = mesh_parametric_surface(as_surface(g), 48, SurfaceClosure{});
    check_well_formed_triangles(m);
    int boundary = 0;
    for (const auto& [edge, count] : edge_counts(m)) boundary += count == 1;
    CHECK(boundary > 0);
    CHECK(std::abs(area(m) - 8 * kSurfacePi * kSurfacePi) <= 0.01 * 8 * kSurfacePi * kSurfacePi);
  }
}

namespace {

long euler_characteristic(const Mesh& m) {
  return static_cast<long>(m.vertices.size()) - static_cast<long>(edge_counts(m).size()) +
         static_cast<long>(m.triangles.size());
}

// Edges in one triangle only (the mesh's boundary).
int boundary_edges(const Mesh& m) {
  int n = 0;
  for (const auto& [edge, count] : edge_counts(m)) n += count == 1;
  return n;
}

// No two vertices at one point (a seam's or a pole's vertices are not repeated).
void check_no_duplicates(const Mesh& m, double size) {
  std::vector<std::size_t> order(m.vertices.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return m.vertices[a].x < m.vertices[b].x; });
  int duplicates = 0;
  for (std::size_t i = 0; i < order.size(); ++i)
    for (std::size_t j = i + 1;
         j < order.size() && m.vertices[order[j]].x - m.vertices[order[i]].x <= 1e-9 * size; ++j)
      duplicates += norm(m.vertices[order[i]] - m.vertices[order[j]]) <= 1e-9 * size;
  CHECK(duplicates == 0);
}

}  // namespace

TEST_CASE("closed meshes from the API's path (mesh_geometry): Euler characteristics, no duplicate vertices") {
  SUBCASE("torus: V - E + F = 0, every edge in two triangles") {
    const auto g = surface("(2+0.5*cos(v))*cos(u)", "(2+0.5*cos(v))*sin(u)", "0.5*sin(v)",
                           {0, 2 * kSurfacePi}, {0, 2 * kSurfacePi});
    const Mesh m = mesh_geometry(*g, MeshOptions{40});
    check_well_formed_triangles(m);
    CHECK(euler_characteristic(m) == 0);
    CHECK(boundary_edges(m) == 0);
    check_no_duplicates(m, 5.0);
  }
  SUBCASE("sphere over longitude x latitude (tests/data/surface_sphere.json): V - E + F = 2") {
    const auto g = surface("cos(u)*cos(v)", "sin(u)*cos(v)", "sin(v)", {0, 2 * kSurfacePi},
                           {-kSurfacePi / 2, kSurfacePi / 2});
    const Mesh m = mesh_geometry(*g, MeshOptions{40});
    check_well_formed_triangles(m);
    CHECK(euler_characteristic(m) == 2);
    CHECK(boundary_edges(m) == 0);
    check_no_duplicates(m, 2.0);
  }
  SUBCASE("cylinder: one seam, two boundary circles, V - E + F = 0") {
    const auto g = surface("cos(u)", "sin(u)", "v", {0, 2 * kSurfacePi}, {-1, 1});
    const Mesh m = mesh_geometry(*g, MeshOptions{40});
    check_well_formed_triangles(m);
    CHECK(euler_characteristic(m) == 0);
    // The two circles: as many boundary edges as cells around, each circle closed.
    const auto& closure = as_surface(g).closure();
    CHECK(closure.periodic(0));
    int around = 0;
    for (std::size_t k = 0; k < m.vertices.size(); ++k) around += m.parameters[2 * k + 1] == -1.0;
    CHECK(boundary_edges(m) == 2 * around);
    check_no_duplicates(m, 3.0);
  }
  SUBCASE("cone: the apex one vertex, a disc, V - E + F = 1") {
    const auto g = surface("v*cos(u)", "v*sin(u)", "v", {0, 2 * kSurfacePi}, {0, 1});
    const Mesh m = mesh_geometry(*g, MeshOptions{40});
    check_well_formed_triangles(m);
    CHECK(euler_characteristic(m) == 1);
    int apex = 0;
    for (const Vec3& x : m.vertices) apex += norm(x) == 0.0;
    CHECK(apex == 1);
    check_no_duplicates(m, 2.0);
  }
  SUBCASE("Möbius band: its reversed seam is left open, the grid well formed") {
    const auto g = surface("(1+v*cos(u/2))*cos(u)", "(1+v*cos(u/2))*sin(u)", "v*sin(u/2)",
                           {0, 2 * kSurfacePi}, {-0.5, 0.5});
    CHECK(as_surface(g).closure().seams[0].reversed);
    const Mesh m = mesh_geometry(*g, MeshOptions{40});
    check_well_formed_triangles(m);
    CHECK(euler_characteristic(m) == 1);  // a disc: the grid, unstitched
  }
  SUBCASE("a plane stays a grid") {
    const auto g = surface("u", "v", "u*v", {-1, 1}, {-1, 1});
    const Mesh m = mesh_geometry(*g, MeshOptions{20});
    CHECK(euler_characteristic(m) == 1);
  }
}

TEST_CASE("grid lines crowd where the surface bends and stay uniform where it does not") {
  // z = exp(-20 u^2): bends near u = 0 only; along v a straight line of uniform speed.
  const auto g = surface("u", "v", "exp(-20*u^2)", {-1, 1}, {-1, 1});
  const int n = 24;
  const Mesh m = mesh_geometry(*g, MeshOptions{n});
  check_well_formed_triangles(m);
  std::vector<double> us, vs;
  for (std::size_t k = 0; k < m.vertices.size(); ++k) {
    us.push_back(m.parameters[2 * k]);
    vs.push_back(m.parameters[2 * k + 1]);
  }
  for (auto* lines : {&us, &vs}) {
    std::sort(lines->begin(), lines->end());
    lines->erase(std::unique(lines->begin(), lines->end()), lines->end());
  }
  REQUIRE(vs.size() >= 3);
  for (std::size_t j = 0; j + 1 < vs.size(); ++j)
    CHECK(vs[j + 1] - vs[j] == doctest::Approx(2.0 / static_cast<double>(vs.size() - 1)).epsilon(1e-9));
  // The largest gap between the profile z(u) and its chords, for these lines and for as many
  // uniform ones.
  auto chord_error = [](const std::vector<double>& lines) {
    double worst = 0.0;
    for (std::size_t i = 0; i + 1 < lines.size(); ++i)
      for (int s = 1; s < 16; ++s) {
        const double a = lines[i], b = lines[i + 1], t = s / 16.0, u = a + t * (b - a);
        const double chord = (1 - t) * std::exp(-20 * a * a) + t * std::exp(-20 * b * b);
        worst = std::max(worst, std::abs(std::exp(-20 * u * u) - chord));
      }
    return worst;
  };
  std::vector<double> uniform(us.size());
  for (std::size_t i = 0; i < us.size(); ++i)
    uniform[i] = -1.0 + 2.0 * i / static_cast<double>(us.size() - 1);
  INFO("chord error, equidistributed " << chord_error(us) << ", uniform " << chord_error(uniform));
  CHECK(chord_error(us) < 0.6 * chord_error(uniform));
  const double middle_gap =
      *std::upper_bound(us.begin(), us.end(), 0.0) - *(std::upper_bound(us.begin(), us.end(), 0.0) - 1);
  CHECK(middle_gap < us.back() - us[us.size() - 2]);
}

TEST_CASE("where the formulas are not finite the mesh leaves the part out") {
  // The upper unit hemisphere over [-1, 1]^2: sqrt of a negative number outside the disc.
  const auto g = surface("u", "v", "sqrt(1-u^2-v^2)", {-1, 1}, {-1, 1});
  const Mesh m = mesh_geometry(*g, MeshOptions{48});
  check_well_formed_triangles(m);
  for (std::size_t k = 0; k < m.vertices.size(); ++k) {
    const double u = m.parameters[2 * k], v = m.parameters[2 * k + 1];
    CHECK(u * u + v * v <= 1.0);
    CHECK(std::abs(norm(m.vertices[k]) - 1.0) <= 1e-15);
  }
  CHECK(area(m) > 0.75 * 2 * kSurfacePi);  // most of the hemisphere: the steep cells at the rim are cut
  CHECK(area(m) < 2 * kSurfacePi);
}
