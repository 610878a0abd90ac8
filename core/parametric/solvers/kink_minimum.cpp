#include "parametric/solvers/kink_minimum.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "formula/ball.hpp"
#include "parametric/geometry/params.hpp"

namespace footpoint {

namespace {

// Bisects [a, b] (a < b), across which a slope changes sign, down to adjacent doubles, at most
// `steps` halvings: `at(x, point)` evaluates the point at x (false where it is not finite: the
// bisection fails), `left(point)` says whether it takes a's place (its slope has a's sign) or b's.
template <class Point, class At, class Left>
bool bisect_slope_sign(double& a, double& b, Point& pa, Point& pb, int steps, At&& at, Left&& left) {
  for (int i = 0; i < steps; ++i) {
    const double m = 0.5 * (a + b);
    if (!(m > a && m < b)) break;
    Point pm;
    if (!at(m, pm)) return false;
    if (left(pm))
      a = m, pa = pm;
    else
      b = m, pb = pm;
  }
  return true;
}

}  // namespace

}  // namespace footpoint

namespace footpoint::curve {

namespace {

using formula::ball::kU;  // the unit roundoff

struct Slope {
  double g = 0.0;     // φ'(t)
  double dg = 0.0;    // |φ''(t)|
  double size = 0.0;  // |c'| |c - p|: the scale of φ'(t)'s rounding
  double phi = 0.0;   // φ(t)
};

Slope slope_at(const CurveFormulas& formulas, Vec3 p, double t) {
  const CurveJet j = formulas.jet(t);
  const Vec3 d = j.c - p;
  return {dot(d, j.d1), std::abs(dot(j.d1, j.d1) + dot(d, j.d2)), norm(j.d1) * norm(d), 0.5 * dot(d, d)};
}

}  // namespace

bool kink_minimum(const CurveFormulas& formulas, Vec3 p, double scale, double& t) {
  const double h = 16.0 * kU * std::max(std::abs(t), scale);
  double a = t - h, b = t + h;
  Slope sa = slope_at(formulas, p, a), sb = slope_at(formulas, p, b);
  const auto kink = [](const Slope& l, const Slope& r, double width) {
    const double smooth = 1e3 * width * std::max(l.dg, r.dg) + 64.0 * kU * std::max(l.size, r.size);
    return l.g <= 0.0 && r.g >= 0.0 && r.g - l.g > smooth;
  };
  if (!std::isfinite(sa.g) || !std::isfinite(sb.g) || !kink(sa, sb, b - a)) return false;
  // φ' keeps its signs on each side of the kink: bisect on them to adjacent doubles
  const auto at = [&](double x, Slope& s) {
    s = slope_at(formulas, p, x);
    return std::isfinite(s.g);
  };
  if (!bisect_slope_sign(a, b, sa, sb, 64, at, [](const Slope& s) { return s.g <= 0.0; })) return false;
  t = sa.phi <= sb.phi ? a : b;
  return true;
}

}  // namespace footpoint::curve

namespace footpoint::surface {

namespace {

Params<2> along(const Params<2>& t, double mu, const Params<2>& d) {
  return {t[0] + mu * d[0], t[1] + mu * d[1]};
}
double dot2(const Params<2>& a, const Params<2>& b) { return a[0] * b[0] + a[1] * b[1]; }
double norm2d(const Params<2>& a) { return std::hypot(a[0], a[1]); }

// f, its gradient and Hessian at t (the piece of the formulas that t lies on).
struct Local {
  Params<2> t;
  SurfaceJet jet;
  double f = 0.0;
  Params<2> g{};
  double h[3]{};  // H_uu, H_uv, H_vv
  double h_norm = 0.0;
  bool finite = false;
};

Local local_at(const SurfaceFormulas& formulas, const Vec3& p, const Params<2>& t) {
  Local l;
  l.t = t;
  l.jet = formulas.jet(t[0], t[1]);
  const Vec3 r = l.jet.s - p;
  l.f = 0.5 * dot(r, r);
  l.g = {dot(r, l.jet.su), dot(r, l.jet.sv)};
  l.h[0] = dot(l.jet.su, l.jet.su) + dot(r, l.jet.suu);
  l.h[1] = dot(l.jet.su, l.jet.sv) + dot(r, l.jet.suv);
  l.h[2] = dot(l.jet.sv, l.jet.sv) + dot(r, l.jet.svv);
  l.h_norm = std::abs(l.h[0]) + std::abs(l.h[1]) + std::abs(l.h[2]);
  l.finite = std::isfinite(l.f) && std::isfinite(l.g[0]) && std::isfinite(l.g[1]) && std::isfinite(l.h_norm);
  return l;
}

// A bracket of K: adjacent doubles a, b on the line t + μ d (a first) between which the
// gradient jumps.
struct Bracket {
  Local a, b;
};

// The slope of f along d at a point, and its rate of change there (<d, H d>).
double slope(const Local& l, const Params<2>& d) { return dot2(l.g, d); }
double bend(const Local& l, const Params<2>& d) {
  return l.h[0] * d[0] * d[0] + 2.0 * l.h[1] * d[0] * d[1] + l.h[2] * d[1] * d[1];
}

// How far the slope's change over [a, b] is from what a smooth f gives (the trapezoidal rule of its
// rate): O(|b - a|^3) where f is smooth, the jump's size across a kink.
double mismatch(const Local& a, const Local& b, const Params<2>& d, double width) {
  return std::abs(slope(b, d) - slope(a, d) - 0.5 * (bend(a, d) + bend(b, d)) * width);
}

// Bisects t + μ d, μ in [lo, hi], towards the half whose slope change a smooth f explains least,
// down to adjacent doubles.
bool bracket_along(const SurfaceFormulas& formulas, const Vec3& p, const Params<2>& t, const Params<2>& d,
                   double lo, double hi, Bracket& out) {
  Local a = local_at(formulas, p, along(t, lo, d)), b = local_at(formulas, p, along(t, hi, d));
  if (!a.finite || !b.finite) return false;
  for (int i = 0; i < 160; ++i) {
    const double mid = 0.5 * (lo + hi);
    const Params<2> m = along(t, mid, d);
    if (m == a.t || m == b.t) break;
    const Local l = local_at(formulas, p, m);
    if (!l.finite) return false;
    if (mismatch(a, l, d, mid - lo) >= mismatch(l, b, d, hi - mid)) {
      hi = mid, b = l;
    } else {
      lo = mid, a = l;
    }
  }
  out = {a, b};
  return true;
}

bool inside(const ParamBox& box, const Params<2>& t, double margin) {
  return t[0] > box.umin + margin && t[0] < box.umax - margin && t[1] > box.vmin + margin &&
         t[1] < box.vmax - margin;
}

// The gradient jumps across the bracket by more than a smooth f allows.
bool jumps(const Bracket& k) {
  const Params<2> jump{k.b.g[0] - k.a.g[0], k.b.g[1] - k.a.g[1]};
  const double width = norm2d({k.b.t[0] - k.a.t[0], k.b.t[1] - k.a.t[1]});
  const double size = std::max(norm2d(k.a.g), norm2d(k.b.g));
  return norm2d(jump) > 1e3 * width * std::max(k.a.h_norm, k.b.h_norm) + 1e-12 * size;
}

// No direction of the fan at angles [first, first + width] (65 of them) descends from `best`: the
// one-sided derivative f'(t; r) is read as <g(t + h r), r>, the gradient of the piece r points into
// a step h = 1e-7 of the box's size along r (clamped to the box), off by at most |H| h, which the
// tolerance allows with the rounding of the orthogonality.
bool rises_across_fan(const SurfaceFormulas& formulas, const ParamBox& box, const Vec3& p, const Local& best,
                      double scale, double first, double width) {
  const double h = 1e-7 * scale;
  const Vec3 r = best.jet.s - p;
  constexpr int kFan = 64;
  for (int i = 0; i <= kFan; ++i) {
    const double angle = first + width * i / kFan;
    const Params<2> dir{std::cos(angle), std::sin(angle)};
    Params<2> q = along(best.t, h, dir);
    q = {std::clamp(q[0], box.umin, box.umax), std::clamp(q[1], box.vmin, box.vmax)};
    const Local l = local_at(formulas, p, q);
    if (!l.finite) return false;
    const Vec3 s_dir = l.jet.su * dir[0] + l.jet.sv * dir[1];
    const double tolerance = 2.0 * l.h_norm * h + 1e-12 * norm(r) * norm(s_dir);
    if (dot2(l.g, dir) < -tolerance) return false;
  }
  return true;
}

// The solve's answer becomes the kink point `best` (converged).
void adopt(const Local& best, LocalSolution& s) {
  s.u = best.t[0];
  s.v = best.t[1];
  s.jet = best.jet;
  s.distance = std::sqrt(2.0 * best.f);
  s.status = Status::converged;
  s.abandoned = false;
  s.kink = true;
}

// Where K meets the box's boundary: t0 on an edge or at a corner (within `margin`). The point is
// the corner itself, or on an edge the minimum of f along the edge, bracketed where the slope along
// the edge changes sign and bisected to adjacent doubles. It is stationary when no feasible
// direction r (into the box) descends: the one-sided derivative f'(t; r) >= 0. f' is linear in r
// on each side of K, and the feasible cone (a half-plane, a quadrant) is at most two cones on
// which it is linear, so a fan of directions across the feasible cone tells; f'(t; r) is read as
// <g(t + h r), r>, the gradient of the piece r points into, off by at most |H| h.
bool boundary_kink_minimum(const SurfaceFormulas& formulas, const ParamBox& box, const Vec3& p, double scale,
                           double margin, LocalSolution& s) {
  Params<2> t{s.u, s.v};
  bool u_lo = std::abs(t[0] - box.umin) <= margin, u_hi = std::abs(t[0] - box.umax) <= margin;
  bool v_lo = std::abs(t[1] - box.vmin) <= margin, v_hi = std::abs(t[1] - box.vmax) <= margin;
  bool at_u = u_lo || u_hi, at_v = v_lo || v_hi;
  if (!at_u && !at_v) return false;
  if (at_u) t[0] = u_lo ? box.umin : box.umax;
  if (at_v) t[1] = v_lo ? box.vmin : box.vmax;
  Local best = local_at(formulas, p, t);
  if (!best.finite) return false;
  if (at_u != at_v) {  // along the edge: direction k of the parameters, between lo and hi
    const std::size_t k = at_u ? 1 : 0;
    const double lo = k == 0 ? box.umin : box.vmin, hi = k == 0 ? box.umax : box.vmax;
    const auto point = [&](double x) {
      Params<2> q = t;
      q[k] = x;
      return local_at(formulas, p, q);
    };
    const double x0 = t[k];
    // the slope along the edge just inside its ends: f falls towards a corner there
    const Local near_lo = point(lo + margin), near_hi = point(hi - margin);
    double h = margin;
    Local a = best, b = best;
    bool bracketed = false, corner = false;
    for (int grow = 0; grow < 64 && !bracketed && !corner; ++grow, h *= 2.0) {
      a = point(std::max(lo, x0 - h));
      b = point(std::min(hi, x0 + h));
      if (!a.finite || !b.finite) return false;
      bracketed = a.g[k] < 0.0 && b.g[k] > 0.0;
      if (bracketed) break;
      // the edge's least value at its end: the corner
      if (b.t[k] == hi && near_hi.g[k] < 0.0) {
        corner = true, t[k] = hi;
      } else if (a.t[k] == lo && near_lo.g[k] > 0.0) {
        corner = true, t[k] = lo;
      }
    }
    if (corner) {
      at_u = at_v = true;
      (k == 0 ? u_lo : v_lo) = t[k] == lo;
      (k == 0 ? u_hi : v_hi) = t[k] == hi;
      best = local_at(formulas, p, t);
      if (!best.finite) return false;
    } else {
      if (!bracketed) return false;
      // as a curve's kink (the edge is one): bisection on the sign of the slope along the edge
      double xa = a.t[k], xb = b.t[k];
      const auto at = [&](double x, Local& l) {
        l = point(x);
        return l.finite;
      };
      if (!bisect_slope_sign(xa, xb, a, b, 160, at, [&](const Local& l) { return l.g[k] < 0.0; }))
        return false;
      best = a.f <= b.f ? a : b;
    }
  }
  // the feasible cone: directions at angles [first, first + width]
  double first = 0.0, width = 0.0;
  if (at_u && at_v) {
    first =
        u_lo ? (v_lo ? 0.0 : -0.5 * std::numbers::pi) : (v_lo ? 0.5 * std::numbers::pi : std::numbers::pi);
    width = 0.5 * std::numbers::pi;
  } else if (at_u) {
    first = u_lo ? -0.5 * std::numbers::pi : 0.5 * std::numbers::pi;
    width = std::numbers::pi;
  } else {
    first = v_lo ? 0.0 : std::numbers::pi;
    width = std::numbers::pi;
  }
  if (!rises_across_fan(formulas, box, p, best, scale, first, width)) return false;
  if (!(best.f <= 0.5 * s.distance * s.distance)) return false;
  adopt(best, s);
  return true;
}

// A kink point inside the box: where kink curves cross (z = |u| + |v| at (0, 0)) or where the
// formulas are not differentiable at a point alone (z = sqrt(u^2 + v^2) at its tip). Compass search
// (T. G. Kolda, R. M. Lewis, V. Torczon, Optimization by direct search: new perspectives on some
// classical and modern methods, SIAM Review 45(3), 385-482, 2003, Section 1.1) from `start` closes
// in on it, as it needs no gradient: ±`along_k` (the tangent of a kink curve
// whose crossing is sought: its valley is too narrow for fixed directions) and eight directions
// turned by an irrational angle at every level, steps halved from `first_step` down to rounding.
// Where it ends within `margin` of the box's boundary, the boundary's test decides. Else the point
// is accepted when no direction descends: f'(t; r) >= 0 for every r (Clarke's condition,
// Section 2.3 of the book the header cites), read from a fan of directions all around it as on the boundary;
// f' is linear on each of the finitely many sectors between kinks.
bool point_kink_minimum(const SurfaceFormulas& formulas, const ParamBox& box, const Vec3& p, double scale,
                        double margin, const Local& start, const Params<2>& along_k, double first_step,
                        LocalSolution& s) {
  Local best = start;
  double angle0 = 0.0;
  int evaluations = 0;
  for (double step = first_step; step > 1e-17 * scale && evaluations < 4000;) {
    bool moved = false;
    for (int i = 0; i < 10 && !moved; ++i) {
      const double angle = angle0 + 0.25 * std::numbers::pi * (i - 2);
      const Params<2> dir = i == 0 ? along_k
                                   : (i == 1 ? Params<2>{-along_k[0], -along_k[1]}
                                             : Params<2>{std::cos(angle), std::sin(angle)});
      if (!(norm2d(dir) > 0.0)) continue;
      const Params<2> q = along(best.t, step, dir);
      if (!inside(box, q, 0.0)) continue;
      const Local l = local_at(formulas, p, q);
      ++evaluations;
      if (l.finite && l.f < best.f) best = l, moved = true;
    }
    if (!moved) step *= 0.5, angle0 += 0.6180339887498949;  // the golden ratio's fraction, in radians
  }
  if (!(best.f <= 0.5 * s.distance * s.distance)) return false;
  if (!inside(box, best.t, margin)) {
    LocalSolution at = s;
    at.u = best.t[0];
    at.v = best.t[1];
    if (!boundary_kink_minimum(formulas, box, p, scale, margin, at)) return false;
    s = at;
    return true;
  }
  if (!rises_across_fan(formulas, box, p, best, scale, 0.0, 2.0 * std::numbers::pi)) return false;
  adopt(best, s);
  return true;
}

// Steps 1-3 of the header: a minimum on a kink curve K, from the unconverged iterate t0.
bool kink_curve_minimum(const SurfaceFormulas& formulas, const ParamBox& box, const Vec3& p, double scale,
                        double margin, LocalSolution& s) {
  const Params<2> t0{s.u, s.v};
  const Local l0 = local_at(formulas, p, t0);
  if (!l0.finite) return false;
  // 1. across K along the piece's Newton step (its gradient where the Hessian is not definite)
  const double det = l0.h[0] * l0.h[2] - l0.h[1] * l0.h[1];
  Params<2> d = det > 0.0 && l0.h[0] > 0.0 ? Params<2>{-(l0.h[2] * l0.g[0] - l0.h[1] * l0.g[1]) / det,
                                                       -(l0.h[0] * l0.g[1] - l0.h[1] * l0.g[0]) / det}
                                           : Params<2>{-l0.g[0], -l0.g[1]};
  const double dn = norm2d(d);
  if (!(dn > 0.0) || !std::isfinite(dn)) return false;
  d = {d[0] / dn, d[1] / dn};
  // the Newton step of t0's piece crosses K (else the solve would have converged on the piece)
  Bracket k;
  if (!bracket_along(formulas, p, t0, d, 0.0, dn, k) || !jumps(k)) return false;
  // 2. along K
  double f = std::min(k.a.f, k.b.f);
  // the previous point on K and its derivative along K, for the secant of that derivative
  Params<2> last{};
  double last_D = 0.0;
  for (int step = 0; step < 32; ++step) {
    Params<2> n{k.b.g[0] - k.a.g[0], k.b.g[1] - k.a.g[1]};
    const double jn = norm2d(n);
    n = {n[0] / jn, n[1] / jn};
    const Params<2> tau{-n[1], n[0]};
    const Params<2> g{0.5 * (k.a.g[0] + k.b.g[0]), 0.5 * (k.a.g[1] + k.b.g[1])};
    const double D = dot2(g, tau);
    const Vec3 s_tau = k.a.jet.su * tau[0] + k.a.jet.sv * tau[1];
    if (std::abs(D) <= 1e-12 * std::sqrt(2.0 * f) * norm(s_tau)) {
      // 3. Clarke stationarity: f falls towards K from both sides
      if (!(dot2(k.a.g, n) <= 0.0 && dot2(k.b.g, n) >= 0.0)) return false;
      const Local& best = k.a.f <= k.b.f ? k.a : k.b;
      if (!inside(box, best.t, margin) || !(best.f <= l0.f)) return false;
      adopt(best, s);
      s.iterations += step + 1;
      return true;
    }
    const double curvature =
        0.5 * (k.a.h[0] * tau[0] * tau[0] + 2.0 * k.a.h[1] * tau[0] * tau[1] + k.a.h[2] * tau[1] * tau[1] +
               k.b.h[0] * tau[0] * tau[0] + 2.0 * k.b.h[1] * tau[0] * tau[1] + k.b.h[2] * tau[1] * tau[1]);
    // f along K bends by <τ, H τ> plus K's own curvature times the normal slope, which H does
    // not see: after the first step the secant of D along K measures the two together
    const Params<2> mid{0.5 * (k.a.t[0] + k.b.t[0]), 0.5 * (k.a.t[1] + k.b.t[1])};
    const double moved_along = dot2({mid[0] - last[0], mid[1] - last[1]}, tau);
    const double secant = step > 0 && moved_along != 0.0 ? (D - last_D) / moved_along : 0.0;
    const double rate = secant > 0.0 && std::isfinite(secant) ? secant : curvature;
    double sigma = rate > 0.0 ? -D / rate : -D;
    last = mid;
    last_D = D;
    bool moved = false;
    for (int halve = 0; halve < 30 && !moved; ++halve, sigma *= 0.5) {
      const Params<2> q = along(mid, sigma, tau);
      if (!inside(box, q, margin)) continue;
      // back onto K across it: K bends away from its tangent by O(σ^2)
      const double w = std::abs(sigma) + 1e-9 * scale;
      Bracket next;
      if (!bracket_along(formulas, p, q, n, -w, w, next) || !jumps(next)) continue;
      const double fn = std::min(next.a.f, next.b.f);
      if (!(fn <= f)) continue;
      k = next;
      f = fn;
      moved = true;
    }
    if (!moved) break;
  }
  // No stationary point found along K by Newton: K may run into a crossing of another kink (D
  // jumps there, and the secant steps across it back and forth) or into the boundary, where the
  // search along K's tangent takes over from the best point found on K.
  const Local& here = k.a.f <= k.b.f ? k.a : k.b;
  Params<2> n{k.b.g[0] - k.a.g[0], k.b.g[1] - k.a.g[1]};
  const double jn = norm2d(n);
  if (!(jn > 0.0)) return false;
  return point_kink_minimum(formulas, box, p, scale, margin, here, {-n[1] / jn, n[0] / jn}, 1e-4 * scale, s);
}

}  // namespace

bool kink_minimum(const SurfaceFormulas& formulas, const ParamBox& box, const Vec3& p, LocalSolution& s) {
  if (!std::isfinite(s.u) || !std::isfinite(s.v)) return false;
  const double scale = std::max({box.umax - box.umin, box.vmax - box.vmin, std::abs(s.u), std::abs(s.v)});
  const double margin = 1e-9 * scale;
  if (!inside(box, {s.u, s.v}, margin)) return boundary_kink_minimum(formulas, box, p, scale, margin, s);
  const Local start = local_at(formulas, p, {s.u, s.v});
  if (!start.finite) return false;
  return kink_curve_minimum(formulas, box, p, scale, margin, s) ||
         point_kink_minimum(formulas, box, p, scale, margin, start, {0.0, 0.0}, 1e-4 * scale, s);
}

}  // namespace footpoint::surface
