#include "parametric/solvers/bezier_patch_nearest.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "geometry/box3.hpp"
#include "projection/certificate.hpp"
#include "solvers/piecewise_nearest.hpp"

namespace footpoint {

namespace {

// A result of one operation rounded to nearest moved outwards: the exact value is within 2^-53 |x|
// of x, and the absolute term covers underflow.
double bz_down(double x) { return x - (std::fabs(x) * 0x1p-50 + 0x1p-1000); }
double bz_up(double x) { return x + (std::fabs(x) * 0x1p-50 + 0x1p-1000); }

using BzInterval = bezier_detail::Interval;
using BzVec = bezier_detail::IntervalVec;
using BzCell = bezier_detail::Cell;

// Interval sums, products and squares, rounded outwards (formula/interval.hpp).
using formula::interval::add;
using formula::interval::mul;
using formula::interval::sqr;

// The sum of three intervals' bounds computed in floating point (lo, hi, each term rounded once
// from its exact value), moved outwards by their rounding: the three terms' and the two sums'
// are each at most 2^-53 of the terms' magnitudes' sum m (m rounded too: 2^-50 m covers all of
// them), and bz_down / bz_up cover the last subtraction's. A NaN (0 x inf) gives the whole line.
BzInterval bz_sum_widened(double lo, double hi, double m) {
  if (std::isnan(lo) || std::isnan(hi)) return formula::interval::entire();
  const double e = m * 0x1p-50 + 0x1p-1000;
  return {bz_down(lo - e), bz_up(hi + e)};
}
// a·b: each product's bounds are the least and greatest of its four corner products.
BzInterval bz_dot(const BzVec& a, const BzVec& b) {
  double lo = 0.0, hi = 0.0, m = 0.0;
  for (std::size_t c = 0; c < 3; ++c) {
    const double p0 = a[c].lo * b[c].lo, p1 = a[c].lo * b[c].hi, p2 = a[c].hi * b[c].lo,
                 p3 = a[c].hi * b[c].hi;
    const double l = std::min(std::min(p0, p1), std::min(p2, p3)),
                 h = std::max(std::max(p0, p1), std::max(p2, p3));
    lo += l;
    hi += h;
    m += std::max(std::fabs(l), std::fabs(h));
  }
  return bz_sum_widened(lo, hi, m);
}
// |a|²: each square's least value is 0 where the interval holds 0.
BzInterval bz_norm2(const BzVec& a) {
  double lo = 0.0, hi = 0.0;
  for (std::size_t c = 0; c < 3; ++c) {
    const double l = std::fabs(a[c].lo), h = std::fabs(a[c].hi), big = std::max(l, h);
    lo += a[c].lo <= 0.0 && a[c].hi >= 0.0 ? 0.0 : std::min(l, h) * std::min(l, h);
    hi += big * big;
  }
  const BzInterval sum = bz_sum_widened(lo, hi, hi);
  return {std::max(sum.lo, 0.0), sum.hi};
}

// The box of computed values v (each within w of its exact value, plus its own rounding) less
// `origin`, as intervals.
struct BzHull {
  Vec3 lo{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
          std::numeric_limits<double>::infinity()};
  Vec3 hi{-std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
          -std::numeric_limits<double>::infinity()};
  void add(const Vec3& v) {
    lo = min(lo, v);
    hi = max(hi, v);
  }
  BzVec minus(const Vec3& origin, double w) const {
    BzVec out;
    for (int c = 0; c < 3; ++c)
      out[c] = {bz_down(bz_down(lo[c] - origin[c]) - w), bz_up(bz_up(hi[c] - origin[c]) + w)};
    return out;
  }
};

// The Bernstein basis of degree n at x and its first two derivatives (zero below degree 1, 2).
// The triangle of the bases of degree 0 to n, B_k^m = (1 - x) B_k^(m-1) + x B_(k-1)^(m-1), is built in
// place (k descending), keeping the levels n - 2 and n - 1 that the derivatives take.
void bz_basis(int n, double x, double* b0, double* b1, double* b2) {
  constexpr int kSize = BezierPatch::kMaxDegree + 3;
  double b[kSize] = {1.0}, below1[kSize] = {}, below2[kSize] = {};  // levels n - 1, n - 2 (shifted by 2)
  for (int m = 1; m <= n; ++m) {
    if (m == n - 1) std::copy(b, b + m, below2 + 2);
    if (m == n) std::copy(b, b + m, below1 + 2);
    b[m] = x * b[m - 1];
    for (int k = m - 1; k >= 1; --k) b[k] = (1.0 - x) * b[k] + x * b[k - 1];
    b[0] = (1.0 - x) * b[0];
  }
  // below1[k + 2] = B_k^(n-1) (0 outside 0..n-1), below2[k + 2] = B_k^(n-2) (0 outside 0..n-2).
  for (int k = 0; k <= n; ++k) {
    b0[k] = b[k];
    b1[k] = n * (below1[k + 1] - below1[k + 2]);
    b2[k] = n * (n - 1) * (below2[k] - 2.0 * below2[k + 1] + below2[k + 2]);
  }
}

// de Casteljau at a along s (dir 0; T a point or a weight: the index k of b_kl) or t (dir 1), net of (p + 1)
// x (q + 1).
template <class T>
void bz_split(const T* in, int p, int q, int dir, double a, T* left, T* right) {
  const int n = dir == 0 ? p : q, lines = dir == 0 ? q + 1 : p + 1;
  auto index = [&](int along, int line) {
    return dir == 0 ? along * (q + 1) + line : line * (q + 1) + along;
  };
  T tmp[BezierPatch::kMaxDegree + 1];
  for (int line = 0; line < lines; ++line) {
    for (int k = 0; k <= n; ++k) tmp[k] = in[index(k, line)];
    left[index(0, line)] = tmp[0];
    right[index(n, line)] = tmp[n];
    for (int r = 1; r <= n; ++r) {
      for (int k = 0; k <= n - r; ++k) tmp[k] = (1.0 - a) * tmp[k] + a * tmp[k + 1];
      left[index(r, line)] = tmp[0];
      right[index(n - r, line)] = tmp[n - r];
    }
  }
}

// A cell over [s0, s1] x [t0, t1] whose net is within err of the exact sub-patch's.
BzCell bz_cell(double s0, double s1, double t0, double t1, double err) {
  BzCell c;
  c.s0 = s0;
  c.s1 = s1;
  c.t0 = t0;
  c.t1 = t1;
  c.err = err;
  return c;
}

// The enclosures of a sub-patch that do not depend on the point (bezier_detail::Cell), from its
// net n, within err of the exact sub-patch's. Each computed difference is within its inputs'
// errors plus a rounding of the net's magnitude m.
BzCell bz_make_cell(const Vec3* n, int p, int q, double err, double m, double s0, double s1, double t0,
                    double t1) {
  BzCell c = bz_cell(s0, s1, t0, t1, err);
  auto at = [&](int k, int l) -> const Vec3& { return n[k * (q + 1) + l]; };
  const Vec3 zero{0.0, 0.0, 0.0};
  const double w1s = p * (2.0 * err + 0x1p-50 * m), w1t = q * (2.0 * err + 0x1p-50 * m);
  const double w2s = p * (p - 1) * (4.0 * err + 0x1p-49 * m), w2t = q * (q - 1) * (4.0 * err + 0x1p-49 * m);
  const double wst = p * q * (4.0 * err + 0x1p-49 * m);
  BzHull hs, hu, hv, huu, huv, hvv;
  for (int k = 0; k <= p; ++k)
    for (int l = 0; l <= q; ++l) {
      hs.add(at(k, l));
      if (k < p) hu.add(p * (at(k + 1, l) - at(k, l)));
      if (l < q) hv.add(q * (at(k, l + 1) - at(k, l)));
      if (k + 1 < p) huu.add(p * (p - 1) * (at(k + 2, l) - 2.0 * at(k + 1, l) + at(k, l)));
      if (l + 1 < q) hvv.add(q * (q - 1) * (at(k, l + 2) - 2.0 * at(k, l + 1) + at(k, l)));
      if (k < p && l < q) huv.add(p * q * ((at(k + 1, l + 1) - at(k + 1, l)) - (at(k, l + 1) - at(k, l))));
    }
  if (p < 2) huu.add(zero);
  if (q < 2) hvv.add(zero);
  const BzVec box = hs.minus(zero, err);
  for (int d = 0; d < 3; ++d) {
    c.lo[d] = box[static_cast<std::size_t>(d)].lo;
    c.hi[d] = box[static_cast<std::size_t>(d)].hi;
  }
  c.su = hu.minus(zero, w1s);
  c.sv = hv.minus(zero, w1t);
  c.suu = huu.minus(zero, w2s);
  c.svv = hvv.minus(zero, w2t);
  c.suv = huv.minus(zero, wst);
  c.su2 = bz_norm2(c.su);
  c.sv2 = bz_norm2(c.sv);
  c.susv = bz_dot(c.su, c.sv);
  c.size_s = c.size_t = 0.0;
  for (int d = 0; d < 3; ++d) {
    c.size_s = std::max({c.size_s, std::fabs(c.su[d].lo), std::fabs(c.su[d].hi)});
    c.size_t = std::max({c.size_t, std::fabs(c.sv[d].lo), std::fabs(c.sv[d].hi)});
  }
  for (int cs = 0; cs < 2; ++cs)
    for (int ct = 0; ct < 2; ++ct) {
      const int K = cs ? p : 0, L = ct ? q : 0, Ki = cs ? p - 1 : 1, Li = ct ? q - 1 : 1;
      BzHull point, es, et;
      point.add(at(K, L));
      es.add(p * (at(Ki, L) - at(K, L)));
      et.add(q * (at(K, Li) - at(K, L)));
      BzCell::Corner& corner = c.corners[static_cast<std::size_t>(cs * 2 + ct)];
      corner.point = point.minus(zero, err);
      corner.es = es.minus(zero, w1s);
      corner.et = et.minus(zero, w1t);
    }
  return c;
}

// A rational sub-patch's cell: its nets of homogeneous points a (within err) and weights w (within
// err_w), and the box of its Euclidean points a / w, which holds it (with positive weights a
// rational Bézier patch lies in the convex hull of its control points, [PieglTiller] property
// P4.9), widened by the quotients' error (|a/w - a'/w'| <= (err + |a/w| err_w) / (w - err_w)).
BzCell bz_make_rational_cell(const Vec3* a, const double* w, int p, int q, double err, double err_w,
                             double s0, double s1, double t0, double t1) {
  BzCell c = bz_cell(s0, s1, t0, t1, err);
  c.err_w = err_w;
  BzHull h;
  double widen = 0.0;
  for (int k = 0; k < (p + 1) * (q + 1); ++k) {
    const Vec3 x = (1.0 / w[k]) * a[k];
    h.add(x);
    const double size = std::max({std::fabs(x.x), std::fabs(x.y), std::fabs(x.z)});
    widen = std::max(widen, (err + size * err_w) / (w[k] - err_w) + 0x1p-51 * size);
  }
  if (!std::isfinite(widen) || !(widen >= 0.0)) widen = std::numeric_limits<double>::infinity();
  const BzVec box = h.minus(Vec3{0.0, 0.0, 0.0}, widen);
  for (int d = 0; d < 3; ++d) {
    c.lo[d] = box[static_cast<std::size_t>(d)].lo;
    c.hi[d] = box[static_cast<std::size_t>(d)].hi;
  }
  return c;
}

// The binomial coefficients C(n, k), n <= 2 kMaxDegree (exact in doubles).
constexpr int kMaxProduct = 2 * BezierPatch::kMaxDegree;
struct BzBinomials {
  double c[kMaxProduct + 1][kMaxProduct + 1] = {};
  constexpr BzBinomials() {
    for (int n = 0; n <= kMaxProduct; ++n) {
      c[n][0] = c[n][n] = 1.0;
      for (int k = 1; k < n; ++k) c[n][k] = c[n - 1][k - 1] + c[n - 1][k];
    }
  }
};
constexpr BzBinomials kBinomials;

// The product of two Bernstein forms of degree p x q (nets a, b; `times` multiplies two entries to a
// double) as a Bernstein form of degree 2p x 2q into out, at k * (2q + 1) + l ([FaroukiRajan]
// R. T. Farouki, V. T. Rajan, Algorithms for polynomials in Bernstein form, CAGD 5 (1988) 1-26,
// the product: (a b)_kl = Σ_{i+i'=k, j+j'=l} C(p,i) C(p,i') C(q,j) C(q,j') / (C(2p,k) C(2q,l))
// a_ij b_i'j'). The weights of each out_kl are nonnegative and sum to 1 (Vandermonde), so out_kl
// is within (p + 1)(q + 1) + 8 roundings of max |a_ij b_i'j'| of the exact value.
template <class T, class Times>
void bz_product(const T* a, const T* b, int p, int q, double* out, Times times) {
  const int Q = 2 * q;
  std::fill(out, out + (2 * p + 1) * (Q + 1), 0.0);
  for (int i = 0; i <= p; ++i)
    for (int j = 0; j <= q; ++j)
      for (int i2 = 0; i2 <= p; ++i2)
        for (int j2 = 0; j2 <= q; ++j2)
          out[(i + i2) * (Q + 1) + j + j2] += (kBinomials.c[p][i] * kBinomials.c[p][i2]) *
                                              (kBinomials.c[q][j] * kBinomials.c[q][j2]) *
                                              times(a[i * (q + 1) + j], b[i2 * (q + 1) + j2]);
  for (int k = 0; k <= 2 * p; ++k)
    for (int l = 0; l <= Q; ++l) out[k * (Q + 1) + l] /= kBinomials.c[2 * p][k] * kBinomials.c[Q][l];
}

// A rational cell's scalar nets for the point p (degree 2p x 2q): N = |A - p W|² and M = W², each
// within its error bound of the exact sub-patch's, and M's range.
struct BzLevelNets {
  static constexpr int kSize = (kMaxProduct + 1) * (kMaxProduct + 1);
  double n[kSize], m[kSize];
  double err_n = 0.0, err_m = 0.0, m_lo = 0.0, m_hi = 0.0, n_max = 0.0;
};

// D = A - p W per point: within err + |p| err_w of the exact, plus two roundings of |A| + |p| W.
// N's error: |D_i·D_j - D'_i·D'_j| <= 3 (|D| + |D'|) e <= 6 (m_D + e) e, then the product's
// roundings of at most 3 m_D² (taken twice over); M's alike.
void bz_level_nets(const Vec3* a, const double* w, int p, int q, double err, double err_w, const Vec3& point,
                   BzLevelNets& out) {
  const int count = (p + 1) * (q + 1);
  Vec3 d[(BezierPatch::kMaxDegree + 1) * (BezierPatch::kMaxDegree + 1)];
  const double pm = std::max({std::fabs(point.x), std::fabs(point.y), std::fabs(point.z)});
  double ma = 0.0, mw = 0.0, md = 0.0;
  for (int k = 0; k < count; ++k) {
    d[k] = a[k] - w[k] * point;
    ma = std::max({ma, std::fabs(a[k].x), std::fabs(a[k].y), std::fabs(a[k].z)});
    mw = std::max(mw, std::fabs(w[k]));
    md = std::max({md, std::fabs(d[k].x), std::fabs(d[k].y), std::fabs(d[k].z)});
  }
  const double e = err + pm * err_w + 0x1p-51 * (ma + pm * mw);
  const double rounding = (count + 8) * 0x1p-51;
  bz_product(d, d, p, q, out.n, [](const Vec3& x, const Vec3& y) { return dot(x, y); });
  bz_product(w, w, p, q, out.m, [](double x, double y) { return x * y; });
  out.err_n = bz_up(6.0 * (md + e) * e + rounding * 3.0 * md * md);
  out.err_m = bz_up(2.0 * (mw + err_w) * err_w + rounding * mw * mw);
  out.m_lo = std::numeric_limits<double>::infinity();
  out.m_hi = out.n_max = 0.0;
  for (int k = 0; k < (2 * p + 1) * (2 * q + 1); ++k) {
    out.m_lo = std::min(out.m_lo, bz_down(out.m[k] - out.err_m));
    out.m_hi = std::max(out.m_hi, bz_up(out.m[k] + out.err_m));
    out.n_max = std::max(out.n_max, std::fabs(out.n[k]));
  }
}

// The enclosures over a cell of the second derivatives (its local parameters) of the polynomial of
// the scalar net g of degree P x Q (each entry within e), from the nets of its second differences.
void bz_hessian_hull(const double* g, int P, int Q, double e, BzInterval& ss, BzInterval& st,
                     BzInterval& tt) {
  double m = 0.0;
  for (int k = 0; k < (P + 1) * (Q + 1); ++k) m = std::max(m, std::fabs(g[k]));
  const double inf = std::numeric_limits<double>::infinity();
  ss = st = tt = {inf, -inf};
  auto at = [&](int k, int l) { return g[k * (Q + 1) + l]; };
  for (int k = 0; k <= P; ++k)
    for (int l = 0; l <= Q; ++l) {
      if (k + 2 <= P) {
        const double x = (at(k + 2, l) - 2.0 * at(k + 1, l)) + at(k, l);
        ss = {std::min(ss.lo, x), std::max(ss.hi, x)};
      }
      if (l + 2 <= Q) {
        const double x = (at(k, l + 2) - 2.0 * at(k, l + 1)) + at(k, l);
        tt = {std::min(tt.lo, x), std::max(tt.hi, x)};
      }
      if (k + 1 <= P && l + 1 <= Q) {
        const double x = (at(k + 1, l + 1) - at(k + 1, l)) - (at(k, l + 1) - at(k, l));
        st = {std::min(st.lo, x), std::max(st.hi, x)};
      }
    }
  // Each difference: four entries' errors and three roundings of at most 4 m; then the factor.
  const double w = 4.0 * e + 0x1p-49 * m;
  const auto scaled = [&](BzInterval x, double f) {
    return BzInterval{bz_down(f * (x.lo - w)), bz_up(f * (x.hi + w))};
  };
  ss = scaled(ss, P * (P - 1.0));
  tt = scaled(tt, Q * (Q - 1.0));
  st = scaled(st, static_cast<double>(P) * Q);
}

// The four halves-by-halves of net n (s, then t, at ½: exact halvings of sums) into out[0..3]
// (s low t low, s low t high, s high t low, s high t high), each of `stride` points.
template <class T>
void bz_quarters(const T* n, int p, int q, T* out) {
  const int stride = (p + 1) * (q + 1);
  T left[(BezierPatch::kMaxDegree + 1) * (BezierPatch::kMaxDegree + 1)];
  T right[(BezierPatch::kMaxDegree + 1) * (BezierPatch::kMaxDegree + 1)];
  bz_split(n, p, q, 0, 0.5, left, right);
  bz_split(left, p, q, 1, 0.5, out, out + stride);
  bz_split(right, p, q, 1, 0.5, out + 2 * stride, out + 3 * stride);
}

// The error a quartering adds to the nets' points: p + q levels of averaging, each one rounding
// of the magnitude m.
double bz_quarter_error(int p, int q, double m) { return (p + q) * 0x1p-49 * m; }

// min over x in [0, X], y in [0, Y] of gx x + gy y + ½ (A x² + C y² + 2 E x y), rounded down: at
// a corner, at an edge's one-dimensional minimum, or at the interior stationary point where the
// form is positive definite (else no interior point is below the boundary's minimum).
double bz_min_form(double gx, double gy, double A, double C, double E, double X, double Y) {
  const auto q = [&](double x, double y) {
    return gx * x + gy * y + 0.5 * (A * x * x + C * y * y + 2.0 * E * x * y);
  };
  double m = std::min({0.0, q(X, 0.0), q(0.0, Y), q(X, Y)});
  if (C > 0.0) {
    m = std::min(m, q(0.0, std::clamp(-gy / C, 0.0, Y)));
    m = std::min(m, q(X, std::clamp(-(gy + E * X) / C, 0.0, Y)));
  }
  if (A > 0.0) {
    m = std::min(m, q(std::clamp(-gx / A, 0.0, X), 0.0));
    m = std::min(m, q(std::clamp(-(gx + E * Y) / A, 0.0, X), Y));
  }
  const double det = A * C - E * E;
  if (A > 0.0 && C > 0.0 && det > 0.0) {
    const double x = (-gx * C + gy * E) / det, y = (-gy * A + gx * E) / det;
    if (x > 0.0 && x < X && y > 0.0 && y < Y) m = std::min(m, q(x, y));
  }
  const double scale = std::fabs(gx) * X + std::fabs(gy) * Y +
                       0.5 * (std::fabs(A) * X * X + std::fabs(C) * Y * Y + 2.0 * std::fabs(E) * X * Y);
  return std::isfinite(m) ? m - scale * 0x1p-48 : -std::numeric_limits<double>::infinity();
}

// The second-order lower bound of f - f(c) over the part of a box on one side of c along each
// parameter: δs = sign_s x, δt = sign_t y (sign = ±1) with x in [0, X], y in [0, Y]; g the gradient at c and
// fss, fst, ftt the Hessian's enclosures over the box, all in the box's local parameters.
double bz_quadrant(BzInterval gs, BzInterval gt, BzInterval fss, BzInterval fst, BzInterval ftt, int sign_s,
                   int sign_t, double X, double Y) {
  if (!(X > 0.0) && !(Y > 0.0)) return 0.0;
  const double gx = sign_s > 0 ? gs.lo : -gs.hi, gy = sign_t > 0 ? gt.lo : -gt.hi;
  const double E = sign_s * sign_t > 0 ? fst.lo : -fst.hi;
  return bz_min_form(gx, gy, fss.lo, ftt.lo, E, X, Y);
}

BzInterval bz_scaled(BzInterval a, double w) { return {bz_down(a.lo * w), bz_up(a.hi * w)}; }
// A box of the search: a cell, and what is known of f over it for this point.
struct BzBox {
  int cell;  // >= 0: the patch's cell; < 0: the search's cell -1 - cell
  double s0, s1, t0, t1;
  double lower = 0.0;
  double lambda = 0.0;
  BzInterval fs{0.0, 0.0}, ft{0.0, 0.0};  // f's gradient over it
  double fss = 0.0, ftt = 0.0;            // lower bounds of f_ss, f_tt over it
  bool contains(double s, double t) const { return s >= s0 && s <= s1 && t >= t0 && t <= t1; }
};

// The search's storage, kept by each thread from one point to the next.
struct BzScratch {
  std::vector<Vec3> pool;      // the nets of the cells below the patch's own
  std::vector<double> pool_w;  // their weights (a rational patch), beside them
  std::vector<BzCell> cells;
  std::vector<BzBox> boxes;
  std::vector<int> open, settled;
};

class BzSearch {
 public:
  BzSearch(const BezierPatch& patch, const Vec3& p, BzScratch& scratch, double cutoff)
      : patch_(patch),
        p_(p),
        deg_{patch.degree_s(), patch.degree_t()},
        pool_(scratch.pool),
        pool_w_(scratch.pool_w),
        cells_(scratch.cells),
        boxes_(scratch.boxes),
        open_(scratch.open),
        settled_(scratch.settled),
        f_cut_(cutoff < std::numeric_limits<double>::infinity() ? 0.5 * cutoff * cutoff * (1.0 + 0x1p-48)
                                                                : std::numeric_limits<double>::infinity()) {
    stride_ = (deg_[0] + 1) * (deg_[1] + 1);
    magnitude_ = patch.magnitude() + std::numeric_limits<double>::min();
    weight_magnitude_ = patch.weight_magnitude() + std::numeric_limits<double>::min();
  }

  // Newton from (s, t); the answer replaces the candidate when nearer.
  void newton(double s, double t) {
    ++starts_;
    SurfaceJet j = patch_.power_jet(s, t);
    double f = 0.5 * norm2(j.s - p_), step_norm = 0.0;
    for (int it = 0; it < 60; ++it) {
      ++iterations_;
      const Vec3 r = j.s - p_;
      double g0 = dot(r, j.su), g1 = dot(r, j.sv);
      double h00 = dot(j.su, j.su) + dot(r, j.suu), h01 = dot(j.su, j.sv) + dot(r, j.suv),
             h11 = dot(j.sv, j.sv) + dot(r, j.svv);
      const bool free0 = !((s <= 0.0 && g0 > 0.0) || (s >= 1.0 && g0 < 0.0));
      const bool free1 = !((t <= 0.0 && g1 > 0.0) || (t >= 1.0 && g1 < 0.0));
      if (!free0) g0 = h01 = 0.0;
      if (!free1) g1 = h01 = 0.0;
      if (g0 == 0.0 && g1 == 0.0) break;
      double d0 = 0.0, d1 = 0.0;
      const double det = h00 * h11 - h01 * h01;
      if (free0 && free1 && h00 > 0.0 && det > 0.0) {
        d0 = -(h11 * g0 - h01 * g1) / det;
        d1 = -(h00 * g1 - h01 * g0) / det;
      } else if (free0 && !free1 && h00 > 0.0) {
        d0 = -g0 / h00;
      } else if (free1 && !free0 && h11 > 0.0) {
        d1 = -g1 / h11;
      } else {
        d0 = -g0 / std::max(dot(j.su, j.su), 1e-300);
        d1 = -g1 / std::max(dot(j.sv, j.sv), 1e-300);
      }
      // A step below the parameters' rounding: converged. Below 1e-8 Newton's step is within its
      // quadratic convergence: taken without a line search, it leaves an error of ~1e-16.
      const double size = std::max(std::fabs(d0), std::fabs(d1));
      if (!(size > 1e-15)) break;
      if (size < 1e-8) {
        const double ns = std::clamp(s + d0, 0.0, 1.0), nt = std::clamp(t + d1, 0.0, 1.0);
        step_norm = std::max(std::fabs(ns - s), std::fabs(nt - t));
        s = ns;
        t = nt;
        break;
      }
      // Backtracking while f grows beyond its own rounding.
      bool accepted = false;
      double ns = s, nt = t, nf = f;
      SurfaceJet nj;
      for (double step = 1.0; step > 0x1p-20; step *= 0.5) {
        ns = std::clamp(s + step * d0, 0.0, 1.0);
        nt = std::clamp(t + step * d1, 0.0, 1.0);
        nj = patch_.power_jet(ns, nt);
        nf = 0.5 * norm2(nj.s - p_);
        if (nf <= f * (1.0 + 0x1p-50)) {
          accepted = true;
          break;
        }
      }
      if (!accepted && size < 1e-5) {
        // So near the minimum f's decrease may be below its rounding: the full step is taken
        // where it shrinks the gradient instead (resolved far above its rounding there).
        ns = std::clamp(s + d0, 0.0, 1.0);
        nt = std::clamp(t + d1, 0.0, 1.0);
        nj = patch_.power_jet(ns, nt);
        nf = 0.5 * norm2(nj.s - p_);
        const Vec3 nr = nj.s - p_;
        const double n0 = free0 ? dot(nr, nj.su) : 0.0, n1 = free1 ? dot(nr, nj.sv) : 0.0;
        accepted = n0 * n0 + n1 * n1 < 0.25 * (g0 * g0 + g1 * g1);
      }
      if (!accepted || !std::isfinite(nf)) break;
      step_norm = std::max(std::fabs(ns - s), std::fabs(nt - t));
      s = ns;
      t = nt;
      j = nj;
      f = nf;
      if (step_norm <= 1e-15) break;
    }
    consider(s, t, step_norm, 1.0);
  }

  // (s, t) becomes the candidate where f is below `factor` times the candidate's.
  void consider(double s, double t, double step_norm, double factor) {
    // The answer by the Bernstein form: its rounding is what the enclosures below assume.
    const SurfaceJet j = patch_.jet(s, t);
    const double f = 0.5 * norm2(j.s - p_);
    if (!has_candidate_ || f < f_ * factor) {
      has_candidate_ = true;
      pole_ = -1;
      for (int e = 0; e < 4; ++e)
        if (patch_.pole(e) && (e == 0 ? s <= 0.0 : e == 1 ? s >= 1.0 : e == 2 ? t <= 0.0 : t >= 1.0))
          pole_ = e;
      s_ = s;
      t_ = t;
      jet_ = j;
      f_ = f;
      step_norm_ = step_norm;
      const double d = norm(j.s - p_);
      const Vec3 foot = j.s;
      gap_ = std::fmax(Certificate::kRelativeGap * d, Certificate::absolute_gap_at(p_, foot));
      distance_ = d;
      const BzPoint at = enclose(j);
      cand_f_ = at.f;
      cand_gs_ = at.gs;
      cand_gt_ = at.gt;
      const int pq = deg_[0] + deg_[1] + 2;
      f_cert_ = 0.5 * std::pow(std::max(d - 0.5 * gap_, 0.0), 2);
      f_tie_ = 0.5 * (d + gap_) * (d + gap_);
      if (patch_.rational()) rational_candidate(s, t, pq);
    }
  }

  // f (rounded down) and its gradient at a point of the patch, enclosed from the jet j there by
  // the Bernstein form (BezierPatch::jet): the Bernstein sums' rounding is at most (p + q + 2)
  // roundings of the net's magnitude per term (the basis is nonnegative and sums to 1; its
  // derivatives' absolute values sum to at most 2p), taken 16 times over.
  struct BzPoint {
    double f;
    BzInterval gs, gt;
  };
  BzPoint enclose(const SurfaceJet& j) const {
    const int pq = deg_[0] + deg_[1] + 2;
    const double err0 = 16.0 * pq * 0x1p-53 * magnitude_;
    const double err1 = 32.0 * std::max(deg_[0], deg_[1]) * pq * 0x1p-53 * magnitude_;
    BzVec r, es, et;
    for (int c = 0; c < 3; ++c) {
      const double x = j.s[c] - p_[c];
      r[c] = {bz_down(x - err0), bz_up(x + err0)};
      es[c] = {bz_down(j.su[c] - err1), bz_up(j.su[c] + err1)};
      et[c] = {bz_down(j.sv[c] - err1), bz_up(j.sv[c] + err1)};
    }
    return {0.5 * bz_norm2(r).lo, bz_dot(r, es), bz_dot(r, et)};
  }

  PatchNearest run(int max_boxes) {
    PatchNearest out;
    if (beyond_cutoff(out)) return out;
    // Newton from the parameters of the control point nearest p.
    int best = 0;
    double best_d2 = norm2(patch_.point(0) - p_);
    for (int i = 1; i < stride_; ++i) {
      const double d2 = norm2(patch_.point(static_cast<std::size_t>(i)) - p_);
      if (d2 < best_d2) {
        best_d2 = d2;
        best = i;
      }
    }
    newton(static_cast<double>(best / (deg_[1] + 1)) / deg_[0],
           static_cast<double>(best % (deg_[1] + 1)) / deg_[1]);
    if (!std::isfinite(f_)) return out;
    // Next to a pole the distance is flat along the pole's edge and Newton's steps towards it
    // shrink: the pole itself, where it is as near.
    for (int e = 0; e < 4; ++e)
      if (patch_.pole(e) && pole_ < 0)
        consider(e == 0   ? 0.0
                 : e == 1 ? 1.0
                          : s_,
                 e == 2   ? 0.0
                 : e == 3 ? 1.0
                          : t_,
                 step_norm_, 1.0 + 0x1p-45);

    pool_.clear();
    pool_w_.clear();
    cells_.clear();
    boxes_.clear();
    open_.clear();
    settled_.clear();
    file(0);
    while (!open_.empty()) {
      // The open box of the least bound.
      auto it = std::min_element(open_.begin(), open_.end(), [&](int a, int b) {
        return boxes_[static_cast<std::size_t>(a)].lower < boxes_[static_cast<std::size_t>(b)].lower;
      });
      const BzBox box = boxes_[static_cast<std::size_t>(*it)];
      open_.erase(it);
      if (static_cast<int>(boxes_.size()) + 4 > max_boxes) {
        out.boxes = static_cast<int>(boxes_.size());
        return out;
      }
      if (!box.contains(s_, t_) && box.lower < f_ && restarts_ < 3) {
        // It may hold a nearer point: Newton from its centre.
        ++restarts_;
        const double before = f_;
        newton(0.5 * (box.s0 + box.s1), 0.5 * (box.t0 + box.t1));
        if (f_ < before) {
          // A new candidate: every settled box is judged again.
          open_.insert(open_.end(), settled_.begin(), settled_.end());
          settled_.clear();
          settle_all();
        }
      }
      split(box);
    }
    double lower = f_;
    for (const int i : settled_) lower = std::min(lower, boxes_[static_cast<std::size_t>(i)].lower);
    out.proved = true;
    out.pole = pole_ >= 0;
    out.s = s_;
    out.t = t_;
    out.jet = jet_;
    out.distance = distance_;
    out.lower_bound = std::min(distance_, lower > 0.0 ? bz_down(std::sqrt(bz_down(2.0 * lower))) : 0.0);
    out.boxes = static_cast<int>(boxes_.size());
    out.iterations = iterations_;
    out.starts = starts_;
    out.step_norm = step_norm_;
    return out;
  }

 private:
  // A rational patch: the candidate's level L = |S(z) - p|² (as computed) and g_L = |A - pW|² - L W²
  // with its gradient at z = (s, t), enclosed from the homogeneous jet (its Bernstein sums within
  // err0, err1 of the net's magnitude as above): g_s = 2 (D·D_s - L W W_s), D = A - p W.
  void rational_candidate(double s, double t, int pq) {
    SurfaceJet a;
    std::array<double, 6> w{};
    patch_.homogeneous_jet(s, t, a, w);
    // A value's Bernstein sum: each basis value within 3n + 1 roundings (n levels of the triangle,
    // each a product, a sum and 1 - x), the two sums' p + q + 2, of a sum of |b_kl| B_kl <= m:
    // (4 (p + q) + 6) roundings of m, taken twice over.
    const double m = std::max(magnitude_, weight_magnitude_);
    const double err0 = 2.0 * (4.0 * (pq - 2) + 6.0) * 0x1p-53 * m;
    const double err1 = 32.0 * std::max(deg_[0], deg_[1]) * pq * 0x1p-53 * m;
    const auto widened = [](double x, double e) { return BzInterval{bz_down(x - e), bz_up(x + e)}; };
    const BzInterval W = widened(w[0], err0), Ws = widened(w[1], err1), Wt = widened(w[2], err1);
    BzVec D, Ds, Dt;
    for (int c = 0; c < 3; ++c) {
      const auto k = static_cast<std::size_t>(c);
      D[k] = formula::interval::sub(widened(a.s[c], err0), mul(p_[c], W));
      Ds[k] = formula::interval::sub(widened(a.su[c], err1), mul(p_[c], Ws));
      Dt[k] = formula::interval::sub(widened(a.sv[c], err1), mul(p_[c], Wt));
    }
    level_ = 2.0 * f_;
    const BzInterval L{level_, level_};
    cand_g_ = formula::interval::sub(bz_norm2(D), mul(L, sqr(W)));
    const BzInterval hs = formula::interval::sub(bz_dot(D, Ds), mul(L, mul(W, Ws)));
    const BzInterval ht = formula::interval::sub(bz_dot(D, Dt), mul(L, mul(W, Wt)));
    cand_gs_ = {2.0 * hs.lo, 2.0 * hs.hi};
    cand_gt_ = {2.0 * ht.lo, 2.0 * ht.hi};
  }

  // A rational cell's nets for this point.
  void level_nets(int id, const BzCell& c, BzLevelNets& nets) const {
    const Vec3* a = id >= 0 ? &patch_.cell_nets()[static_cast<std::size_t>(c.net)]
                            : &pool_[static_cast<std::size_t>(c.net)];
    const double* w = id >= 0 ? &patch_.cell_weights()[static_cast<std::size_t>(c.net)]
                              : &pool_w_[static_cast<std::size_t>(c.net)];
    bz_level_nets(a, w, deg_[0], deg_[1], c.err, c.err_w, p_, nets);
  }

  // F = |S - p|² >= min_k N_k / M_k over the cell (N = F M with every M_k > 0), in f = F / 2.
  static double ratio_bound(const BzLevelNets& nets, int count) {
    if (!(nets.m_lo > 0.0)) return 0.0;
    double least = std::numeric_limits<double>::infinity();
    for (int k = 0; k < count && least > 0.0; ++k) {
      const double n = bz_down(nets.n[k] - nets.err_n);
      least = std::min(least, n > 0.0 ? bz_down(n / bz_up(nets.m[k] + nets.err_m)) : 0.0);
    }
    return std::isfinite(least) ? bz_down(0.5 * least) : 0.0;
  }

  // f >= ½ (L + g / M) over a cell where g_L >= g_low, M = W² in [m_lo, m_hi].
  double level_bound(double g_low, const BzLevelNets& nets) const {
    if (!std::isfinite(g_low) || !(nets.m_lo > 0.0)) return 0.0;
    const double F = g_low >= 0.0 ? bz_down(level_ + bz_down(g_low / nets.m_hi))
                                  : bz_down(level_ + bz_down(g_low / nets.m_lo));
    return std::max(0.0, bz_down(0.5 * F));
  }

  // A rational cell bounded for this point: by its hull, by the ratio of N's and M's nets, and by
  // g_L (L the candidate's level): its Taylor form from the candidate on a cell holding it, else
  // from the corner nearest it, the Hessian enclosed from g_L's nets of second differences. On a
  // cell holding the candidate, λ bounds below the least eigenvalue of g_L'’s Hessian for every
  // level L' between the cell's lower bound and the tie's (see the header).
  // Its hull's bound is b.lower already.
  void rational_bound(BzBox& b, const BzCell& c) const {
    double lower = b.lower;
    const bool holds = b.contains(s_, t_);
    BzLevelNets nets;
    level_nets(b.cell, c, nets);
    const int P = 2 * deg_[0], Q = 2 * deg_[1], count = (P + 1) * (Q + 1);
    lower = std::max(lower, ratio_bound(nets, count));
    b.lower = lower;
    if ((!holds && lower > f_tie_) || lower > f_cut_ || !(nets.m_lo > 0.0)) return;
    double g[BzLevelNets::kSize];
    for (int k = 0; k < count; ++k) g[k] = nets.n[k] - level_ * nets.m[k];
    const double err_g =
        bz_up(nets.err_n + level_ * nets.err_m + 0x1p-51 * (nets.n_max + level_ * nets.m_hi));
    BzInterval gss, gst, gtt;
    bz_hessian_hull(g, P, Q, err_g, gss, gst, gtt);
    if (holds) {
      lower =
          std::max(lower, level_bound(bz_down(cand_g_.lo + candidate_form(b, gss, gst, gtt).least), nets));
      b.lower = lower;
      // The levels L' of local minima within the tie: [2 lower, 2 f_tie]; Hess g_L' = Hess g_L -
      // (L' - L) Hess M.
      double mss[BzLevelNets::kSize];
      std::copy(nets.m, nets.m + count, mss);
      BzInterval mxx, mxy, myy;
      bz_hessian_hull(mss, P, Q, nets.err_m, mxx, mxy, myy);
      const BzInterval shift{std::min(0.0, bz_down(2.0 * lower - level_)),
                             std::max(0.0, bz_up(2.0 * f_tie_ - level_))};
      const BzInterval hxx = formula::interval::sub(gss, mul(shift, mxx));
      const BzInterval hyy = formula::interval::sub(gtt, mul(shift, myy));
      const BzInterval hxy = formula::interval::sub(gst, mul(shift, mxy));
      const double ha = hxx.lo, hc = hyy.lo, hb = std::max(std::fabs(hxy.lo), std::fabs(hxy.hi));
      double lambda = 0.5 * (ha + hc) - std::sqrt(0.25 * (ha - hc) * (ha - hc) + hb * hb);
      lambda -= (std::fabs(ha) + std::fabs(hc) + hb) * 0x1p-48;
      if (std::isfinite(lambda)) b.lambda = lambda;
      return;
    }
    // Taylor from the corner (cs, ct) nearest the candidate, in the inward local parameters.
    const int cs = s_ - b.s0 > b.s1 - s_ ? 1 : 0, ct = t_ - b.t0 > b.t1 - t_ ? 1 : 0;
    const int K = cs ? P : 0, L = ct ? Q : 0, Ki = cs ? P - 1 : 1, Li = ct ? Q - 1 : 1;
    const auto at = [&](int k, int l) { return g[k * (Q + 1) + l]; };
    const double e1 =
        2.0 * err_g + 0x1p-51 * (std::fabs(at(K, L)) + std::fabs(at(Ki, L)) + std::fabs(at(K, Li)));
    const double gs = bz_down(P * bz_down(at(Ki, L) - at(K, L)) - P * e1);
    const double gt = bz_down(Q * bz_down(at(K, Li) - at(K, L)) - Q * e1);
    const int sign_s = cs ? -1 : 1, sign_t = ct ? -1 : 1;
    const double E = sign_s * sign_t > 0 ? gst.lo : -gst.hi;
    const double g_low =
        bz_down(bz_down(at(K, L) - err_g) + bz_min_form(gs, gt, gss.lo, gtt.lo, E, 1.0, 1.0));
    b.lower = std::max(lower, level_bound(g_low, nets));
  }

  // Whether the kept cells of one level (the root, its quarters, theirs) are all beyond the
  // cutoff, by their hulls and a second-order form from their corner nearest p: then no point of
  // the patch is within it, and `out` is its corner nearest p (a point of it: a Bézier patch
  // interpolates its corner points) with the least of those bounds.
  bool beyond_cutoff(PatchNearest& out) const {
    if (!(f_cut_ < std::numeric_limits<double>::infinity())) return false;
    const std::vector<BzCell>& cells = patch_.cells();
    std::size_t begin = 0, count = 1;
    for (int level = 0; level <= BezierPatch::kCellLevels && begin + count <= cells.size(); ++level) {
      double least = std::numeric_limits<double>::infinity();
      for (std::size_t i = begin; i < begin + count && least > f_cut_; ++i)
        least = std::min(least, beyond_bound(static_cast<int>(i), cells[i]));
      out.boxes += static_cast<int>(count);
      if (least > f_cut_) {
        const int corners[4][2] = {{0, 0}, {deg_[0], 0}, {0, deg_[1]}, {deg_[0], deg_[1]}};
        int nearest = 0;
        double d2 = std::numeric_limits<double>::infinity();
        for (int c = 0; c < 4; ++c) {
          const double e = norm2(
              patch_.point(static_cast<std::size_t>(corners[c][0] * (deg_[1] + 1) + corners[c][1])) - p_);
          if (e < d2) {
            d2 = e;
            nearest = c;
          }
        }
        out.proved = true;
        out.s = corners[nearest][0] == 0 ? 0.0 : 1.0;
        out.t = corners[nearest][1] == 0 ? 0.0 : 1.0;
        out.jet = patch_.jet(out.s, out.t);
        out.distance = norm(out.jet.s - p_);
        out.lower_bound = std::min(out.distance, bz_down(std::sqrt(bz_down(2.0 * least))));
        return true;
      }
      begin += count;
      count *= 4;
    }
    return false;
  }

  // A cell's lower bound of f without a candidate: its hull's, else the larger of that and the
  // second-order form from its corner nearest p; infinite where f descends inwards over it
  // (descends_inwards: the patch's least value is attained in the other cells).
  double beyond_bound(int id, const BzCell& c) const {
    BzVec r;
    const double lower = hull_bound(c, r);
    if (lower > f_cut_) return lower;
    if (patch_.rational()) {
      BzLevelNets nets;
      level_nets(id, c, nets);
      return std::max(lower, ratio_bound(nets, (2 * deg_[0] + 1) * (2 * deg_[1] + 1)));
    }
    if (descends_inwards(c.s0, c.s1, c.t0, c.t1, bz_dot(r, c.su), bz_dot(r, c.sv)))
      return std::numeric_limits<double>::infinity();
    const BzInterval fss = add(c.su2, bz_dot(r, c.suu)), ftt = add(c.sv2, bz_dot(r, c.svv));
    const BzInterval fst = add(c.susv, bz_dot(r, c.suv));
    int best = 0;
    double least = std::numeric_limits<double>::infinity();
    for (int i = 0; i < 4; ++i) {
      double e = 0.0;
      for (std::size_t d = 0; d < 3; ++d) {
        const double mid = 0.5 * (c.corners[static_cast<std::size_t>(i)].point[d].lo +
                                  c.corners[static_cast<std::size_t>(i)].point[d].hi) -
                           p_[static_cast<int>(d)];
        e += mid * mid;
      }
      if (e < least) {
        least = e;
        best = i;
      }
    }
    const double taylor = corner_taylor(c, best / 2, best % 2, fss, fst, ftt);
    return std::isfinite(taylor) ? std::max(lower, taylor) : lower;
  }

  // The second-order lower bound of f over a cell from its corner (cs, ct), in the inward local
  // parameters δ in [0, 1]².
  double corner_taylor(const BzCell& c, int cs, int ct, BzInterval fss, BzInterval fst,
                       BzInterval ftt) const {
    const BzCell::Corner& corner = c.corners[static_cast<std::size_t>(cs * 2 + ct)];
    BzVec rc;
    for (int d = 0; d < 3; ++d)
      rc[static_cast<std::size_t>(d)] = {bz_down(corner.point[static_cast<std::size_t>(d)].lo - p_[d]),
                                         bz_up(corner.point[static_cast<std::size_t>(d)].hi - p_[d])};
    const double fc = 0.5 * bz_norm2(rc).lo;
    // The inward directions: δs = sign_s x with sign_s = +1 from s = 0, -1 from s = 1; es and et
    // already point inwards (the gradient's sign is folded in), the cross term's sign is not.
    const BzInterval gs = bz_dot(corner.es, rc), gt = bz_dot(corner.et, rc);
    const int sign_s = cs ? -1 : 1, sign_t = ct ? -1 : 1;
    const double E = sign_s * sign_t > 0 ? fst.lo : -fst.hi;
    return bz_down(fc + bz_min_form(gs.lo, gt.lo, fss.lo, ftt.lo, E, 1.0, 1.0));
  }

  const BzCell& cell(int id) const {
    return id >= 0 ? patch_.cells()[static_cast<std::size_t>(id)] : cells_[static_cast<std::size_t>(-1 - id)];
  }

  // Splits a box into its four quarters (the patch's cells where it has them, else by de
  // Casteljau from the box's net), bounds them and files them as open or settled.
  void split(const BzBox& box) {
    const BzCell& c = cell(box.cell);
    if (box.cell >= 0 && c.child >= 0) {
      for (int i = 0; i < 4; ++i) file(c.child + i);
      return;
    }
    Vec3 net[(BezierPatch::kMaxDegree + 1) * (BezierPatch::kMaxDegree + 1)];
    const Vec3* source = box.cell >= 0 ? &patch_.cell_nets()[static_cast<std::size_t>(c.net)]
                                       : &pool_[static_cast<std::size_t>(c.net)];
    std::copy(source, source + stride_, net);
    const double err = c.err + bz_quarter_error(deg_[0], deg_[1], magnitude_);
    const double s0 = c.s0, s1 = c.s1, t0 = c.t0, t1 = c.t1, sm = 0.5 * (s0 + s1), tm = 0.5 * (t0 + t1);
    const auto first = static_cast<int>(pool_.size());
    pool_.resize(pool_.size() + 4 * static_cast<std::size_t>(stride_));
    bz_quarters(net, deg_[0], deg_[1], &pool_[static_cast<std::size_t>(first)]);
    const bool rational = patch_.rational();
    const double err_w = c.err_w + bz_quarter_error(deg_[0], deg_[1], weight_magnitude_);
    if (rational) {
      double w[(BezierPatch::kMaxDegree + 1) * (BezierPatch::kMaxDegree + 1)];
      const double* wsource = box.cell >= 0 ? &patch_.cell_weights()[static_cast<std::size_t>(c.net)]
                                            : &pool_w_[static_cast<std::size_t>(c.net)];
      std::copy(wsource, wsource + stride_, w);
      pool_w_.resize(pool_.size());
      bz_quarters(w, deg_[0], deg_[1], &pool_w_[static_cast<std::size_t>(first)]);
    }
    const double bounds[4][4] = {{s0, sm, t0, tm}, {s0, sm, tm, t1}, {sm, s1, t0, tm}, {sm, s1, tm, t1}};
    for (int i = 0; i < 4; ++i) {
      const int offset = first + i * stride_;
      BzCell child =
          rational ? bz_make_rational_cell(&pool_[static_cast<std::size_t>(offset)],
                                           &pool_w_[static_cast<std::size_t>(offset)], deg_[0], deg_[1], err,
                                           err_w, bounds[i][0], bounds[i][1], bounds[i][2], bounds[i][3])
                   : bz_make_cell(&pool_[static_cast<std::size_t>(offset)], deg_[0], deg_[1], err, magnitude_,
                                  bounds[i][0], bounds[i][1], bounds[i][2], bounds[i][3]);
      child.net = offset;
      cells_.push_back(child);
      file(-static_cast<int>(cells_.size()));
    }
  }

  // Bounds the box of a cell and files it as open or settled.
  void file(int id) {
    const BzCell& c = cell(id);
    BzBox box{id, c.s0, c.s1, c.t0, c.t1};
    bound(box, c);
    boxes_.push_back(box);
    if (descends_inwards(box)) return;
    const int index = static_cast<int>(boxes_.size()) - 1;
    (is_settled(box) ? settled_ : open_).push_back(index);
  }

  // Whether f is strictly monotone over the box along a direction in which the box's lower side
  // (f increasing) or upper side (decreasing) is inside the patch: then at every point y of the
  // box that partial derivative is nonzero and a step against it stays in the patch (y is not on
  // the patch's side there), so y is neither the patch's nearest point nor a local minimum. The
  // box drops out of the search and of the bound: the least of f over the patch is attained
  // outside every such box, i.e. in the boxes kept ([Hansen] the monotonicity test). The
  // gradient's enclosures (fs, ft) hold over the closed box; where they are not computed they are
  // the whole line.
  static bool descends_inwards(const BzBox& b) {
    return descends_inwards(b.s0, b.s1, b.t0, b.t1, b.fs, b.ft);
  }
  static bool descends_inwards(double s0, double s1, double t0, double t1, BzInterval fs, BzInterval ft) {
    return (fs.lo > 0.0 && s0 > 0.0) || (fs.hi < 0.0 && s1 < 1.0) || (ft.lo > 0.0 && t0 > 0.0) ||
           (ft.hi < 0.0 && t1 < 1.0);
  }

  void settle_all() {
    std::size_t keep = 0;
    for (const int i : open_)
      if (is_settled(boxes_[static_cast<std::size_t>(i)]))
        settled_.push_back(i);
      else
        open_[keep++] = i;
    open_.resize(keep);
  }

  // Cannot hold a foot within the gap of the candidate other than the candidate itself. A box
  // holding the candidate x*: along a direction where x* is on the patch's edge and f decreases
  // towards that edge over the whole box, no local minimum lies off the edge; along the others f
  // must be strictly convex (both: λ > 0), so that the box's only local minimum is the minimum of
  // f over it, which x* is (it meets the patch's first-order conditions, and so the box's).
  bool is_settled(const BzBox& b) const {
    if (b.lower > f_cut_) return true;  // beyond the cutoff: no answer, no tie there
    // The candidate at a pole, which every box along the pole's edge holds: their bound suffices
    // (the foot's multiplicity is then the caller's, PatchNearest::pole).
    if (pole_ >= 0 && (pole_ == 0   ? b.s0 <= 0.0
                       : pole_ == 1 ? b.s1 >= 1.0
                       : pole_ == 2 ? b.t0 <= 0.0
                                    : b.t1 >= 1.0))
      return b.lower >= f_cert_;
    if (!b.contains(s_, t_)) return b.lower > f_tie_;
    const bool edge_s = (s_ <= 0.0 && b.fs.lo > 0.0) || (s_ >= 1.0 && b.fs.hi < 0.0);
    const bool edge_t = (t_ <= 0.0 && b.ft.lo > 0.0) || (t_ >= 1.0 && b.ft.hi < 0.0);
    const bool single = edge_s && edge_t ? true
                        : edge_s         ? b.ftt > 0.0
                        : edge_t         ? b.fss > 0.0
                                         : b.lambda > 0.0;
    return single && b.lower >= f_cert_;
  }

  // f's lower bound over a cell from the box of its net (the hull), and S - p enclosed as r.
  double hull_bound(const BzCell& c, BzVec& r) const {
    Box3 hull;
    for (int d = 0; d < 3; ++d) {
      r[static_cast<std::size_t>(d)] = {bz_down(c.lo[d] - p_[d]), bz_up(c.hi[d] - p_[d])};
      hull.lo[d] = c.lo[d];
      hull.hi[d] = c.hi[d];
    }
    const double dh = distance_lower_bound(hull, p_);
    const double lower = bz_down(0.5 * bz_down(dh * dh));
    return std::isfinite(lower) ? lower : 0.0;
  }

  // Taylor's form from a point z = (s, t) of a box (the candidate x* on a box holding it), in the
  // box's local parameters: δ in [ds, dt] about z, the gradient (gs, gt) at z scaled by the box's
  // widths to as, at, and the least over the box of as δs + at δt + ½ δᵀ H δ for every H in (hss,
  // hst, htt).
  struct BzForm {
    double least;
    BzInterval ds, dt, as, at;
  };
  BzForm candidate_form(const BzBox& b, BzInterval hss, BzInterval hst, BzInterval htt) const {
    return taylor_form(b, s_, t_, cand_gs_, cand_gt_, hss, hst, htt);
  }
  static BzForm taylor_form(const BzBox& b, double s, double t, BzInterval gs, BzInterval gt, BzInterval hss,
                            BzInterval hst, BzInterval htt) {
    const double ws = b.s1 - b.s0, wt = b.t1 - b.t0;
    const double ls = std::min(bz_down((b.s0 - s) / ws), 0.0), hs = std::max(bz_up((b.s1 - s) / ws), 0.0);
    const double lt = std::min(bz_down((b.t0 - t) / wt), 0.0), ht = std::max(bz_up((b.t1 - t) / wt), 0.0);
    BzForm form{0.0, {ls, hs}, {lt, ht}, bz_scaled(gs, ws), bz_scaled(gt, wt)};
    for (const int sign_s : {-1, 1})
      for (const int sign_t : {-1, 1}) {
        const double X = sign_s > 0 ? hs : -ls, Y = sign_t > 0 ? ht : -lt;
        // A quadrant of no width lies in its neighbour across that side.
        if (X > 0.0 && Y > 0.0)
          form.least =
              std::min(form.least, bz_quadrant(form.as, form.at, hss, hst, htt, sign_s, sign_t, X, Y));
      }
    return form;
  }

  void bound(BzBox& b, const BzCell& c) const {
    BzVec r;
    double lower = hull_bound(c, r);
    b.lower = lower;
    b.lambda = -std::numeric_limits<double>::infinity();
    b.fs = b.ft = {-std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
    b.fss = b.ftt = -std::numeric_limits<double>::infinity();
    if ((!b.contains(s_, t_) && b.lower > f_tie_) || b.lower > f_cut_) return;  // settled by the hull alone
    if (patch_.rational()) {
      rational_bound(b, c);
      return;
    }
    // f's Hessian over the box and its smallest eigenvalue, bounded below: λ_min of [a b; b c] is
    // (a + c)/2 - sqrt(((a - c)/2)² + b²), increasing in a and c, decreasing in |b|.
    const BzInterval fss = add(c.su2, bz_dot(r, c.suu)), ftt = add(c.sv2, bz_dot(r, c.svv));
    const BzInterval fst = add(c.susv, bz_dot(r, c.suv));
    const double ha = fss.lo, hc = ftt.lo, hb = std::max(std::fabs(fst.lo), std::fabs(fst.hi));
    double lambda = 0.5 * (ha + hc) - std::sqrt(0.25 * (ha - hc) * (ha - hc) + hb * hb);
    lambda -= (std::fabs(ha) + std::fabs(hc) + hb) * 0x1p-48;
    if (!std::isfinite(lambda)) return;
    b.lambda = lambda;
    b.fs = bz_dot(r, c.su);
    b.ft = bz_dot(r, c.sv);
    b.fss = fss.lo;
    b.ftt = ftt.lo;
    // Taylor from the point z of the box nearest the candidate x* in the parameters: x* itself on
    // a box holding it, else a corner (whose jet the cell holds) or a point of a side (evaluated).
    // Near x*, where the boxes about a minimum cluster, f(z) exceeds f(x*) by ~ ½ |z - x*|² in
    // f's Hessian, which an expansion from a farther corner loses. The gradient over the box in
    // the centred form ∇f(z) + H δ bounds its sign far tighter than the hulls' product near z.
    const double zs = std::clamp(s_, b.s0, b.s1), zt = std::clamp(t_, b.t0, b.t1);
    const bool side_s = zs == b.s0 || zs == b.s1, side_t = zt == b.t0 || zt == b.t1;
    if (!b.contains(s_, t_) && side_s && side_t) {
      lower = std::max(lower, corner_taylor(c, zs == b.s1 ? 1 : 0, zt == b.t1 ? 1 : 0, fss, fst, ftt));
      b.lower = std::isfinite(lower) ? lower : 0.0;
      return;
    }
    BzForm form{};
    double fz = cand_f_;
    if (b.contains(s_, t_)) {
      form = candidate_form(b, fss, fst, ftt);
    } else {
      const BzPoint z = enclose(patch_.jet(zs, zt));
      form = taylor_form(b, zs, zt, z.gs, z.gt, fss, fst, ftt);
      fz = z.f;
    }
    lower = std::max(lower, bz_down(fz + form.least));
    b.lower = std::isfinite(lower) ? lower : 0.0;
    const BzInterval cs = add(form.as, add(mul(fss, form.ds), mul(fst, form.dt)));
    const BzInterval ct = add(form.at, add(mul(fst, form.ds), mul(ftt, form.dt)));
    b.fs = {std::max(b.fs.lo, cs.lo), std::min(b.fs.hi, cs.hi)};
    b.ft = {std::max(b.ft.lo, ct.lo), std::min(b.ft.hi, ct.hi)};
  }

  const BezierPatch& patch_;
  Vec3 p_;
  std::array<int, 2> deg_;
  int stride_ = 0;
  double magnitude_ = 0.0;

  bool has_candidate_ = false;
  double s_ = 0.0, t_ = 0.0, f_ = std::numeric_limits<double>::infinity(), distance_ = 0.0, gap_ = 0.0;
  double f_cert_ = 0.0, f_tie_ = 0.0, step_norm_ = 0.0;
  SurfaceJet jet_{};
  double cand_f_ = 0.0;                               // f at the candidate, rounded down
  BzInterval cand_gs_{0.0, 0.0}, cand_gt_{0.0, 0.0};  // its gradient (the patch's parameters)
  int iterations_ = 0, starts_ = 0, restarts_ = 0;
  double weight_magnitude_ = 0.0;
  double level_ = 0.0;
  int pole_ = -1;  // the candidate's degenerate edge (BezierPatch::pole), -1: none           // a rational
                   // patch: the candidate's |S - p|²
  BzInterval cand_g_{0.0, 0.0};  // and g at the candidate (cand_gs_, cand_gt_: its gradient)

  std::vector<Vec3>& pool_;
  std::vector<double>& pool_w_;
  std::vector<BzCell>& cells_;
  std::vector<BzBox>& boxes_;
  std::vector<int>&open_, &settled_;
  double f_cut_;  // ½ cutoff², rounded up
};

}  // namespace

namespace {

// Σ_k b_k B_k^n(x) = Σ_j a_j x^j with a_j = binom(n, j) Σ_{k<=j} binom(j, k) (-1)^(j-k) b_k, along s
// then t.
template <class T>
std::vector<T> bz_power_basis(const std::vector<T>& net, int p, int q) {
  auto index = [&](int k, int l) { return static_cast<std::size_t>(k * (q + 1) + l); };
  const auto sign = [](int n) { return n % 2 ? -1.0 : 1.0; };
  std::vector<T> along_s(net.size(), T{});
  for (int l = 0; l <= q; ++l)
    for (int j = 0; j <= p; ++j)
      for (int k = 0; k <= j; ++k)
        along_s[index(j, l)] += (kBinomials.c[p][j] * kBinomials.c[j][k] * sign(j - k)) * net[index(k, l)];
  std::vector<T> power(net.size(), T{});
  for (int k = 0; k <= p; ++k)
    for (int j = 0; j <= q; ++j)
      for (int l = 0; l <= j; ++l)
        power[index(k, j)] += (kBinomials.c[q][j] * kBinomials.c[j][l] * sign(j - l)) * along_s[index(k, l)];
  return power;
}

// The value and derivatives (s, t, ss, st, tt) at (s, t) of the power-basis form a, by Horner's
// scheme in t per row k (the row's value, first and half second derivative), then in s.
template <class T>
std::array<T, 6> bz_horner(const T* a, int p, int q, double s, double t) {
  T v[BezierPatch::kMaxDegree + 1], d1[BezierPatch::kMaxDegree + 1], d2[BezierPatch::kMaxDegree + 1];
  for (int k = 0; k <= p; ++k) {
    const T* row = a + k * (q + 1);
    T x = row[q], x1{}, x2{};
    for (int l = q - 1; l >= 0; --l) {
      x2 = x2 * t + x1;
      x1 = x1 * t + x;
      x = x * t + row[l];
    }
    v[k] = x;
    d1[k] = x1;
    d2[k] = 2.0 * x2;
  }
  T y = v[p], y1{}, y2{}, z = d1[p], z1{}, w = d2[p];
  for (int k = p - 1; k >= 0; --k) {
    y2 = y2 * s + y1;
    y1 = y1 * s + y;
    y = y * s + v[k];
    z1 = z1 * s + z;
    z = z * s + d1[k];
    w = w * s + d2[k];
  }
  return {y, y1, z, 2.0 * y2, z1, w};
}

// The same from the Bernstein net b by the basis and its derivatives.
template <class T>
std::array<T, 6> bz_bernstein(const T* b, int p, int q, double s, double t) {
  double bs[3][BezierPatch::kMaxDegree + 1], bt[3][BezierPatch::kMaxDegree + 1];
  bz_basis(p, s, bs[0], bs[1], bs[2]);
  bz_basis(q, t, bt[0], bt[1], bt[2]);
  std::array<T, 6> out{};
  for (int k = 0; k <= p; ++k) {
    // The row's sums along t: value, d/dt, d²/dt².
    T r0{}, r1{}, r2{};
    for (int l = 0; l <= q; ++l) {
      const T& x = b[k * (q + 1) + l];
      r0 += bt[0][l] * x;
      r1 += bt[1][l] * x;
      r2 += bt[2][l] * x;
    }
    out[0] += bs[0][k] * r0;
    out[1] += bs[1][k] * r0;
    out[2] += bs[0][k] * r1;
    out[3] += bs[2][k] * r0;
    out[4] += bs[1][k] * r1;
    out[5] += bs[0][k] * r2;
  }
  return out;
}

SurfaceJet bz_jet(const std::array<Vec3, 6>& a) { return {a[0], a[1], a[2], a[3], a[4], a[5]}; }

// S = A / W and its derivatives from A's and W's: A = W S differentiated ([PieglTiller] algorithm A4.4).
SurfaceJet bz_quotient(const std::array<Vec3, 6>& a, const std::array<double, 6>& w) {
  SurfaceJet j{};
  const double iw = 1.0 / w[0];
  j.s = iw * a[0];
  j.su = iw * (a[1] - w[1] * j.s);
  j.sv = iw * (a[2] - w[2] * j.s);
  j.suu = iw * (a[3] - 2.0 * w[1] * j.su - w[3] * j.s);
  j.suv = iw * (a[4] - w[1] * j.sv - w[2] * j.su - w[4] * j.s);
  j.svv = iw * (a[5] - 2.0 * w[2] * j.sv - w[5] * j.s);
  return j;
}

}  // namespace

BezierPatch::BezierPatch(int p, int q, std::vector<Vec3> net, std::vector<double> weights)
    : p_(p), q_(q), net_(std::move(net)), weights_(std::move(weights)) {
  for (const Vec3& x : net_)
    magnitude_ = std::max({magnitude_, std::fabs(x.x), std::fabs(x.y), std::fabs(x.z)});
  for (const double w : weights_) weight_magnitude_ = std::max(weight_magnitude_, std::fabs(w));
  power_ = bz_power_basis(net_, p_, q_);
  for (int e = 0; e < 4; ++e) {
    const int count = e < 2 ? q_ + 1 : p_ + 1;
    const auto index = [&](int i) {
      return static_cast<std::size_t>(e == 0   ? i
                                      : e == 1 ? p_ * (q_ + 1) + i
                                      : e == 2 ? i * (q_ + 1)
                                               : i * (q_ + 1) + q_);
    };
    const Vec3 first = point(index(0));
    bool same = true;
    for (int i = 1; i < count; ++i) {
      const Vec3 d = point(index(i)) - first;
      same = same && std::max({std::fabs(d.x), std::fabs(d.y), std::fabs(d.z)}) <=
                         0x1p-48 * (magnitude_ + weight_magnitude_ + std::numeric_limits<double>::min());
    }
    poles_[static_cast<std::size_t>(e)] = same;
  }
  if (rational()) power_w_ = bz_power_basis(weights_, p_, q_);
  // The cells of the first kCellLevels levels of quarters, each with its net.
  const double m = magnitude_ + std::numeric_limits<double>::min();
  const double mw = weight_magnitude_ + std::numeric_limits<double>::min();
  const auto stride = static_cast<std::size_t>((p_ + 1) * (q_ + 1));
  std::size_t cells = 1;
  for (int level = 0, width = 1; level < kCellLevels; ++level, width *= 4)
    cells += 4 * static_cast<std::size_t>(width);
  cells_.reserve(cells);
  cell_nets_.reserve(cells * stride);
  cell_nets_ = net_;
  if (rational()) {
    cell_weights_.reserve(cells * stride);
    cell_weights_ = weights_;
  }
  const auto make = [&](std::size_t first, double err, double err_w, double s0, double s1, double t0,
                        double t1) {
    return rational() ? bz_make_rational_cell(&cell_nets_[first], &cell_weights_[first], p_, q_, err, err_w,
                                              s0, s1, t0, t1)
                      : bz_make_cell(&cell_nets_[first], p_, q_, err, m, s0, s1, t0, t1);
  };
  cells_.push_back(make(0, 0.0, 0.0, 0.0, 1.0, 0.0, 1.0));
  cells_.back().net = 0;
  std::size_t level_begin = 0;
  for (int level = 0; level < kCellLevels; ++level) {
    const std::size_t level_end = cells_.size();
    for (std::size_t i = level_begin; i < level_end; ++i) {
      const std::size_t first = cell_nets_.size();
      const auto parent = static_cast<std::size_t>(cells_[i].net);
      cell_nets_.resize(first + 4 * stride);
      Vec3 copy[(kMaxDegree + 1) * (kMaxDegree + 1)];
      std::copy(&cell_nets_[parent], &cell_nets_[parent] + stride, copy);
      bz_quarters(copy, p_, q_, &cell_nets_[first]);
      if (rational()) {
        cell_weights_.resize(first + 4 * stride);
        double wcopy[(kMaxDegree + 1) * (kMaxDegree + 1)];
        std::copy(&cell_weights_[parent], &cell_weights_[parent] + stride, wcopy);
        bz_quarters(wcopy, p_, q_, &cell_weights_[first]);
      }
      const BzCell c = cells_[i];
      const double sm = 0.5 * (c.s0 + c.s1), tm = 0.5 * (c.t0 + c.t1);
      const double bounds[4][4] = {
          {c.s0, sm, c.t0, tm}, {c.s0, sm, tm, c.t1}, {sm, c.s1, c.t0, tm}, {sm, c.s1, tm, c.t1}};
      cells_[i].child = static_cast<int>(cells_.size());
      for (std::size_t k = 0; k < 4; ++k) {
        BzCell child = make(first + k * stride, c.err + bz_quarter_error(p_, q_, m),
                            c.err_w + bz_quarter_error(p_, q_, mw), bounds[k][0], bounds[k][1], bounds[k][2],
                            bounds[k][3]);
        child.net = static_cast<int>(first + k * stride);
        cells_.push_back(child);
      }
    }
    level_begin = level_end;
  }
}

SurfaceJet BezierPatch::power_jet(double s, double t) const {
  const std::array<Vec3, 6> a = bz_horner(power_.data(), p_, q_, s, t);
  return rational() ? bz_quotient(a, bz_horner(power_w_.data(), p_, q_, s, t)) : bz_jet(a);
}

SurfaceJet BezierPatch::jet(double s, double t) const {
  const std::array<Vec3, 6> a = bz_bernstein(net_.data(), p_, q_, s, t);
  return rational() ? bz_quotient(a, bz_bernstein(weights_.data(), p_, q_, s, t)) : bz_jet(a);
}

void BezierPatch::homogeneous_jet(double s, double t, SurfaceJet& a, std::array<double, 6>& w) const {
  a = bz_jet(bz_bernstein(net_.data(), p_, q_, s, t));
  w = rational() ? bz_bernstein(weights_.data(), p_, q_, s, t)
                 : std::array<double, 6>{1.0, 0.0, 0.0, 0.0, 0.0, 0.0};
}

std::vector<double> distance_level_net(const BezierPatch& patch, const Vec3& p, double L) {
  const std::vector<double> ones(patch.net().size(), 1.0);
  const std::vector<double>& w = patch.rational() ? patch.weights() : ones;
  BzLevelNets nets;
  bz_level_nets(patch.net().data(), w.data(), patch.degree_s(), patch.degree_t(), 0.0, 0.0, p, nets);
  std::vector<double> g(static_cast<std::size_t>((2 * patch.degree_s() + 1) * (2 * patch.degree_t() + 1)));
  for (std::size_t k = 0; k < g.size(); ++k) g[k] = nets.n[k] - L * nets.m[k];
  return g;
}

PatchNearest nearest_on_patch(const BezierPatch& patch, const Vec3& p, int max_boxes, double cutoff) {
  thread_local BzScratch scratch;
  BzSearch search(patch, p, scratch, cutoff);
  return search.run(max_boxes);
}

}  // namespace footpoint
