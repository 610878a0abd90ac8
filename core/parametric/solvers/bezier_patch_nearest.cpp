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
BzInterval bz_dot(const BzVec& a, const BzVec& b) {
  return add(add(mul(a[0], b[0]), mul(a[1], b[1])), mul(a[2], b[2]));
}
BzInterval bz_norm2(const BzVec& a) { return add(add(sqr(a[0]), sqr(a[1])), sqr(a[2])); }

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
void bz_basis(int n, double x, double* b0, double* b1, double* b2) {
  double level[BezierPatch::kMaxDegree + 1][BezierPatch::kMaxDegree + 1] = {};
  level[0][0] = 1.0;
  for (int m = 1; m <= n; ++m) {
    level[m][0] = (1.0 - x) * level[m - 1][0];
    for (int k = 1; k < m; ++k) level[m][k] = (1.0 - x) * level[m - 1][k] + x * level[m - 1][k - 1];
    level[m][m] = x * level[m - 1][m - 1];
  }
  auto at = [&](int m, int k) { return m < 0 || k < 0 || k > m ? 0.0 : level[m][k]; };
  for (int k = 0; k <= n; ++k) {
    b0[k] = level[n][k];
    b1[k] = n * (at(n - 1, k - 1) - at(n - 1, k));
    b2[k] = n * (n - 1) * (at(n - 2, k - 2) - 2.0 * at(n - 2, k - 1) + at(n - 2, k));
  }
}

// de Casteljau at a along s (dir 0: the index k of b_kl) or t (dir 1), net of (p + 1) x (q + 1).
void bz_split(const Vec3* in, int p, int q, int dir, double a, Vec3* left, Vec3* right) {
  const int n = dir == 0 ? p : q, lines = dir == 0 ? q + 1 : p + 1;
  auto index = [&](int along, int line) {
    return dir == 0 ? along * (q + 1) + line : line * (q + 1) + along;
  };
  Vec3 tmp[BezierPatch::kMaxDegree + 1];
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

// The enclosures of a sub-patch that do not depend on the point (bezier_detail::Cell), from its
// net n, within err of the exact sub-patch's. Each computed difference is within its inputs'
// errors plus a rounding of the net's magnitude m.
BzCell bz_make_cell(const Vec3* n, int p, int q, double err, double m, double s0, double s1, double t0,
                    double t1) {
  BzCell c;
  c.s0 = s0;
  c.s1 = s1;
  c.t0 = t0;
  c.t1 = t1;
  c.err = err;
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

// The four halves-by-halves of net n (s, then t, at ½: exact halvings of sums) into out[0..3]
// (s low t low, s low t high, s high t low, s high t high), each of `stride` points.
void bz_quarters(const Vec3* n, int p, int q, Vec3* out) {
  const int stride = (p + 1) * (q + 1);
  Vec3 left[(BezierPatch::kMaxDegree + 1) * (BezierPatch::kMaxDegree + 1)];
  Vec3 right[(BezierPatch::kMaxDegree + 1) * (BezierPatch::kMaxDegree + 1)];
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
  std::vector<Vec3> pool;  // the nets of the cells below the patch's own
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
        cells_(scratch.cells),
        boxes_(scratch.boxes),
        open_(scratch.open),
        settled_(scratch.settled),
        f_cut_(cutoff < std::numeric_limits<double>::infinity() ? 0.5 * cutoff * cutoff * (1.0 + 0x1p-48)
                                                                : std::numeric_limits<double>::infinity()) {
    stride_ = (deg_[0] + 1) * (deg_[1] + 1);
    magnitude_ = patch.magnitude() + std::numeric_limits<double>::min();
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
      if (!accepted || !std::isfinite(nf)) break;
      step_norm = std::max(std::fabs(ns - s), std::fabs(nt - t));
      s = ns;
      t = nt;
      j = nj;
      f = nf;
      if (step_norm <= 1e-15) break;
    }
    // The answer by the Bernstein form: its rounding is what the enclosures below assume.
    j = patch_.jet(s, t);
    f = 0.5 * norm2(j.s - p_);
    if (!has_candidate_ || f < f_) {
      has_candidate_ = true;
      s_ = s;
      t_ = t;
      jet_ = j;
      f_ = f;
      step_norm_ = step_norm;
      const double d = norm(j.s - p_);
      const Vec3 foot = j.s;
      gap_ = std::fmax(Certificate::kRelativeGap * d, Certificate::absolute_gap_at(p_, foot));
      distance_ = d;
      // f and its gradient at the candidate, enclosed: the Bernstein sums' rounding is at most
      // (p + q + 2) roundings of the net's magnitude per term (the basis is nonnegative and sums to
      // 1; its derivatives' absolute values sum to at most 2p), taken 16 times over.
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
      cand_f_ = 0.5 * bz_norm2(r).lo;
      cand_gs_ = bz_dot(r, es);
      cand_gt_ = bz_dot(r, et);
      f_cert_ = 0.5 * std::pow(std::max(d - 0.5 * gap_, 0.0), 2);
      f_tie_ = 0.5 * (d + gap_) * (d + gap_);
    }
  }

  PatchNearest run(int max_boxes) {
    PatchNearest out;
    if (beyond_cutoff(out)) return out;
    // Newton from the parameters of the control point nearest p.
    int best = 0;
    for (int i = 1; i < stride_; ++i)
      if (norm2(patch_.net()[static_cast<std::size_t>(i)] - p_) <
          norm2(patch_.net()[static_cast<std::size_t>(best)] - p_))
        best = i;
    newton(static_cast<double>(best / (deg_[1] + 1)) / deg_[0],
           static_cast<double>(best % (deg_[1] + 1)) / deg_[1]);
    if (!std::isfinite(f_)) return out;

    pool_.clear();
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
      if (static_cast<int>(boxes_.size()) + 4 > max_boxes) return out;
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
        least = std::min(least, beyond_bound(cells[i]));
      out.boxes += static_cast<int>(count);
      if (least > f_cut_) {
        const int corners[4][2] = {{0, 0}, {deg_[0], 0}, {0, deg_[1]}, {deg_[0], deg_[1]}};
        int nearest = 0;
        double d2 = std::numeric_limits<double>::infinity();
        for (int c = 0; c < 4; ++c) {
          const double e = norm2(
              patch_.net()[static_cast<std::size_t>(corners[c][0] * (deg_[1] + 1) + corners[c][1])] - p_);
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
  // second-order form from its corner nearest p.
  double beyond_bound(const BzCell& c) const {
    BzVec r;
    const double lower = hull_bound(c, r);
    if (lower > f_cut_) return lower;
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
    const double bounds[4][4] = {{s0, sm, t0, tm}, {s0, sm, tm, t1}, {sm, s1, t0, tm}, {sm, s1, tm, t1}};
    for (int i = 0; i < 4; ++i) {
      const int offset = first + i * stride_;
      BzCell child = bz_make_cell(&pool_[static_cast<std::size_t>(offset)], deg_[0], deg_[1], err, magnitude_,
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
    const int index = static_cast<int>(boxes_.size()) - 1;
    (is_settled(box) ? settled_ : open_).push_back(index);
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

  void bound(BzBox& b, const BzCell& c) const {
    BzVec r;
    double lower = hull_bound(c, r);
    b.lower = lower;
    b.lambda = -std::numeric_limits<double>::infinity();
    b.fs = b.ft = {-std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
    b.fss = b.ftt = -std::numeric_limits<double>::infinity();
    if ((!b.contains(s_, t_) && b.lower > f_tie_) || b.lower > f_cut_) return;  // settled by the hull alone
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
    if (b.contains(s_, t_)) {
      // Taylor from the candidate x*, in the box's local parameters: δ in [lo, hi] about x*, the
      // gradient scaled by the box's widths. The gradient over the box in the centred form
      // ∇f(x*) + H δ bounds its sign far tighter than the hulls' product near x*.
      const double ws = b.s1 - b.s0, wt = b.t1 - b.t0;
      const double ls = std::min(bz_down((b.s0 - s_) / ws), 0.0), hs = std::max(bz_up((b.s1 - s_) / ws), 0.0);
      const double lt = std::min(bz_down((b.t0 - t_) / wt), 0.0), ht = std::max(bz_up((b.t1 - t_) / wt), 0.0);
      const BzInterval as = bz_scaled(cand_gs_, ws), at = bz_scaled(cand_gt_, wt);
      double least = 0.0;
      for (const int sign_s : {-1, 1})
        for (const int sign_t : {-1, 1}) {
          const double X = sign_s > 0 ? hs : -ls, Y = sign_t > 0 ? ht : -lt;
          // A quadrant of no width lies in its neighbour across that side.
          if (X > 0.0 && Y > 0.0)
            least = std::min(least, bz_quadrant(as, at, fss, fst, ftt, sign_s, sign_t, X, Y));
        }
      const double taylor = bz_down(cand_f_ + least);
      lower = std::max(lower, taylor);
      b.lower = std::isfinite(lower) ? lower : 0.0;
      const BzInterval ds{ls, hs}, dt{lt, ht};
      const BzInterval cs = add(as, add(mul(fss, ds), mul(fst, dt)));
      const BzInterval ct = add(at, add(mul(fst, ds), mul(ftt, dt)));
      b.fs = {std::max(b.fs.lo, cs.lo), std::min(b.fs.hi, cs.hi)};
      b.ft = {std::max(b.ft.lo, ct.lo), std::min(b.ft.hi, ct.hi)};
      return;
    }
    // Taylor from the corner nearest the candidate.
    const double taylor =
        corner_taylor(c, s_ - b.s0 > b.s1 - s_ ? 1 : 0, t_ - b.t0 > b.t1 - t_ ? 1 : 0, fss, fst, ftt);
    lower = std::max(lower, taylor);
    b.lower = std::isfinite(lower) ? lower : 0.0;
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

  std::vector<Vec3>& pool_;
  std::vector<BzCell>& cells_;
  std::vector<BzBox>& boxes_;
  std::vector<int>&open_, &settled_;
  double f_cut_;  // ½ cutoff², rounded up
};

}  // namespace

BezierPatch::BezierPatch(int p, int q, std::vector<Vec3> net) : p_(p), q_(q), net_(std::move(net)) {
  for (const Vec3& x : net_)
    magnitude_ = std::max({magnitude_, std::fabs(x.x), std::fabs(x.y), std::fabs(x.z)});
  // Σ_k b_k B_k^n(x) = Σ_j a_j x^j with a_j = binom(n, j) Σ_{k<=j} binom(j, k) (-1)^(j-k) b_k, along s
  // then t.
  auto binomial = [](int n, int k) {
    double b = 1.0;
    for (int i = 1; i <= k; ++i) b = b * (n - k + i) / i;
    return b;
  };
  auto index = [&](int k, int l) { return static_cast<std::size_t>(k * (q_ + 1) + l); };
  std::vector<Vec3> along_s(net_.size(), Vec3{0.0, 0.0, 0.0});
  for (int l = 0; l <= q_; ++l)
    for (int j = 0; j <= p_; ++j)
      for (int k = 0; k <= j; ++k)
        along_s[index(j, l)] +=
            (binomial(p_, j) * binomial(j, k) * ((j - k) % 2 ? -1.0 : 1.0)) * net_[index(k, l)];
  power_.assign(net_.size(), Vec3{0.0, 0.0, 0.0});
  for (int k = 0; k <= p_; ++k)
    for (int j = 0; j <= q_; ++j)
      for (int l = 0; l <= j; ++l)
        power_[index(k, j)] +=
            (binomial(q_, j) * binomial(j, l) * ((j - l) % 2 ? -1.0 : 1.0)) * along_s[index(k, l)];
  // The cells of the first kCellLevels levels of quarters, each with its net.
  const double m = magnitude_ + std::numeric_limits<double>::min();
  const auto stride = static_cast<std::size_t>((p_ + 1) * (q_ + 1));
  std::size_t cells = 1;
  for (int level = 0, width = 1; level < kCellLevels; ++level, width *= 4)
    cells += 4 * static_cast<std::size_t>(width);
  cells_.reserve(cells);
  cell_nets_.reserve(cells * stride);
  cell_nets_ = net_;
  cells_.push_back(bz_make_cell(net_.data(), p_, q_, 0.0, m, 0.0, 1.0, 0.0, 1.0));
  cells_.back().net = 0;
  std::size_t level_begin = 0;
  for (int level = 0; level < kCellLevels; ++level) {
    const std::size_t level_end = cells_.size();
    for (std::size_t i = level_begin; i < level_end; ++i) {
      const std::size_t first = cell_nets_.size();
      cell_nets_.resize(first + 4 * stride);
      const Vec3* parent = &cell_nets_[static_cast<std::size_t>(cells_[i].net)];
      Vec3 copy[(kMaxDegree + 1) * (kMaxDegree + 1)];
      std::copy(parent, parent + stride, copy);
      bz_quarters(copy, p_, q_, &cell_nets_[first]);
      const BzCell c = cells_[i];
      const double sm = 0.5 * (c.s0 + c.s1), tm = 0.5 * (c.t0 + c.t1);
      const double bounds[4][4] = {
          {c.s0, sm, c.t0, tm}, {c.s0, sm, tm, c.t1}, {sm, c.s1, c.t0, tm}, {sm, c.s1, tm, c.t1}};
      cells_[i].child = static_cast<int>(cells_.size());
      for (std::size_t k = 0; k < 4; ++k) {
        BzCell child =
            bz_make_cell(&cell_nets_[first + k * stride], p_, q_, c.err + bz_quarter_error(p_, q_, m), m,
                         bounds[k][0], bounds[k][1], bounds[k][2], bounds[k][3]);
        child.net = static_cast<int>(first + k * stride);
        cells_.push_back(child);
      }
    }
    level_begin = level_end;
  }
}

SurfaceJet BezierPatch::power_jet(double s, double t) const {
  // Horner in t per row k (the row's value, first and half second derivative), then in s.
  Vec3 v[kMaxDegree + 1], d1[kMaxDegree + 1], d2[kMaxDegree + 1];
  for (int k = 0; k <= p_; ++k) {
    const Vec3* a = &power_[static_cast<std::size_t>(k * (q_ + 1))];
    Vec3 x = a[q_], x1{0.0, 0.0, 0.0}, x2{0.0, 0.0, 0.0};
    for (int l = q_ - 1; l >= 0; --l) {
      x2 = x2 * t + x1;
      x1 = x1 * t + x;
      x = x * t + a[l];
    }
    v[k] = x;
    d1[k] = x1;
    d2[k] = 2.0 * x2;
  }
  SurfaceJet j{};
  Vec3 y = v[p_], y1{0.0, 0.0, 0.0}, y2{0.0, 0.0, 0.0}, z = d1[p_], z1{0.0, 0.0, 0.0}, w = d2[p_];
  for (int k = p_ - 1; k >= 0; --k) {
    y2 = y2 * s + y1;
    y1 = y1 * s + y;
    y = y * s + v[k];
    z1 = z1 * s + z;
    z = z * s + d1[k];
    w = w * s + d2[k];
  }
  j.s = y;
  j.su = y1;
  j.suu = 2.0 * y2;
  j.sv = z;
  j.suv = z1;
  j.svv = w;
  return j;
}

SurfaceJet BezierPatch::jet(double s, double t) const {
  double bs[3][kMaxDegree + 1], bt[3][kMaxDegree + 1];
  bz_basis(p_, s, bs[0], bs[1], bs[2]);
  bz_basis(q_, t, bt[0], bt[1], bt[2]);
  SurfaceJet j{};
  for (int k = 0; k <= p_; ++k) {
    // The row's sums along t: value, d/dt, d²/dt².
    Vec3 r0{}, r1{}, r2{};
    for (int l = 0; l <= q_; ++l) {
      const Vec3& b = net_[static_cast<std::size_t>(k * (q_ + 1) + l)];
      r0 += bt[0][l] * b;
      r1 += bt[1][l] * b;
      r2 += bt[2][l] * b;
    }
    j.s += bs[0][k] * r0;
    j.su += bs[1][k] * r0;
    j.suu += bs[2][k] * r0;
    j.sv += bs[0][k] * r1;
    j.suv += bs[1][k] * r1;
    j.svv += bs[0][k] * r2;
  }
  return j;
}

PatchNearest nearest_on_patch(const BezierPatch& patch, const Vec3& p, int max_boxes, double cutoff) {
  thread_local BzScratch scratch;
  BzSearch search(patch, p, scratch, cutoff);
  return search.run(max_boxes);
}

}  // namespace footpoint
