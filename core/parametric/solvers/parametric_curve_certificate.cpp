#include "parametric/solvers/parametric_curve_certificate.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <queue>

#include "formula/ball.hpp"
#include "parametric/geometry/distance_bound.hpp"
#include "solvers/certificate_ledger.hpp"

namespace footpoint::curve {

namespace {

using formula::ball::kU;  // the unit roundoff
constexpr double kNoPoint = std::numeric_limits<double>::infinity();

struct OpenInterval {
  double t0 = 0.0, t1 = 0.0;
  std::int32_t cell = -1;  // the compiled cell, or -1 (a sub-interval)
  double lb = 0.0;         // the best lower bound of the distance over it so far
  HessianBounds<1> hessian;
  bool bounded = true;  // the formulas are finite and smooth over it
  bool finite = true;   // the formulas are finite over it (else: non_finite)
  bool solved = false;
  bool nearer = false;  // a point of it is nearer than the answer by more than the gap
};

struct ByBound {
  bool operator()(const OpenInterval& a, const OpenInterval& b) const { return a.lb > b.lb; }
};

struct Known {
  explicit Known(double at) : t(at) {}
  double t;
  bool enclosed = false;
  GradientEnclosure<1> at;
};

class Certifier {
 public:
  Certifier(const ParametricCurveCells& cells, const CurveFormulas& formulas, Vec3 p, CurveMinimum answer,
            const std::vector<double>& known, const CurveLocalSolve& solve, bool may_improve,
            const CurveCertifyOptions& options)
      : cells_(cells),
        formulas_(formulas),
        p_(p),
        solve_(solve),
        may_improve_(may_improve),
        options_(options),
        best_(answer),
        ledger_(answer.distance, Certificate::absolute_gap_at(p, formulas.point(answer.t))) {
    known_.emplace_back(answer.t);
    measure(known_.front());
    for (double t : known)
      if (t != answer.t) known_.emplace_back(t);
  }

  CurveCertification run() {
    walk();
    while (!open_.empty() && !ledger_.refuted()) {
      const OpenInterval b = open_.top();
      open_.pop();
      examine(b);
    }
    while (!open_.empty()) {
      note_unclosed(open_.top());
      open_.pop();
    }
    CurveCertification out;
    out.improved = improved_;
    out.better = best_;
    out.certificate = ledger_.finish(runtime_boxes_);
    return out;
  }

 private:
  void close(double lb) { ledger_.close(lb); }
  void note_unclosed(const OpenInterval& b) { ledger_.leave_open(b.lb, b.finite); }

  // The distance to the box of c over an interval: over the points where c is finite (the curve
  // is the part of the domain where the formulas are finite); none where no point is in the
  // formulas' domain (+inf), 0 where the enclosure is not finite.
  double zero_order(const BoxEnclosure<1>& e) const {
    if (e.empty) return kNoPoint;
    return e.bounded || e.finite_part ? std::sqrt(box_distance2_lower(e.s_mid, e.s_rad, p_)) : 0.0;
  }

  // An interval whose formulas are finite but not smooth over it: where the switch of a select
  // crosses it, the bound of its branches (branch_lower_bound).
  void bound_branches(OpenInterval& o) {
    if (o.bounded || !o.finite) return;
    std::vector<Params<1>> near_t;
    for (const Known& k : known_)
      if (near(k, o)) near_t.push_back({k.t});
    o.lb = std::max(o.lb,
                    branch_lower_bound<1>(formulas_.program(), p_, {o.t0}, {o.t1}, near_t, ledger_.target()));
  }

  // 1. nearest box first; a subtree whose box is beyond the target is closed whole
  void walk() {
    const auto& nodes = cells_.nodes();
    if (nodes.empty()) {
      visit_cell(0);
      return;
    }
    const double target = ledger_.target(), target2 = target > 0.0 ? target * target : 0.0;
    std::vector<std::int32_t> stack{0};
    while (!stack.empty()) {
      const ParametricCurveCellNode& n = nodes[static_cast<std::size_t>(stack.back())];
      stack.pop_back();
      if (target > 0.0 && box_distance2(n.lo, n.hi) * (1.0 - 16.0 * kU) >= target2) {
        ledger_.skip();
        continue;
      }
      for (std::int32_t child : n.child) {
        if (child >= 0)
          stack.push_back(child);
        else
          visit_cell(~child);
      }
    }
  }

  double box_distance2(const Vec3& lo, const Vec3& hi) const {
    double d2 = 0.0;
    for (int k = 0; k < 3; ++k) {
      const double d = std::max({lo[k] - p_[k], 0.0, p_[k] - hi[k]});
      d2 += d * d;
    }
    return std::isnan(d2) ? 0.0 : d2;
  }

  // 2.-4. for a compiled cell
  void visit_cell(std::int32_t index) {
    const ParametricCurveCell& c = cells_.cells()[static_cast<std::size_t>(index)];
    OpenInterval o;
    o.t0 = c.t0;
    o.t1 = c.t1;
    o.cell = index;
    const BoxEnclosure<1>& e = c.enclosure;
    o.bounded = e.bounded && e.smooth && c.centre_valid;
    o.finite = e.bounded;
    o.lb = zero_order(e);
    if (o.lb >= ledger_.target()) return close(o.lb);
    bound_branches(o);
    if (o.lb >= ledger_.target()) return close(o.lb);
    if (c.centre_valid && std::isfinite(c.rho)) {  // 2. the tangent line's segment
      const Vec3 r = p_ - c.centre.c;
      const double speed2 = norm2(c.centre.d1), h = 0.5 * (c.t1 - c.t0);
      const double delta = speed2 > 0.0 ? std::clamp(dot(r, c.centre.d1) / speed2, -h, h) : 0.0;
      const double segment = norm(c.centre.c + c.centre.d1 * delta - p_);
      o.lb = std::max(o.lb, segment - c.rho - kBoundRounding * (norm(r) + norm(c.centre.d1) * h + c.rho));
      if (o.lb >= ledger_.target()) return close(o.lb);
    }
    if (o.bounded) {  // 3. second order from the centre
      o.hessian = hessian_bounds(e, p_);
      PointEnclosure<1> centre;
      centre.s = c.centre.c;
      centre.s_rad = c.c_rad;
      centre.ds = {c.centre.d1};
      centre.ds_rad = {c.d1_rad};
      centre.valid = true;
      const double f = second_order_lower_bound(enclose_gradient(centre, p_), {c.tc()}, {c.t0}, {c.t1},
                                                o.hessian, ledger_.target_f());
      o.lb = std::max(o.lb, distance_from_f_lower(f));
      if (o.lb >= ledger_.target()) return close(o.lb);
    }
    open_.push(o);
  }

  static bool near(const Known& k, const OpenInterval& b) {
    const double w = b.t1 - b.t0;
    return k.t >= b.t0 - w && k.t <= b.t1 + w;
  }

  // 4. from the known minimisers near the interval
  bool close_from_known(OpenInterval& b) {
    if (!b.bounded || !b.hessian.valid) return false;
    for (Known& k : known_) {
      if (!near(k, b)) continue;
      const double q = std::clamp(k.t, b.t0, b.t1);
      GradientEnclosure<1> at;
      if (q == k.t) {
        if (!k.enclosed) {
          const PointEnclosure<1> e = enclose_point<1>(formulas_.program(), {k.t});
          if (!e.valid) continue;
          k.at = enclose_gradient(e, p_);
          k.enclosed = true;
        }
        at = k.at;
      } else {
        const PointEnclosure<1> e = enclose_point<1>(formulas_.program(), {q});
        if (!e.valid) continue;
        at = enclose_gradient(e, p_);
      }
      b.lb = std::max(b.lb, distance_from_f_lower(second_order_lower_bound(at, {q}, {b.t0}, {b.t1}, b.hessian,
                                                                           ledger_.target_f())));
      if (b.lb >= ledger_.target()) return true;
    }
    return false;
  }

  void solve_from(OpenInterval& b) {
    b.solved = true;
    if (solves_ >= options_.max_solves) return;
    ++solves_;
    const double start =
        b.cell >= 0 ? model_minimiser(cells_.cells()[static_cast<std::size_t>(b.cell)]) : 0.5 * (b.t0 + b.t1);
    const CurveMinimum s = solve_(start);
    if (!std::isfinite(s.distance)) return;
    known_.emplace_back(s.t);
    if (!(s.distance < best_.distance)) return;
    if (!may_improve_) {
      if (s.distance < best_.distance - ledger_.gap()) ledger_.refute();
      return;
    }
    best_ = s;
    improved_ = true;
    ledger_.retarget(s.distance, Certificate::absolute_gap_at(p_, formulas_.point(s.t)));
    measure(known_.back());
  }

  // The answer's distance measured from its parameters' point, enclosed (CertificateLedger::
  // measure_from); the enclosure is kept for the bounds from it.
  void measure(Known& k) {
    const PointEnclosure<1> e = enclose_point<1>(formulas_.program(), {k.t});
    if (!e.valid) return;
    ledger_.measure_from(e.s, e.s_rad, p_);
    k.at = enclose_gradient(e, p_);
    k.enclosed = true;
  }

  // The minimiser over the cell of the Newton model of f at its centre.
  double model_minimiser(const ParametricCurveCell& c) const {
    const Vec3 r = c.centre.c - p_;
    const double g = dot(r, c.centre.d1), h = norm2(c.centre.d1) + dot(r, c.centre.d2);
    const double t = h > 0.0 ? c.tc() - g / h : (g > 0.0 ? c.t0 : c.t1);
    return std::isfinite(t) ? std::clamp(t, c.t0, c.t1) : c.tc();
  }

  void examine(OpenInterval b) {
    if (b.lb >= ledger_.target()) return close(b.lb);
    if (close_from_known(b)) return close(b.lb);
    const bool known_near =
        std::any_of(known_.begin(), known_.end(), [&](const Known& k) { return near(k, b); });
    if (!b.solved && (b.nearer || !known_near)) {
      solve_from(b);
      if (ledger_.refuted()) return note_unclosed(b);
      if (b.lb >= ledger_.target() || close_from_known(b)) return close(b.lb);
    }
    if (runtime_boxes_ + 2 > options_.max_boxes) return note_unclosed(b);
    const double mid = 0.5 * (b.t0 + b.t1);
    if (!(mid > b.t0 && mid < b.t1)) return note_unclosed(b);
    for (const auto& [a, z] : {std::pair{b.t0, mid}, std::pair{mid, b.t1}}) {
      OpenInterval child = bound_sub_interval(a, z);
      if (ledger_.refuted()) return note_unclosed(child);
      if (child.lb >= ledger_.target())
        close(child.lb);
      else
        open_.push(child);
    }
  }

  // 1, 3 for a sub-interval, with an interval jet of its own and a ball jet at its centre
  OpenInterval bound_sub_interval(double t0, double t1) {
    ++runtime_boxes_;
    OpenInterval b;
    b.t0 = t0;
    b.t1 = t1;
    const BoxEnclosure<1> e = enclose_box<1>(formulas_.program(), {t0}, {t1});
    const double tc = 0.5 * (t0 + t1);
    const PointEnclosure<1> at = enclose_point<1>(formulas_.program(), {tc});
    b.bounded = e.bounded && e.smooth && at.valid;
    b.finite = e.bounded;
    b.lb = zero_order(e);
    if (b.lb >= ledger_.target()) return b;
    bound_branches(b);
    if (!b.bounded) return b;
    b.hessian = hessian_bounds(e, p_);
    b.lb = std::max(b.lb, distance_from_f_lower(second_order_lower_bound(
                              enclose_gradient(at, p_), {tc}, {t0}, {t1}, b.hessian, ledger_.target_f())));
    if (ledger_.nearer_than_answer(at.s, at.s_rad, p_)) {
      b.nearer = true;
      if (!may_improve_) ledger_.refute();
    }
    return b;
  }

  const ParametricCurveCells& cells_;
  const CurveFormulas& formulas_;
  const Vec3 p_;
  const CurveLocalSolve& solve_;
  const bool may_improve_;
  const CurveCertifyOptions& options_;
  CurveMinimum best_;
  CertificateLedger ledger_;
  bool improved_ = false;
  int runtime_boxes_ = 0, solves_ = 0;
  std::vector<Known> known_;
  std::priority_queue<OpenInterval, std::vector<OpenInterval>, ByBound> open_;
};

}  // namespace

CurveCertification certify_parametric_curve(const ParametricCurveCells& cells, const CurveFormulas& formulas,
                                            Vec3 p, CurveMinimum answer, const std::vector<double>& known,
                                            const CurveLocalSolve& solve, bool may_improve,
                                            const CurveCertifyOptions& options) {
  return Certifier(cells, formulas, p, answer, known, solve, may_improve, options).run();
}

Certificate certify_curve_answer(const ParametricCurveCells& cells, const CurveFormulas& formulas,
                                 const ParamInterval& domain, Vec3 p, double t) {
  const CurveLocalSolve solve = [&](double t0) { return descend_on_interval(formulas, domain, p, t0); };
  return certify_parametric_curve(cells, formulas, p, {t, norm(formulas.point(t) - p)}, {}, solve, false)
      .certificate;
}

CurveMinimum descend_on_interval(const CurveFormulas& formulas, const ParamInterval& domain, Vec3 p,
                                 double t0) {
  auto f = [&](double t) { return 0.5 * norm2(formulas.point(t) - p); };
  double t = std::clamp(t0, domain.tmin, domain.tmax), ft = f(t);
  const double width = domain.tmax - domain.tmin;
  for (int it = 0; it < 100; ++it) {
    const CurveJet j = formulas.jet(t);
    const Vec3 r = j.c - p;
    const double g = dot(r, j.d1), h = norm2(j.d1) + dot(r, j.d2);
    if (!std::isfinite(g) || g == 0.0) break;
    // Newton where f is convex, else a step of a hundredth of the domain downhill
    double step = h > 0.0 ? -g / h : (g > 0.0 ? -0.01 * width : 0.01 * width);
    double next = std::clamp(t + step, domain.tmin, domain.tmax), fn = f(next);
    for (int halve = 0; halve < 60 && !(fn < ft); ++halve) {
      step *= 0.5;
      next = std::clamp(t + step, domain.tmin, domain.tmax);
      fn = f(next);
    }
    if (!(fn < ft)) break;  // no descent left: a minimum to rounding (or an end)
    t = next;
    ft = fn;
  }
  return {t, norm(formulas.point(t) - p)};
}

}  // namespace footpoint::curve
