#include "parametric/geometry/distance_bound.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "formula/ball.hpp"
#include "parametric/geometry/box_quadratic.hpp"

namespace footpoint {

namespace {

using formula::ball::kU;  // the unit roundoff
constexpr double kInf = std::numeric_limits<double>::infinity();

// Σ_k (s_k - p_k) ∂²_ij s_k over the box as centre ± radius.
template <int N>
void curvature_term(const BoxEnclosure<N>& box, int pair, const Vec3& p, double* centre, double* radius) {
  double c = 0.0, r = 0.0, magnitude = 0.0;
  for (int k = 0; k < 3; ++k) {
    const double m = box.s_mid[k] - p[k];
    const double mr = box.s_rad[k] + kU * std::abs(m);  // and the rounding of m itself
    const double M = box.d2_mid[pair][k], R = box.d2_rad[pair][k];
    c += m * M;
    magnitude += std::abs(m * M);
    r += std::abs(m) * R + mr * std::abs(M) + mr * R;
  }
  *centre = c;
  *radius = (r + kBoundRounding * magnitude) * (1.0 + kBoundRounding);
}

}  // namespace

double box_distance2_lower(const Vec3& s_mid, const Vec3& s_rad, const Vec3& p) {
  double d2 = 0.0;
  for (int k = 0; k < 3; ++k) {
    const double gap = std::abs(p[k] - s_mid[k]) * (1.0 - 4.0 * kU) - s_rad[k] * (1.0 + 4.0 * kU);
    if (gap > 0.0) d2 += gap * gap;
  }
  if (std::isnan(d2)) return 0.0;
  return d2 * (1.0 - 16.0 * kU);
}

template <int N>
double HessianBounds<N>::smallest_eigenvalue() const {
  if (!valid) return -kInf;
  if constexpr (N == 1) {
    return diagonal_lo[0];
  } else {
    const double a = diagonal_lo[0], c = diagonal_lo[1], b = std::max(std::abs(off_lo), std::abs(off_hi));
    const double lambda = 0.5 * (a + c) - std::sqrt(0.25 * (a - c) * (a - c) + b * b);
    return lambda - kBoundRounding * (std::abs(a) + std::abs(c) + b);
  }
}

template <int N>
HessianBounds<N> hessian_bounds(const BoxEnclosure<N>& box, const Vec3& p) {
  HessianBounds<N> h;
  if (!box.smooth) return h;
  for (int i = 0; i < N; ++i) {
    const int ii = BoxEnclosure<N>::pair(i, i);
    double c, r;
    curvature_term(box, ii, p, &c, &r);
    const double a = box.metric_lo[ii] + c - r;
    h.diagonal_lo[i] = a - kBoundRounding * (std::abs(box.metric_lo[ii]) + std::abs(c) + r);
  }
  if constexpr (N == 2) {
    const int ij = BoxEnclosure<N>::pair(0, 1);
    double c, r;
    curvature_term(box, ij, p, &c, &r);
    const double slack =
        kBoundRounding * (std::abs(box.metric_lo[ij]) + std::abs(box.metric_hi[ij]) + std::abs(c) + r);
    h.off_lo = box.metric_lo[ij] + c - r - slack;
    h.off_hi = box.metric_hi[ij] + c + r + slack;
  }
  h.valid = true;
  for (double d : h.diagonal_lo) h.valid = h.valid && !std::isnan(d);
  h.valid = h.valid && !std::isnan(h.off_lo) && !std::isnan(h.off_hi);
  return h;
}

template <int N>
GradientEnclosure<N> enclose_gradient(const PointEnclosure<N>& q, const Vec3& p) {
  GradientEnclosure<N> e;
  double r[3], rho[3], f = 0.0, f_error = 0.0;
  for (int k = 0; k < 3; ++k) {
    r[k] = q.s[k] - p[k];
    rho[k] = q.s_rad[k] + kU * std::abs(r[k]);
    f += 0.5 * r[k] * r[k];
    f_error += std::abs(r[k]) * rho[k];
  }
  e.f_lo = f - (f_error * (1.0 + kBoundRounding) + kBoundRounding * f);
  for (int i = 0; i < N; ++i) {
    double g = 0.0, magnitude = 0.0, error = 0.0;
    for (int k = 0; k < 3; ++k) {
      const double a = q.ds[i][k], ar = q.ds_rad[i][k];
      g += a * r[k];
      magnitude += std::abs(a * r[k]);
      error += std::abs(a) * rho[k] + ar * std::abs(r[k]) + ar * rho[k];
    }
    e.g[i] = g;
    e.g_rad[i] = (error + kBoundRounding * magnitude) * (1.0 + kBoundRounding);
  }
  return e;
}

double quadratic_lower_bound_1d(double g, double h, double lo, double hi) {
  if (h > 0.0) {  // convex: the tangent at the clamped vertex lies below
    const double x = std::clamp(-g / h, lo, hi);
    const double slope = g + h * x;
    return g * x + 0.5 * h * x * x + std::min(slope * (lo - x), slope * (hi - x));
  }
  return std::min(g * lo + 0.5 * h * lo * lo, g * hi + 0.5 * h * hi * hi);  // concave: an end
}

double quadratic_lower_bound(const std::array<double, 2>& g, const std::array<std::array<double, 2>, 2>& H,
                             const Params<2>& lo, const Params<2>& hi) {
  const double a = H[0][0], b = H[0][1], c = H[1][1];
  if (a >= 0.0 && c >= 0.0 && a * c - b * b >= 0.0) {  // convex
    BoxQuadratic q;
    q.g = g;
    q.H = H;
    const Params<2> d = minimize_on_box(q, lo, hi).delta;
    if (std::isfinite(d[0]) && std::isfinite(d[1])) {
      const double s0 = g[0] + a * d[0] + b * d[1], s1 = g[1] + b * d[0] + c * d[1];
      return q.value(d[0], d[1]) + std::min(s0 * (lo[0] - d[0]), s0 * (hi[0] - d[0])) +
             std::min(s1 * (lo[1] - d[1]), s1 * (hi[1] - d[1]));
    }
  }
  // not convex (or no usable minimiser): the least of the four edges
  double best = kInf;
  for (double d0 : {lo[0], hi[0]})
    best = std::min(best,
                    g[0] * d0 + 0.5 * a * d0 * d0 + quadratic_lower_bound_1d(g[1] + b * d0, c, lo[1], hi[1]));
  for (double d1 : {lo[1], hi[1]})
    best = std::min(best,
                    g[1] * d1 + 0.5 * c * d1 * d1 + quadratic_lower_bound_1d(g[0] + b * d1, a, lo[0], hi[0]));
  return best;
}

template <int N>
double second_order_lower_bound(const GradientEnclosure<N>& at_q, const Params<N>& q, const Params<N>& lo,
                                const Params<N>& hi, const HessianBounds<N>& hessian, double enough) {
  if (!hessian.valid || std::isnan(at_q.f_lo)) return -kInf;
  // δ over [lo - q, hi - q], rounded outwards; each side of q separately
  std::array<double, N> below{}, above{};
  double magnitude = std::abs(at_q.f_lo);
  for (int i = 0; i < N; ++i) {
    below[i] = std::min(lo[i] - q[i], 0.0) * (1.0 + 4.0 * kU);
    above[i] = std::max(hi[i] - q[i], 0.0) * (1.0 + 4.0 * kU);
    const double w = std::max(-below[i], above[i]);
    magnitude += (std::abs(at_q.g[i]) + at_q.g_rad[i]) * w + 0.5 * std::abs(hessian.diagonal_lo[i]) * w * w;
  }
  double least;
  if constexpr (N == 1) {
    const double h = hessian.diagonal_lo[0];
    least = std::min(quadratic_lower_bound_1d(at_q.g[0] - at_q.g_rad[0], h, 0.0, above[0]),
                     quadratic_lower_bound_1d(at_q.g[0] + at_q.g_rad[0], h, below[0], 0.0));
  } else {
    magnitude += std::max(std::abs(hessian.off_lo), std::abs(hessian.off_hi)) *
                 std::max(-below[0], above[0]) * std::max(-below[1], above[1]);
    // first the separable bound with the smallest eigenvalue (δᵀHδ >= λ|δ|^2): cheaper, weaker
    const double lambda = hessian.smallest_eigenvalue();
    least = 0.0;
    for (int i = 0; i < 2; ++i)
      least += std::min(quadratic_lower_bound_1d(at_q.g[i] - at_q.g_rad[i], lambda, 0.0, above[i]),
                        quadratic_lower_bound_1d(at_q.g[i] + at_q.g_rad[i], lambda, below[i], 0.0));
    const double separable = at_q.f_lo + least -
                             kBoundRounding * (magnitude + std::abs(lambda) * 4.0 *
                                                               (above[0] * above[0] + below[0] * below[0] +
                                                                above[1] * above[1] + below[1] * below[1]));
    if (separable >= enough) return separable;
    least = kInf;
    for (int s0 = -1; s0 <= 1; s0 += 2)
      for (int s1 = -1; s1 <= 1; s1 += 2) {
        // the gradient's worst value on this side of q, the cross term's worst coefficient
        const std::array<double, 2> g{s0 > 0 ? at_q.g[0] - at_q.g_rad[0] : at_q.g[0] + at_q.g_rad[0],
                                      s1 > 0 ? at_q.g[1] - at_q.g_rad[1] : at_q.g[1] + at_q.g_rad[1]};
        const double off = s0 * s1 > 0 ? hessian.off_lo : hessian.off_hi;
        const std::array<std::array<double, 2>, 2> H{
            {{hessian.diagonal_lo[0], off}, {off, hessian.diagonal_lo[1]}}};
        least =
            std::min(least, quadratic_lower_bound(g, H, {s0 > 0 ? 0.0 : below[0], s1 > 0 ? 0.0 : below[1]},
                                                  {s0 > 0 ? above[0] : 0.0, s1 > 0 ? above[1] : 0.0}));
      }
  }
  const double result = at_q.f_lo + least - kBoundRounding * magnitude;
  return std::isnan(result) ? -kInf : result;
}

template <int N>
std::array<int, N> gradient_signs(const BoxEnclosure<N>& box, const PointEnclosure<N>& centre,
                                  const Vec3& p) {
  std::array<int, N> signs{};
  if (!box.bounded || !box.smooth || !centre.valid) return signs;
  const auto pair = [](int i, int j) { return N == 1 ? 0 : (i == j ? (i == 0 ? 0 : 2) : 1); };
  for (int i = 0; i < N; ++i) {
    double g = 0.0, g_rad = 0.0, magnitude = 0.0;
    for (int k = 0; k < 3; ++k) {
      // ∂_i s_k over the box: centre value ± its radius and the second partials' reach
      double d_rad = centre.ds_rad[i][k];
      for (int j = 0; j < N; ++j) {
        const std::size_t q = static_cast<std::size_t>(pair(i, j));
        d_rad += (std::abs(box.d2_mid[q][k]) + box.d2_rad[q][k]) * 0.5 * (box.hi[j] - box.lo[j]);
      }
      const double d = centre.ds[i][k], r = box.s_mid[k] - p[k], r_rad = box.s_rad[k];
      g += d * r;
      magnitude += std::abs(d * r);
      g_rad += std::abs(d) * r_rad + d_rad * (std::abs(r) + r_rad);
    }
    g_rad = (g_rad + kBoundRounding * magnitude) * (1.0 + kBoundRounding);
    signs[static_cast<std::size_t>(i)] = g - g_rad > 0.0 ? 1 : (g + g_rad < 0.0 ? -1 : 0);
  }
  return signs;
}

double distance_from_f_lower(double f_lower) {
  if (!(f_lower > 0.0)) return 0.0;
  return std::sqrt(2.0 * f_lower) * (1.0 - 4.0 * kU);
}

template <int N>
double branch_lower_bound(const formula::Program& program, const Vec3& p, const Params<N>& lo,
                          const Params<N>& hi, const std::vector<Params<N>>& near, double enough) {
  formula::Interval x[N];
  for (int i = 0; i < N; ++i) x[i] = {lo[i], hi[i]};
  formula::BranchChoice choice;
  choice.nodes = program.undecided_conditions(x);
  if (choice.nodes.empty() || choice.nodes.size() > kMaxBranchConditions) return 0.0;
  const double enough_f = enough > 0.0 ? 0.5 * enough * enough * (1.0 + 16.0 * kU) : 0.0;
  Params<N> centre;
  for (int i = 0; i < N; ++i) centre[i] = 0.5 * (lo[i] + hi[i]);
  double least = kInf;
  for (std::uint32_t m = 0; m < (1u << choice.nodes.size()); ++m) {
    choice.take_b = m;
    const BoxEnclosure<N> e = enclose_box<N>(program, lo, hi, &choice);
    if (!e.bounded) return 0.0;
    double lb = std::sqrt(box_distance2_lower(e.s_mid, e.s_rad, p));
    const HessianBounds<N> hessian = e.smooth ? hessian_bounds(e, p) : HessianBounds<N>{};
    auto from = [&](const Params<N>& q) {
      if (lb >= enough || !hessian.valid) return;
      const PointEnclosure<N> at = enclose_point<N>(program, q, &choice);
      if (!at.valid) return;
      lb = std::max(lb, distance_from_f_lower(
                            second_order_lower_bound(enclose_gradient(at, p), q, lo, hi, hessian, enough_f)));
    };
    from(centre);
    for (const Params<N>& k : near) {
      Params<N> q;
      for (int i = 0; i < N; ++i) q[i] = std::clamp(k[i], lo[i], hi[i]);
      from(q);
    }
    // a choice short of `enough` leaves the box open: the zero-order bound of all of it is the caller's
    if (!(lb >= enough)) return 0.0;
    least = std::min(least, lb);
  }
  return least;
}

template double branch_lower_bound<1>(const formula::Program&, const Vec3&, const Params<1>&,
                                      const Params<1>&, const std::vector<Params<1>>&, double);
template double branch_lower_bound<2>(const formula::Program&, const Vec3&, const Params<2>&,
                                      const Params<2>&, const std::vector<Params<2>>&, double);
template std::array<int, 1> gradient_signs<1>(const BoxEnclosure<1>&, const PointEnclosure<1>&, const Vec3&);
template std::array<int, 2> gradient_signs<2>(const BoxEnclosure<2>&, const PointEnclosure<2>&, const Vec3&);
template struct HessianBounds<1>;
template struct HessianBounds<2>;
template HessianBounds<1> hessian_bounds<1>(const BoxEnclosure<1>&, const Vec3&);
template HessianBounds<2> hessian_bounds<2>(const BoxEnclosure<2>&, const Vec3&);
template GradientEnclosure<1> enclose_gradient<1>(const PointEnclosure<1>&, const Vec3&);
template GradientEnclosure<2> enclose_gradient<2>(const PointEnclosure<2>&, const Vec3&);
template double second_order_lower_bound<1>(const GradientEnclosure<1>&, const Params<1>&, const Params<1>&,
                                            const Params<1>&, const HessianBounds<1>&, double);
template double second_order_lower_bound<2>(const GradientEnclosure<2>&, const Params<2>&, const Params<2>&,
                                            const Params<2>&, const HessianBounds<2>&, double);

}  // namespace footpoint
