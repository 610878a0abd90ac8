#include "parametric/geometry/nurbs.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace footpoint::nurbs {

namespace {

constexpr int kTable = kMaxDegree + 1;
using Homogeneous = std::array<double, 4>;

Homogeneous scaled(const Homogeneous& a, double s) { return {a[0] * s, a[1] * s, a[2] * s, a[3] * s}; }
void add_to(Homogeneous& a, const Homogeneous& b) {
  for (int k = 0; k < 4; ++k) a[k] += b[k];
}
Vec3 xyz(const Homogeneous& a) { return {a[0], a[1], a[2]}; }

DefinitionError error(std::string field, std::string message) {
  return {std::move(field), std::move(message)};
}

// "name[i]" and "name[i][j]", appended piece by piece (GCC 12 warns falsely about operator+ on a
// literal and a temporary string: -Wrestrict)
std::string element(const std::string& name, std::size_t i) {
  std::string out = name;
  out += '[';
  out += std::to_string(i);
  out += ']';
  return out;
}
std::string element(const std::string& name, std::size_t i, std::size_t j) {
  return element(element(name, i), j);
}

std::optional<DefinitionError> check_knots(const std::string& field, int degree, std::size_t count,
                                           const std::vector<double>& knots) {
  const std::size_t want = count + static_cast<std::size_t>(degree) + 1;
  if (knots.size() != want)
    return error(field, "needs " + std::to_string(want) + " knots (control points + degree + 1), got " +
                            std::to_string(knots.size()));
  for (std::size_t i = 0; i < knots.size(); ++i) {
    if (!std::isfinite(knots[i])) return error(element(field, i), "is not finite");
    if (i > 0 && knots[i] < knots[i - 1])
      return error(element(field, i), "decreases: knots must be non-decreasing");
  }
  if (!(knots[static_cast<std::size_t>(degree)] < knots[count]))
    return error(field, "the domain [knots[degree], knots[control points]] is empty");
  return std::nullopt;
}

std::optional<DefinitionError> check_degree(const std::string& field, int degree) {
  if (degree < 1 || degree > kMaxDegree)
    return error(field,
                 "must be between 1 and " + std::to_string(kMaxDegree) + ", got " + std::to_string(degree));
  return std::nullopt;
}

std::optional<DefinitionError> check_weight(const std::string& field, double w) {
  if (!std::isfinite(w) || !(w > 0.0)) return error(field, "must be finite and > 0");
  return std::nullopt;
}

// The homogeneous point (w x, w y, w z, w) of a control point of `dimension` coordinates.
std::optional<DefinitionError> weigh(const std::string& field, const std::vector<double>& point,
                                     int dimension, double w, Homogeneous& out) {
  if (static_cast<int>(point.size()) != dimension)
    return error(
        field, "has " + std::to_string(point.size()) + " coordinates, expected " + std::to_string(dimension));
  for (double x : point)
    if (!std::isfinite(x)) return error(field, "has a coordinate that is not finite");
  out = {w * point[0], w * point[1], dimension == 3 ? w * point[2] : 0.0, w};
  return std::nullopt;
}

}  // namespace

int find_span(int n, int p, double u, const std::vector<double>& U) {
  if (u >= U[static_cast<std::size_t>(n)]) {
    int i = n - 1;
    while (i > p && !(U[static_cast<std::size_t>(i)] < U[static_cast<std::size_t>(i) + 1])) --i;
    return i;
  }
  if (u <= U[static_cast<std::size_t>(p)]) {
    int i = p;
    while (i < n - 1 && !(U[static_cast<std::size_t>(i)] < U[static_cast<std::size_t>(i) + 1])) ++i;
    return i;
  }
  int low = p, high = n;  // U[low] <= u < U[high]
  while (high - low > 1) {
    const int mid = (low + high) / 2;
    if (u < U[static_cast<std::size_t>(mid)])
      high = mid;
    else
      low = mid;
  }
  return low;
}

void basis_derivatives(int i, double u, int p, int d, const std::vector<double>& U, double* ders) {
  auto knot = [&](int k) { return U[static_cast<std::size_t>(k)]; };
  double ndu[kTable][kTable], left[kTable], right[kTable], a[2][kTable];
  ndu[0][0] = 1.0;
  for (int j = 1; j <= p; ++j) {
    left[j] = u - knot(i + 1 - j);
    right[j] = knot(i + j) - u;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      ndu[j][r] = right[r + 1] + left[j - r];  // knot differences across the span: > 0
      const double temp = ndu[r][j - 1] / ndu[j][r];
      ndu[r][j] = saved + right[r + 1] * temp;
      saved = left[j - r] * temp;
    }
    ndu[j][j] = saved;
  }
  const int width = p + 1;
  for (int j = 0; j <= p; ++j) ders[j] = ndu[j][p];
  for (int r = 0; r <= p; ++r) {
    int s1 = 0, s2 = 1;
    a[0][0] = 1.0;
    for (int k = 1; k <= d; ++k) {
      double sum = 0.0;
      const int rk = r - k, pk = p - k;
      if (r >= k) {
        a[s2][0] = a[s1][0] / ndu[pk + 1][rk];
        sum = a[s2][0] * ndu[rk][pk];
      }
      const int j1 = rk >= -1 ? 1 : -rk;
      const int j2 = r - 1 <= pk ? k - 1 : p - r;
      for (int j = j1; j <= j2; ++j) {
        a[s2][j] = (a[s1][j] - a[s1][j - 1]) / ndu[pk + 1][rk + j];
        sum += a[s2][j] * ndu[rk + j][pk];
      }
      if (r <= pk) {
        a[s2][k] = -a[s1][k - 1] / ndu[pk + 1][r];
        sum += a[s2][k] * ndu[r][pk];
      }
      ders[k * width + r] = sum;
      std::swap(s1, s2);
    }
  }
  double factor = p;  // p! / (p - k)!
  for (int k = 1; k <= d; ++k) {
    for (int j = 0; j <= p; ++j) ders[k * width + j] *= factor;
    factor *= p - k;
  }
}

CurveOrError make_curve(int degree, const std::vector<double>& knots,
                        const std::vector<std::vector<double>>& control_points,
                        const std::vector<double>& weights, std::size_t max_points) {
  CurveOrError out;
  auto fail = [&](const DefinitionError& e) {
    out.error = e;
    return out;
  };
  if (auto e = check_degree("degree", degree)) return fail(*e);
  const std::size_t n = control_points.size();
  if (n < static_cast<std::size_t>(degree) + 1)
    return fail(
        error("control_points", "needs at least degree + 1 = " + std::to_string(degree + 1) + " points"));
  if (n > max_points)
    return fail(error("control_points", "has " + std::to_string(n) + " points, more than the limit " +
                                            std::to_string(max_points)));
  const int dimension = static_cast<int>(control_points[0].size());
  if (dimension != 2 && dimension != 3)
    return fail(error("control_points[0]", "must have 2 or 3 coordinates"));
  if (auto e = check_knots("knots", degree, n, knots)) return fail(*e);
  if (!weights.empty() && weights.size() != n)
    return fail(error("weights", "needs one weight per control point (" + std::to_string(n) + "), got " +
                                     std::to_string(weights.size())));
  Curve c;
  c.degree = degree;
  c.knots = knots;
  c.dimension = dimension;
  c.weighted.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double w = weights.empty() ? 1.0 : weights[i];
    if (auto e = check_weight(element("weights", i), w)) return fail(*e);
    if (w != 1.0) c.rational = true;
    if (auto e = weigh(element("control_points", i), control_points[i], dimension, w, c.weighted[i]))
      return fail(*e);
  }
  out.curve = std::move(c);
  return out;
}

SurfaceOrError make_surface(const std::array<int, 2>& degree, const std::vector<double>& knots_u,
                            const std::vector<double>& knots_v,
                            const std::vector<std::vector<std::vector<double>>>& control_points,
                            const std::vector<std::vector<double>>& weights, std::size_t max_points) {
  SurfaceOrError out;
  auto fail = [&](const DefinitionError& e) {
    out.error = e;
    return out;
  };
  if (auto e = check_degree("degree[0]", degree[0])) return fail(*e);
  if (auto e = check_degree("degree[1]", degree[1])) return fail(*e);
  const std::size_t nu = control_points.size(), nv = nu > 0 ? control_points[0].size() : 0;
  if (nu < static_cast<std::size_t>(degree[0]) + 1)
    return fail(
        error("control_points", "needs at least degree[0] + 1 = " + std::to_string(degree[0] + 1) + " rows"));
  if (nv < static_cast<std::size_t>(degree[1]) + 1)
    return fail(error("control_points[0]",
                      "needs at least degree[1] + 1 = " + std::to_string(degree[1] + 1) + " points"));
  for (std::size_t i = 0; i < nu; ++i)
    if (control_points[i].size() != nv)
      return fail(error(element("control_points", i), "has " + std::to_string(control_points[i].size()) +
                                                          " points, row 0 has " + std::to_string(nv) +
                                                          ": the net must be rectangular"));
  if (nu > max_points / nv)
    return fail(error("control_points", "has " + std::to_string(nu * nv) + " points, more than the limit " +
                                            std::to_string(max_points)));
  if (auto e = check_knots("knots.u", degree[0], nu, knots_u)) return fail(*e);
  if (auto e = check_knots("knots.v", degree[1], nv, knots_v)) return fail(*e);
  if (!weights.empty()) {
    if (weights.size() != nu) return fail(error("weights", "must have the control net's shape"));
    for (std::size_t i = 0; i < nu; ++i)
      if (weights[i].size() != nv)
        return fail(error(element("weights", i), "must have the control net's shape"));
  }
  Surface s;
  s.degree = degree;
  s.knots_u = knots_u;
  s.knots_v = knots_v;
  s.count_u = static_cast<int>(nu);
  s.count_v = static_cast<int>(nv);
  s.weighted.resize(nu * nv);
  for (std::size_t i = 0; i < nu; ++i)
    for (std::size_t j = 0; j < nv; ++j) {
      const double w = weights.empty() ? 1.0 : weights[i][j];
      if (auto e = check_weight(element("weights", i, j), w)) return fail(*e);
      if (w != 1.0) s.rational = true;
      if (auto e = weigh(element("control_points", i, j), control_points[i][j], 3, w, s.weighted[i * nv + j]))
        return fail(*e);
    }
  out.surface = std::move(s);
  return out;
}

CurveJet evaluate(const Curve& curve, double t) {
  const int p = curve.degree, n = static_cast<int>(curve.weighted.size());
  t = std::clamp(t, curve.tmin(), curve.tmax());
  const int span = find_span(n, p, t, curve.knots);
  const int d = std::min(2, p), width = p + 1;
  double ders[3 * kTable];
  basis_derivatives(span, t, p, d, curve.knots, ders);
  Homogeneous A[3] = {};  // A^(k) = Σ N^(k)_i P^w_i   (A3.2)
  for (int k = 0; k <= d; ++k)
    for (int j = 0; j <= p; ++j)
      add_to(A[k], scaled(curve.weighted[static_cast<std::size_t>(span - p + j)], ders[k * width + j]));
  // A4.2: C = A / w, C' = (A' - w' C) / w, C'' = (A'' - 2 w' C' - w'' C) / w
  const double w = A[0][3], w1 = A[1][3], w2 = A[2][3];
  CurveJet j;
  j.c = xyz(A[0]) / w;
  j.d1 = (xyz(A[1]) - w1 * j.c) / w;
  j.d2 = (xyz(A[2]) - 2.0 * w1 * j.d1 - w2 * j.c) / w;
  return j;
}

SurfaceJet evaluate(const Surface& surface, double u, double v) {
  const int p = surface.degree[0], q = surface.degree[1];
  u = std::clamp(u, surface.umin(), surface.umax());
  v = std::clamp(v, surface.vmin(), surface.vmax());
  const int su = find_span(surface.count_u, p, u, surface.knots_u);
  const int sv = find_span(surface.count_v, q, v, surface.knots_v);
  const int du = std::min(2, p), dv = std::min(2, q);
  double Nu[3 * kTable], Nv[3 * kTable];
  basis_derivatives(su, u, p, du, surface.knots_u, Nu);
  basis_derivatives(sv, v, q, dv, surface.knots_v, Nv);
  // A3.6: A_kl = Σ_r N^(l)_{sv-q+r} Σ_s N^(k)_{su-p+s} P^w_{su-p+s, sv-q+r}, k + l <= 2
  Homogeneous A[3][3] = {};
  for (int k = 0; k <= du; ++k) {
    Homogeneous temp[kTable];
    for (int r = 0; r <= q; ++r) {
      temp[r] = {};
      for (int s = 0; s <= p; ++s)
        add_to(temp[r],
               scaled(surface.weighted[static_cast<std::size_t>((su - p + s) * surface.count_v + sv - q + r)],
                      Nu[k * (p + 1) + s]));
    }
    for (int l = 0; l <= std::min(2 - k, dv); ++l)
      for (int r = 0; r <= q; ++r) add_to(A[k][l], scaled(temp[r], Nv[l * (q + 1) + r]));
  }
  // A4.4 (Leibniz's rule, k + l <= 2)
  auto w = [&](int k, int l) { return A[k][l][3]; };
  Vec3 S[3][3];
  const double w00 = w(0, 0);
  S[0][0] = xyz(A[0][0]) / w00;
  S[1][0] = (xyz(A[1][0]) - w(1, 0) * S[0][0]) / w00;
  S[0][1] = (xyz(A[0][1]) - w(0, 1) * S[0][0]) / w00;
  S[2][0] = (xyz(A[2][0]) - 2.0 * w(1, 0) * S[1][0] - w(2, 0) * S[0][0]) / w00;
  S[0][2] = (xyz(A[0][2]) - 2.0 * w(0, 1) * S[0][1] - w(0, 2) * S[0][0]) / w00;
  S[1][1] = (xyz(A[1][1]) - w(0, 1) * S[1][0] - w(1, 0) * S[0][1] - w(1, 1) * S[0][0]) / w00;
  return {S[0][0], S[1][0], S[0][1], S[2][0], S[1][1], S[0][2]};
}

}  // namespace footpoint::nurbs
