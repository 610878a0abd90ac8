#include "mesh/implicit_surface_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>

namespace footpoint {

Mesh mesh_implicit_surface(const ImplicitSurface& surface, int resolution) {
  const Box3& box = surface.box();
  const ImplicitSurfaceEquation& equation = surface.equation();
  const int cells = std::clamp(resolution, 2, kMaxImplicitSurfaceMeshCells);
  const double longest = box.max_edge();
  int n[3];
  for (int k = 0; k < 3; ++k)
    n[k] = std::max(2, static_cast<int>(std::lround(cells * (box.hi[k] - box.lo[k]) / longest)));
  auto node = [&](int i, int j, int l) {
    const int idx[3] = {i, j, l};
    Vec3 x;
    for (int k = 0; k < 3; ++k)
      x[k] = idx[k] == n[k] ? box.hi[k] : box.lo[k] + (box.hi[k] - box.lo[k]) * idx[k] / n[k];
    return x;
  };
  auto id = [&](int i, int j, int l) {
    return static_cast<std::int64_t>(i) +
           static_cast<std::int64_t>(n[0] + 1) * (j + static_cast<std::int64_t>(n[1] + 1) * l);
  };
  std::vector<double> values(static_cast<std::size_t>((n[0] + 1) * (n[1] + 1) * (n[2] + 1)));
  for (int l = 0; l <= n[2]; ++l)
    for (int j = 0; j <= n[1]; ++j)
      for (int i = 0; i <= n[0]; ++i)
        values[static_cast<std::size_t>(id(i, j, l))] = equation.value(node(i, j, l));

  Mesh mesh;
  const double cell =
      std::max({(box.hi.x - box.lo.x) / n[0], (box.hi.y - box.lo.y) / n[1], (box.hi.z - box.lo.z) / n[2]});
  std::unordered_map<std::int64_t, std::int32_t> on_edge;  // grid edge (a, b) -> vertex, -1 none
  auto vertex = [&](std::int64_t a, Vec3 xa, std::int64_t b, Vec3 xb) -> std::int32_t {
    if (a > b) {
      std::swap(a, b);
      std::swap(xa, xb);
    }
    const std::int64_t key = a * static_cast<std::int64_t>(values.size()) + b;
    if (const auto it = on_edge.find(key); it != on_edge.end()) return it->second;
    const double fa = values[static_cast<std::size_t>(a)], fb = values[static_cast<std::size_t>(b)];
    Vec3 x = xa + (fa / (fa - fb)) * (xb - xa);
    std::int32_t v = -1;
    if (land_on_surface(equation, x) && box.contains(x) && norm(x - xa) <= 2.0 * cell) {
      const ImplicitSurfaceJet j = equation.jet(x);
      const double g = norm(j.grad);
      if (g > 0.0 && std::isfinite(g)) {
        v = static_cast<std::int32_t>(mesh.vertices.size());
        mesh.vertices.push_back(x);
        mesh.normals.push_back(j.grad / g);
      }
    }
    on_edge.emplace(key, v);
    return v;
  };
  auto triangle = [&](std::int32_t a, std::int32_t b, std::int32_t c) {
    if (a < 0 || b < 0 || c < 0 || a == b || b == c || a == c) return;
    const Vec3 pa = mesh.vertices[static_cast<std::size_t>(a)],
               pb = mesh.vertices[static_cast<std::size_t>(b)],
               pc = mesh.vertices[static_cast<std::size_t>(c)];
    const Vec3 normal = cross(pb - pa, pc - pa);
    if (!(norm(normal) > 0.0)) return;
    const Vec3 mean = mesh.normals[static_cast<std::size_t>(a)] + mesh.normals[static_cast<std::size_t>(b)] +
                      mesh.normals[static_cast<std::size_t>(c)];
    if (dot(normal, mean) >= 0.0)
      mesh.triangles.push_back({a, b, c});
    else
      mesh.triangles.push_back({a, c, b});
  };
  // The six tetrahedra of a cube about its diagonal from corner 0 to corner 7 (corner bits: x, y, z).
  static constexpr int kTets[6][4] = {{0, 1, 3, 7}, {0, 3, 2, 7}, {0, 2, 6, 7},
                                      {0, 6, 4, 7}, {0, 4, 5, 7}, {0, 5, 1, 7}};
  for (int l = 0; l < n[2]; ++l)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i) {
        std::int64_t ids[8];
        Vec3 xs[8];
        for (int c = 0; c < 8; ++c) {
          ids[c] = id(i + (c & 1), j + ((c >> 1) & 1), l + ((c >> 2) & 1));
          xs[c] = node(i + (c & 1), j + ((c >> 1) & 1), l + ((c >> 2) & 1));
        }
        for (const auto& tet : kTets) {
          int inside[4], outside[4], ni = 0, no = 0;
          for (const int c : tet) {
            const double f = values[static_cast<std::size_t>(ids[c])];
            if (!std::isfinite(f)) {
              ni = no = -1;
              break;
            }
            (f < 0.0 ? inside[ni++] : outside[no++]) = c;
          }
          if (ni <= 0 || no <= 0) continue;
          auto v = [&](int a, int b) { return vertex(ids[a], xs[a], ids[b], xs[b]); };
          if (ni == 1 || no == 1) {
            const int lone = ni == 1 ? inside[0] : outside[0];
            const int* others = ni == 1 ? outside : inside;
            triangle(v(lone, others[0]), v(lone, others[1]), v(lone, others[2]));
          } else {
            const std::int32_t a = v(inside[0], outside[0]), b = v(inside[0], outside[1]),
                               c = v(inside[1], outside[1]), d = v(inside[1], outside[0]);
            triangle(a, b, c);
            triangle(a, c, d);
          }
        }
      }
  return mesh;
}

}  // namespace footpoint
