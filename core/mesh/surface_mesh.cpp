#include "mesh/surface_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

#include "mesh/equidistribution.hpp"

namespace footpoint {

namespace {

// Cross lines the measure of a direction is averaged over, and fine intervals per cell (at
// least kMinFine) it is sampled on.
constexpr int kCrossLines = 9;
constexpr int kFinePerCell = 4;
constexpr int kMinFine = 64;
// |s_u x s_v| below this fraction of |s_u| |s_v| defines no tangent plane.
constexpr double kNoTangentPlane = 1e-10;
// A triangle whose area is below this fraction of its longest edge squared is degenerate (an
// equilateral triangle has 0.43; a quad at a pole collapses to ~1e-16).
constexpr double kDegenerateArea = 1e-9;

// The unit normal s_u x s_v / |.|, or 0 where there is no tangent plane.
Vec3 unit_normal(const SurfaceJet& j) {
  const Vec3 n = cross(j.su, j.sv);
  const double length = norm(n);
  if (!(length > kNoTangentPlane * norm(j.su) * norm(j.sv)) || !is_finite(n)) return {};
  return n / length;
}

// The fine intervals along u (along_u) or v: chord length and normal turn, averaged over the
// cross lines.
std::vector<FineInterval> sample_direction(const SurfaceFormulas& formulas, const ParamBox& box, bool along_u,
                                           int fine) {
  const double lo = along_u ? box.umin : box.vmin, hi = along_u ? box.umax : box.vmax;
  const double cross_lo = along_u ? box.vmin : box.umin, cross_hi = along_u ? box.vmax : box.umax;
  std::vector<FineInterval> out(static_cast<std::size_t>(fine));
  for (int l = 0; l < kCrossLines; ++l) {
    const double c = cross_lo + (cross_hi - cross_lo) * l / (kCrossLines - 1);
    Vec3 last_point, last_normal;
    for (int k = 0; k <= fine; ++k) {
      const double t = k == fine ? hi : lo + (hi - lo) * k / fine;
      const SurfaceJet j = along_u ? formulas.jet(t, c) : formulas.jet(c, t);
      const Vec3 n = unit_normal(j);
      if (k > 0) {
        FineInterval& f = out[static_cast<std::size_t>(k - 1)];
        const double chord = norm(j.s - last_point);
        if (std::isfinite(chord)) f.length += chord / kCrossLines;
        f.turn += turn_angle(last_normal, n) / kCrossLines;
      }
      last_point = j.s;
      last_normal = n;
    }
  }
  return out;
}

// Cells along u and v: the direction with the larger share of the measure (half by length, half
// by turn, as the lines are placed) gets `resolution`, the other its proportion, at least 2.
std::pair<int, int> cell_counts(const Measure& u, const Measure& v, int resolution) {
  auto share = [](double a, double b) { return a + b > 0.0 ? a / (a + b) : 0.5; };
  const double by_length = share(u.length, v.length);
  const double wu = by_length + (u.turn + v.turn > kNoTurn ? share(u.turn, v.turn) : by_length);
  const double wv = 2.0 - wu;
  auto scaled = [resolution](double w, double wmax) {
    return std::max(2, static_cast<int>(std::lround(resolution * w / wmax)));
  };
  return wu >= wv ? std::pair{resolution, scaled(wv, wu)} : std::pair{scaled(wu, wv), resolution};
}

}  // namespace

Mesh mesh_parametric_surface(const ParametricSurface& surface, int resolution) {
  return mesh_parametric_surface(surface, resolution, surface.closure());
}

Mesh mesh_parametric_surface(const ParametricSurface& surface, int resolution,
                             const SurfaceClosure& closure) {
  const SurfaceFormulas& formulas = surface.formulas();
  const ParamBox& box = surface.domain();
  const int fine = std::max(kMinFine, kFinePerCell * resolution);
  const std::vector<FineInterval> fine_u = sample_direction(formulas, box, true, fine);
  const std::vector<FineInterval> fine_v = sample_direction(formulas, box, false, fine);
  const std::pair<int, int> counts = cell_counts(total(fine_u), total(fine_v), resolution);
  const int nu = counts.first, nv = counts.second;
  const std::vector<double> us = equidistributed_lines(box.umin, box.umax, fine_u, nu);
  const std::vector<double> vs = equidistributed_lines(box.vmin, box.vmax, fine_v, nv);

  // The grid point (i, j) stands for the vertex of its canonical point: a closed direction's last
  // line is its first, a pole edge is its first point.
  auto canonical = [&](int i, int j) {
    for (int pass = 0; pass < 2; ++pass) {
      if (closure.periodic(0) && i == nu) i = 0;
      if (closure.periodic(1) && j == nv) j = 0;
      if (closure.pole(BoxEdge::umin) && i == 0) j = 0;
      if (closure.pole(BoxEdge::umax) && i == nu) j = 0;
      if (closure.pole(BoxEdge::vmin) && j == 0) i = 0;
      if (closure.pole(BoxEdge::vmax) && j == nv) i = 0;
    }
    return std::pair{i, j};
  };
  auto at = [nv](int i, int j) { return static_cast<std::size_t>(i) * static_cast<std::size_t>(nv + 1) + j; };

  struct GridVertex {
    Vec3 point, normal;  // normal 0: no tangent plane
    double u = 0.0, v = 0.0;
    bool finite = false;
  };
  std::vector<GridVertex> grid;
  std::vector<std::int32_t> id(at(nu, nv) + 1, -1);
  for (int i = 0; i <= nu; ++i)
    for (int j = 0; j <= nv; ++j) {
      if (canonical(i, j) != std::pair{i, j}) continue;
      const double u = us[static_cast<std::size_t>(i)], v = vs[static_cast<std::size_t>(j)];
      const SurfaceJet jet = formulas.jet(u, v);
      id[at(i, j)] = static_cast<std::int32_t>(grid.size());
      grid.push_back({jet.s, unit_normal(jet), u, v, is_finite(jet.s)});
    }
  for (int i = 0; i <= nu; ++i)
    for (int j = 0; j <= nv; ++j) {
      const auto [ci, cj] = canonical(i, j);
      id[at(i, j)] = id[at(ci, cj)];
    }

  // Triangles of each quad a = (i, j), b = (i+1, j), c = (i+1, j+1), d = (i, j+1): a -> b runs
  // along s_u and b -> c along s_v, so (a, b, c) turns counter-clockwise about s_u x s_v.
  std::vector<std::array<std::int32_t, 3>> triangles;
  // Area-weighted sums of the incident triangles' normals, for vertices without a tangent plane,
  // and the last incident triangle's, should the sum cancel (a surface folded onto itself).
  std::vector<Vec3> face_normals(grid.size()), last_face(grid.size());
  auto add_triangle = [&](std::int32_t a, std::int32_t b, std::int32_t c) {
    if (a == b || b == c || a == c) return;
    const GridVertex &pa = grid[static_cast<std::size_t>(a)], &pb = grid[static_cast<std::size_t>(b)],
                     &pc = grid[static_cast<std::size_t>(c)];
    if (!pa.finite || !pb.finite || !pc.finite) return;
    const Vec3 twice_area = cross(pb.point - pa.point, pc.point - pa.point);
    const double longest =
        std::max({norm2(pb.point - pa.point), norm2(pc.point - pb.point), norm2(pa.point - pc.point)});
    if (!(0.5 * norm(twice_area) > kDegenerateArea * longest)) return;
    triangles.push_back({a, b, c});
    for (std::int32_t k : {a, b, c}) {
      face_normals[static_cast<std::size_t>(k)] += twice_area;
      last_face[static_cast<std::size_t>(k)] = twice_area;
    }
  };
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const std::int32_t a = id[at(i, j)], b = id[at(i + 1, j)], c = id[at(i + 1, j + 1)],
                         d = id[at(i, j + 1)];
      const auto& g = grid;
      const double ac = norm2(g[static_cast<std::size_t>(a)].point - g[static_cast<std::size_t>(c)].point);
      const double bd = norm2(g[static_cast<std::size_t>(b)].point - g[static_cast<std::size_t>(d)].point);
      if (ac <= bd) {
        add_triangle(a, b, c);
        add_triangle(a, c, d);
      } else {
        add_triangle(a, b, d);
        add_triangle(b, c, d);
      }
    }

  // Only the vertices some triangle uses, renumbered in grid order.
  Mesh mesh;
  mesh.num_params = 2;
  std::vector<std::int32_t> renumbered(grid.size(), -1);
  for (const auto& t : triangles)
    for (std::int32_t k : t) renumbered[static_cast<std::size_t>(k)] = 0;
  for (std::size_t k = 0; k < grid.size(); ++k) {
    if (renumbered[k] < 0) continue;
    renumbered[k] = static_cast<std::int32_t>(mesh.vertices.size());
    const GridVertex& g = grid[k];
    mesh.vertices.push_back(g.point);
    const Vec3 mean = norm2(face_normals[k]) > 0.0 ? face_normals[k] : last_face[k];
    mesh.normals.push_back(norm2(g.normal) > 0.0 ? g.normal : mean / norm(mean));
    mesh.parameters.push_back(g.u);
    mesh.parameters.push_back(g.v);
  }
  mesh.triangles.reserve(triangles.size());
  for (const auto& t : triangles)
    mesh.triangles.push_back({renumbered[static_cast<std::size_t>(t[0])],
                              renumbered[static_cast<std::size_t>(t[1])],
                              renumbered[static_cast<std::size_t>(t[2])]});
  return mesh;
}

}  // namespace footpoint
