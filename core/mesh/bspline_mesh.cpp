#include "mesh/bspline_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace footpoint {

namespace {

// Grid values over [knots[p], knots[n]]: every distinct knot, and `cells` intervals in all, each
// span getting its share of them by length (at least one).
std::vector<double> grid_of(const std::vector<double>& knots, double lo, double hi, int cells) {
  std::vector<double> breaks;
  for (const double k : knots)
    if (k >= lo && k <= hi && (breaks.empty() || k > breaks.back())) breaks.push_back(k);
  std::vector<double> out{breaks.front()};
  for (std::size_t i = 0; i + 1 < breaks.size(); ++i) {
    const double a = breaks[i], b = breaks[i + 1];
    const int n = std::max(1, static_cast<int>(std::lround(cells * (b - a) / (hi - lo))));
    for (int k = 1; k < n; ++k) out.push_back(a + (b - a) * k / n);
    out.push_back(b);
  }
  return out;
}

}  // namespace

Mesh mesh_bspline_surface(const BSplineSurface& surface, int resolution) {
  const nurbs::Surface& s = surface.surface();
  const std::vector<double> us = grid_of(s.knots_u, s.umin(), s.umax(), resolution);
  const std::vector<double> vs = grid_of(s.knots_v, s.vmin(), s.vmax(), resolution);
  const bool closed_u = surface.closed()[0], closed_v = surface.closed()[1];
  // Columns (rows) of vertices: a closed direction's last line is its first.
  const std::size_t nu = us.size() - (closed_u ? 1 : 0), nv = vs.size() - (closed_v ? 1 : 0);
  Mesh m;
  m.num_params = 2;
  std::vector<Vec3> points(nu * nv), normals(nu * nv);
  for (std::size_t i = 0; i < nu; ++i)
    for (std::size_t j = 0; j < nv; ++j) {
      const SurfaceJet jet = nurbs::evaluate(s, us[i], vs[j]);
      points[i * nv + j] = jet.s;
      normals[i * nv + j] = unit(cross(jet.su, jet.sv));
    }
  auto index = [&](std::size_t i, std::size_t j) { return (i % nu) * nv + (j % nv); };
  std::vector<std::array<std::size_t, 3>> triangles;
  double scale = 0.0;
  for (const Vec3& p : points) scale = std::max({scale, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
  auto area2 = [&](std::size_t a, std::size_t b, std::size_t c) {
    return norm(cross(points[b] - points[a], points[c] - points[a]));
  };
  const double tiny = 1e-24 * (1.0 + scale * scale);
  for (std::size_t i = 0; i + 1 < us.size(); ++i)
    for (std::size_t j = 0; j + 1 < vs.size(); ++j) {
      const std::size_t a = index(i, j), b = index(i + 1, j), c = index(i + 1, j + 1), d = index(i, j + 1);
      const bool split_ac = norm(points[c] - points[a]) <= norm(points[d] - points[b]);
      const std::array<std::array<std::size_t, 3>, 2> pair =
          split_ac ? std::array<std::array<std::size_t, 3>, 2>{{{a, b, c}, {a, c, d}}}
                   : std::array<std::array<std::size_t, 3>, 2>{{{a, b, d}, {b, c, d}}};
      for (const auto& t : pair)
        if (area2(t[0], t[1], t[2]) > tiny) triangles.push_back(t);
    }
  // Pole vertices (no normal of their own): the mean of the incident triangles' normals.
  std::vector<Vec3> fan(points.size(), Vec3{});
  for (const auto& t : triangles) {
    const Vec3 n = cross(points[t[1]] - points[t[0]], points[t[2]] - points[t[0]]);
    for (const std::size_t v : t) fan[v] = fan[v] + n;
  }
  std::vector<std::int32_t> renumber(points.size(), -1);
  for (const auto& t : triangles) {
    std::array<std::int32_t, 3> out{};
    for (int k = 0; k < 3; ++k) {
      const std::size_t v = t[static_cast<std::size_t>(k)];
      if (renumber[v] < 0) {
        renumber[v] = static_cast<std::int32_t>(m.vertices.size());
        m.vertices.push_back(points[v]);
        m.normals.push_back(norm(normals[v]) > 0.0 ? normals[v] : unit(fan[v]));
        m.parameters.push_back(us[v / nv]);
        m.parameters.push_back(vs[v % nv]);
      }
      out[static_cast<std::size_t>(k)] = renumber[v];
    }
    m.triangles.push_back(out);
  }
  return m;
}

Mesh mesh_bspline_curve(const BSplineCurve& curve, int resolution) {
  const nurbs::Curve& c = curve.curve();
  const std::vector<double> ts = grid_of(c.knots, c.tmin(), c.tmax(), resolution);
  const std::size_t n = ts.size() - (curve.closed() ? 1 : 0);
  Mesh m;
  m.num_params = 1;
  Polyline line;
  line.closed = curve.closed();
  for (std::size_t i = 0; i < n; ++i) {
    const CurveJet j = nurbs::evaluate(c, ts[i]);
    line.vertices.push_back(static_cast<std::int32_t>(m.vertices.size()));
    m.vertices.push_back(j.c);
    m.tangents.push_back(unit(j.d1));
    m.parameters.push_back(ts[i]);
  }
  m.polylines.push_back(std::move(line));
  return m;
}

}  // namespace footpoint
