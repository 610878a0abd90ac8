#include "parametric/solvers/surface_certificate.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <queue>

#include "formula/ball.hpp"
#include "parametric/geometry/box_quadratic.hpp"
#include "parametric/geometry/distance_bound.hpp"
#include "parametric/geometry/foot_region_bound.hpp"
#include "parametric/solvers/surface_convergence.hpp"
#include "solvers/certificate_ledger.hpp"

namespace footpoint::surface {

namespace {

using formula::ball::kU;  // the unit roundoff

// A box still open: a compiled cell, or a sub-box bounded at run time.
struct OpenBox {
  Params<2> lo, hi;
  std::int32_t cell = -1;                            // the compiled cell, or -1 (a sub-box)
  std::atomic<const SubBoxPair*>* halves = nullptr;  // where its halves are published
  const BoxEnclosure<2>* ancestor = nullptr;         // its own enclosure (a cell's, a sub-box's)
  const BoxEnclosure<2>* parent = nullptr;           // the box it was bisected from (a sub-box)
  Params<2> parent_lo{}, parent_hi{};
  double lb = 0.0;           // the best lower bound of the distance over it so far
  HessianBounds<2> hessian;  // ∇²f over it
  bool split_u = true;       // bisect along u (the box is longer along u on the surface)
  bool solved = false;       // a local solve was started from it
  bool nearer = false;       // its centre is nearer than the answer by more than the gap
  bool bounded = true;       // the formulas are finite and smooth over it
  bool finite = true;        // the formulas are finite over it (else: non_finite)
  bool monotone = false;     // f is monotone along a parameter over it, towards an inner face
};

struct ByBound {
  bool operator()(const OpenBox& a, const OpenBox& b) const { return a.lb > b.lb; }  // least first
};

struct Known {
  explicit Known(const Params<2>& at_t) : t(at_t) {}
  Params<2> t;
  bool enclosed = false;
  PointEnclosure<2> point;  // s and J at t (lazily)
  GradientEnclosure<2> at;  // f and ∇f at t, enclosed (lazily)
  // The compiled cell holding t (where the walk met it): the second partials about t.
  const BoxEnclosure<2>* cell = nullptr;
  Params<2> cell_lo{}, cell_hi{};
};

bool holds(const Params<2>& lo, const Params<2>& hi, const Params<2>& t) {
  return t[0] >= lo[0] && t[0] <= hi[0] && t[1] >= lo[1] && t[1] <= hi[1];
}

// Whether the hull of the box [lo, hi] and t lies in the union of that box and [a_lo, a_hi]:
// each piece of the hull outside the box (at most four rectangles) lies in the other.
bool hull_in_union(const Params<2>& lo, const Params<2>& hi, const Params<2>& t, const Params<2>& a_lo,
                   const Params<2>& a_hi) {
  const Params<2> h_lo{std::min(lo[0], t[0]), std::min(lo[1], t[1])};
  const Params<2> h_hi{std::max(hi[0], t[0]), std::max(hi[1], t[1])};
  auto inside = [&](const Params<2>& r_lo, const Params<2>& r_hi) {
    return r_lo[0] >= a_lo[0] && r_hi[0] <= a_hi[0] && r_lo[1] >= a_lo[1] && r_hi[1] <= a_hi[1];
  };
  if (h_lo[0] < lo[0] && !inside({h_lo[0], h_lo[1]}, {lo[0], h_hi[1]})) return false;
  if (h_hi[0] > hi[0] && !inside({hi[0], h_lo[1]}, {h_hi[0], h_hi[1]})) return false;
  if (h_lo[1] < lo[1] && !inside({lo[0], h_lo[1]}, {hi[0], lo[1]})) return false;
  if (h_hi[1] > hi[1] && !inside({lo[0], hi[1]}, {hi[0], h_hi[1]})) return false;
  return true;
}

// The second partials over the union of two boxes: the hull of their enclosures'.
BoxEnclosure<2> second_partials_hull(const BoxEnclosure<2>& a, const BoxEnclosure<2>& b) {
  BoxEnclosure<2> u = a;
  u.smooth = a.smooth && b.smooth;
  for (std::size_t q = 0; q < u.d2_mid.size(); ++q)
    for (int k = 0; k < 3; ++k) {
      const double lo = std::min(a.d2_mid[q][k] - a.d2_rad[q][k], b.d2_mid[q][k] - b.d2_rad[q][k]);
      const double hi = std::max(a.d2_mid[q][k] + a.d2_rad[q][k], b.d2_mid[q][k] + b.d2_rad[q][k]);
      u.d2_mid[q][k] = 0.5 * (lo + hi);
      u.d2_rad[q][k] = (0.5 * (hi - lo)) * (1.0 + kBoundRounding) + 0x1p-1074;
    }
  return u;
}

class Certifier {
 public:
  Certifier(const SurfaceCells& cells, const SurfaceFormulas& formulas, const ParamBox& domain, const Vec3& p,
            const LocalSolution& answer, const std::vector<Params<2>>& known, const SurfaceLocalSolve& solve,
            bool may_improve, const SurfaceCertifyOptions& options)
      : cells_(cells),
        formulas_(formulas),
        domain_(domain),
        p_(p),
        solve_(solve),
        may_improve_(may_improve),
        options_(options),
        best_(answer),
        ledger_(answer.distance, Certificate::absolute_gap_at(p, answer.jet.s)) {
    known_.emplace_back(Params<2>{answer.u, answer.v});
    if (!options.threshold && enclose(known_.front()))
      ledger_.measure_from(known_.front().point.s, known_.front().point.s_rad, p_);
    for (const Params<2>& t : known)
      if (t[0] != answer.u || t[1] != answer.v) known_.emplace_back(t);
  }

  SurfaceCertification run() {
    walk();
    while (!open_.empty() && !ledger_.refuted()) {
      OpenBox b = open_.top();
      open_.pop();
      examine(b);
    }
    // boxes left when the budget ran out keep their bounds
    while (!open_.empty()) {
      const OpenBox& b = open_.top();
      note_unclosed(b);
      open_.pop();
    }
    SurfaceCertification out;
    out.improved = improved_;
    out.better = best_;
    out.certificate = ledger_.finish(runtime_boxes_);
    return out;
  }

 private:
  void close(double lb) { ledger_.close(lb); }
  void note_unclosed(const OpenBox& b) { ledger_.leave_open(b.lb, b.finite); }

  // The distance to the box of s over a box: over the points where s is finite (the surface is
  // the part of the domain where the formulas are finite); none where no point is in the
  // formulas' domain (+inf), 0 where the enclosure is not finite.
  double zero_order(const BoxEnclosure<2>& e) const {
    if (e.empty) return std::numeric_limits<double>::infinity();
    return e.bounded || e.finite_part ? std::sqrt(box_distance2_lower(e.s_mid, e.s_rad, p_)) : 0.0;
  }

  // A box whose formulas are finite but not smooth over it: where the switch of a select crosses
  // it, the bound of its branches (branch_lower_bound).
  void bound_branches(OpenBox& o) {
    if (o.bounded || !o.finite) return;
    std::vector<Params<2>> nearby;
    for (const Known& k : known_)
      if (near(k, o)) nearby.push_back(k.t);
    o.lb =
        std::max(o.lb, branch_lower_bound<2>(formulas_.program(), p_, o.lo, o.hi, nearby, ledger_.target()));
  }

  // 1. The hierarchy of the cells' boxes, nearest first; a subtree beyond the target is closed.
  void walk() {
    const auto& nodes = cells_.nodes();
    const double target = ledger_.target(), target2 = target > 0.0 ? target * target : 0.0;
    auto beyond = [&](double d2) { return d2 * (1.0 - 16.0 * kU) >= target2 && target > 0.0; };
    if (nodes.empty()) {
      visit_cell(0, 0.0);
      return;
    }
    if (beyond(cells_.root_distance2(p_))) {
      ledger_.skip();
      return;
    }
    std::vector<std::int32_t> stack{0};
    while (!stack.empty()) {
      const SurfaceCellNode& node = nodes[static_cast<std::size_t>(stack.back())];
      stack.pop_back();
      double d2[SurfaceCellNode::kWidth];
      SurfaceCells::box_distances2(node, p_, d2);
      for (int k = 0; k < node.children; ++k) {
        if (beyond(d2[k])) {
          ledger_.skip();
          continue;
        }
        if (node.child[k] >= 0)
          stack.push_back(node.child[k]);
        else
          visit_cell(~node.child[k], std::sqrt(d2[k] * (1.0 - 16.0 * kU)));
      }
    }
  }

  // 2., 3. and 5. for a compiled cell
  void visit_cell(std::int32_t index, double box_lb) {
    const SurfaceCell& c = cells_.cells()[static_cast<std::size_t>(index)];
    const SurfaceCellBounds& b = cells_.bounds()[static_cast<std::size_t>(index)];
    OpenBox o;
    o.lo = {c.u0, c.v0};
    o.hi = {c.u1, c.v1};
    o.cell = index;
    o.halves = &cells_.refinement().cell_slot(static_cast<std::size_t>(index));
    o.ancestor = &b.enclosure;
    for (Known& k : known_)
      if (!k.cell && holds(o.lo, o.hi, k.t)) {
        k.cell = &b.enclosure;
        k.cell_lo = o.lo;
        k.cell_hi = o.hi;
      }
    o.split_u = norm2(c.centre.su) * (c.u1 - c.u0) * (c.u1 - c.u0) >=
                norm2(c.centre.sv) * (c.v1 - c.v0) * (c.v1 - c.v0);
    o.bounded = b.enclosure.bounded && b.enclosure.smooth && b.centre_valid;
    o.finite = b.enclosure.bounded;
    o.lb = std::max(box_lb, zero_order(b.enclosure));
    if (o.lb >= ledger_.target()) return close(o.lb);
    bound_branches(o);
    if (o.lb >= ledger_.target()) return close(o.lb);
    const Vec3 r = c.centre.s - p_;
    if (c.framed && std::isfinite(b.rho)) {  // 2. the tangent plane
      const double out1 = std::max(std::abs(dot(r, c.e1)) - c.half1, 0.0);
      const double out2 = std::max(std::abs(dot(r, c.e2)) - c.half2, 0.0);
      const double h = dot(r, c.unit_normal);
      const double plane = std::sqrt(h * h + out1 * out1 + out2 * out2);
      o.lb = std::max(o.lb, plane - b.rho - kBoundRounding * (norm(r) + c.half1 + c.half2 + b.rho));
      if (o.lb >= ledger_.target()) return close(o.lb);
    }
    if (o.bounded) {  // 3. second order from the centre
      o.hessian = hessian_bounds(b.enclosure, p_);
      PointEnclosure<2> centre;
      centre.s = c.centre.s;
      centre.ds = {c.centre.su, c.centre.sv};
      centre.s_rad = b.s_rad;
      centre.ds_rad = {b.su_rad, b.sv_rad};
      centre.valid = true;
      const double f = second_order_lower_bound(enclose_gradient(centre, p_), {c.uc(), c.vc()}, o.lo, o.hi,
                                                o.hessian, ledger_.target_f());
      o.lb = std::max(o.lb, distance_from_f_lower(f));
      if (o.lb >= ledger_.target()) return close(o.lb);
      if (monotone(o, b.enclosure, centre)) return close(ledger_.target());
    }
    open_.push(o);
  }

  // 5. The monotonicity test (distance_bound.hpp: gradient_signs): f rises or falls along a parameter
  // over the whole box, away from the domain's edge on that side; the least of f over the domain
  // is elsewhere, and the box closes without a bound of its own.
  bool monotone(const OpenBox& b, const BoxEnclosure<2>& e, const PointEnclosure<2>& centre) const {
    if (!b.bounded) return false;
    const std::array<int, 2> signs = gradient_signs<2>(e, centre, p_);
    const Params<2> dlo{domain_.umin, domain_.vmin}, dhi{domain_.umax, domain_.vmax};
    for (int i = 0; i < 2; ++i) {
      const std::size_t a = static_cast<std::size_t>(i);
      if ((signs[a] > 0 && b.lo[a] > dlo[a]) || (signs[a] < 0 && b.hi[a] < dhi[a])) return true;
    }
    return false;
  }

  // A known minimiser lies in the box grown by its width on each side.
  static bool near(const Known& k, const OpenBox& b) {
    const double wu = b.hi[0] - b.lo[0], wv = b.hi[1] - b.lo[1];
    return k.t[0] >= b.lo[0] - wu && k.t[0] <= b.hi[0] + wu && k.t[1] >= b.lo[1] - wv &&
           k.t[1] <= b.hi[1] + wv;
  }
  bool near_known(const OpenBox& b) const {
    return std::any_of(known_.begin(), known_.end(), [&](const Known& k) { return near(k, b); });
  }

  // The foot region bound (parametric/geometry/foot_region_bound.hpp) of the box from the known
  // minimiser k, over the hull of the box and k.t, with the second partials of a box that holds
  // that hull: the box itself, the box it was bisected from, or its union with k's cell.
  double foot_region(const OpenBox& b, Known& k) {
    if (!enclose(k)) return -std::numeric_limits<double>::infinity();
    const Params<2> h_lo{std::min(b.lo[0], k.t[0]), std::min(b.lo[1], k.t[1])};
    const Params<2> h_hi{std::max(b.hi[0], k.t[0]), std::max(b.hi[1], k.t[1])};
    auto bound = [&](const BoxEnclosure<2>& d2) {
      return foot_region_lower_bound<2>(k.point, k.at, k.t, d2, h_lo, h_hi, p_);
    };
    if (holds(b.lo, b.hi, k.t)) return bound(*b.ancestor);
    if (b.parent && holds(b.parent_lo, b.parent_hi, k.t)) return bound(*b.parent);
    if (k.cell && hull_in_union(b.lo, b.hi, k.t, k.cell_lo, k.cell_hi))
      return bound(second_partials_hull(*b.ancestor, *k.cell));
    return -std::numeric_limits<double>::infinity();
  }

  // 4. from the known minimisers near the box; true when it closes it
  bool close_from_known(OpenBox& b) {
    if (!b.bounded) return false;
    for (Known& k : known_) {
      if (!near(k, b)) continue;
      b.lb = std::max(b.lb, distance_from_f_lower(foot_region(b, k)));
      if (b.lb >= ledger_.target()) return true;
    }
    if (!b.hessian.valid) return false;
    for (Known& k : known_) {
      if (!near(k, b)) continue;
      const Params<2> q{std::clamp(k.t[0], b.lo[0], b.hi[0]), std::clamp(k.t[1], b.lo[1], b.hi[1])};
      GradientEnclosure<2> at;
      if (q == k.t) {
        if (!enclose(k)) continue;
        at = k.at;
      } else {
        // the bound from the point jet at q (no rounding radii) first: the rigorous enclosure, a
        // ball jet several times dearer, only where that can reach the target
        const SurfaceJet j = formulas_.jet(q[0], q[1]);
        PointEnclosure<2> guess;
        guess.s = j.s;
        guess.ds = {j.su, j.sv};
        const double predicted = second_order_lower_bound(enclose_gradient(guess, p_), q, b.lo, b.hi,
                                                          b.hessian, ledger_.target_f());
        if (!(distance_from_f_lower(predicted) >= ledger_.target())) continue;
        const PointEnclosure<2> e = enclose_point<2>(formulas_.program(), q);
        if (!e.valid) continue;
        at = enclose_gradient(e, p_);
      }
      b.lb = std::max(b.lb, distance_from_f_lower(
                                second_order_lower_bound(at, q, b.lo, b.hi, b.hessian, ledger_.target_f())));
      if (b.lb >= ledger_.target()) return true;
    }
    return false;
  }

  // s, J, f and ∇f at a known minimiser, enclosed once.
  bool enclose(Known& k) {
    if (!k.enclosed) {
      k.point = enclose_point<2>(formulas_.program(), k.t);
      if (!k.point.valid) return false;
      k.at = enclose_gradient(k.point, p_);
      k.enclosed = true;
    }
    return true;
  }

  // Adds t to the known minimisers unless one lies within 2^-40 of the domain's widths of it (a
  // solve that found a known minimiser again: its bounds would repeat that one's). False then.
  bool learn(const Params<2>& t) {
    const double tol_u = 0x1p-40 * (domain_.umax - domain_.umin),
                 tol_v = 0x1p-40 * (domain_.vmax - domain_.vmin);
    for (const Known& k : known_)
      if (std::abs(k.t[0] - t[0]) <= tol_u && std::abs(k.t[1] - t[1]) <= tol_v) return false;
    known_.emplace_back(t);
    return true;
  }

  // Where a local solve starts in the box: the minimiser over it of the Newton model at its
  // centre (a cell's stored jet), or its centre.
  Params<2> start_in(const OpenBox& b) const {
    if (b.cell < 0) return {0.5 * (b.lo[0] + b.hi[0]), 0.5 * (b.lo[1] + b.hi[1])};
    const SurfaceCell& c = cells_.cells()[static_cast<std::size_t>(b.cell)];
    const SurfaceJet& j = c.centre;
    const Vec3 r = j.s - p_;
    BoxQuadratic q;
    q.g = {dot(r, j.su), dot(r, j.sv)};
    q.H = {{{c.E + dot(r, j.suu), c.F + dot(r, j.suv)}, {c.F + dot(r, j.suv), c.G + dot(r, j.svv)}}};
    const BoxMinimum m = minimize_on_box(q, {c.u0 - c.uc(), c.v0 - c.vc()}, {c.u1 - c.uc(), c.v1 - c.vc()});
    if (!std::isfinite(m.delta[0]) || !std::isfinite(m.delta[1])) return {c.uc(), c.vc()};
    return {std::clamp(c.uc() + m.delta[0], c.u0, c.u1), std::clamp(c.vc() + m.delta[1], c.v0, c.v1)};
  }

  // A local solve from the box; its minimum becomes known, and a nearer one than the answer
  // replaces it (auto) or refutes it (a given answer).
  void solve_from(OpenBox& b) {
    b.solved = true;
    if (solves_ >= options_.max_solves) return;
    ++solves_;
    const Params<2> t = start_in(b);
    const LocalSolution s = solve_(t[0], t[1]);
    if (!std::isfinite(s.distance)) return;
    if (!learn(Params<2>{s.u, s.v})) return;  // a minimiser known already
    if (!(s.distance < best_.distance)) return;
    if (!may_improve_) {
      if (s.distance < best_.distance - ledger_.gap()) ledger_.refute();
      return;
    }
    best_ = s;
    improved_ = true;
    ledger_.retarget(s.distance, Certificate::absolute_gap_at(p_, s.jet.s));
    if (enclose(known_.back())) ledger_.measure_from(known_.back().point.s, known_.back().point.s_rad, p_);
  }

  void examine(OpenBox b) {
    if (b.lb >= ledger_.target()) return close(b.lb);  // the target fell with a better answer
    const bool closed = close_from_known(b);
    if (closed) return close(b.lb);
    // a box with no known minimiser near may hide one: solve from it once (a box next to a known
    // minimiser is bisected instead: a solve from it would find that minimiser again)
    if (!b.solved && (b.nearer || !near_known(b))) {
      solve_from(b);
      if (ledger_.refuted()) return note_unclosed(b);
      if (close_from_known(b)) return close(b.lb);
      if (b.lb >= ledger_.target()) return close(b.lb);
    }
    // 6. bisect, into halves kept for later points (parametric/seeding/surface_refinement.hpp)
    if (runtime_boxes_ + 2 > options_.max_boxes) return note_unclosed(b);
    const int axis = b.split_u ? 0 : 1;
    const double mid = 0.5 * (b.lo[axis] + b.hi[axis]);
    if (!(mid > b.lo[axis] && mid < b.hi[axis])) return note_unclosed(b);  // no room left
    std::unique_ptr<SubBoxPair> scratch;
    const SubBoxPair& pair =
        cells_.refinement().halves(*b.halves, *b.ancestor, b.lo, b.hi, b.split_u, b.cell >= 0, scratch);
    if (scratch) scratch_.push_back(std::move(scratch));
    for (const SubBox& half : pair.half) {
      OpenBox child = bound_sub_box(half, &half.enclosure);
      child.parent = b.ancestor;
      child.lb = std::max(child.lb, b.lb);
      child.parent_lo = b.lo;
      child.parent_hi = b.hi;
      if (ledger_.refuted()) return note_unclosed(child);
      if (child.lb >= ledger_.target())
        close(child.lb);
      else if (child.monotone)
        close(ledger_.target());
      else
        open_.push(child);
    }
  }

  // 1, 3 for a sub-box, from its enclosure and the enclosure at its centre.
  OpenBox bound_sub_box(const SubBox& h, const BoxEnclosure<2>* ancestor) {
    ++runtime_boxes_;
    OpenBox b;
    b.ancestor = ancestor;
    b.lo = h.lo;
    b.hi = h.hi;
    b.halves = &h.halves;
    b.split_u = h.split_u;
    const BoxEnclosure<2>& e = h.enclosure;
    b.bounded = e.bounded && e.smooth && h.centre.valid;
    b.finite = e.bounded;
    b.lb = zero_order(e);
    if (b.lb >= ledger_.target()) return b;
    bound_branches(b);
    if (!b.bounded) return b;
    b.hessian = hessian_bounds(e, p_);
    const Params<2> c{0.5 * (b.lo[0] + b.hi[0]), 0.5 * (b.lo[1] + b.hi[1])};
    const GradientEnclosure<2> g = enclose_gradient(h.centre, p_);
    b.lb = std::max(b.lb, distance_from_f_lower(
                              second_order_lower_bound(g, c, b.lo, b.hi, b.hessian, ledger_.target_f())));
    b.monotone = monotone(b, e, h.centre);
    // the centre is a point of the surface: nearer than the answer by more than the gap, it holds
    // a better minimum (or refutes a given answer)
    if (ledger_.nearer_than_answer(h.centre.s, h.centre.s_rad, p_)) {
      b.nearer = true;
      if (!may_improve_) ledger_.refute();
    }
    return b;
  }

  const SurfaceCells& cells_;
  const SurfaceFormulas& formulas_;
  const ParamBox domain_;
  const Vec3 p_;
  const SurfaceLocalSolve& solve_;
  const bool may_improve_;
  const SurfaceCertifyOptions& options_;
  LocalSolution best_;
  CertificateLedger ledger_;
  bool improved_ = false;
  int runtime_boxes_ = 0, solves_ = 0;
  std::vector<std::unique_ptr<SubBoxPair>> scratch_;  // halves past the refinement's cap
  std::vector<Known> known_;
  std::priority_queue<OpenBox, std::vector<OpenBox>, ByBound> open_;
};

}  // namespace

SurfaceCertification certify_surface(const SurfaceCells& cells, const SurfaceFormulas& formulas,
                                     const ParamBox& box, const Vec3& p, const LocalSolution& answer,
                                     const std::vector<Params<2>>& known, const SurfaceLocalSolve& solve,
                                     bool may_improve, const SurfaceCertifyOptions& options) {
  return Certifier(cells, formulas, box, p, answer, known, solve, may_improve, options).run();
}

Certificate certify_answer(const SurfaceCells& cells, const SurfaceFormulas& formulas, const ParamBox& box,
                           const Vec3& p, double u, double v, const SurfaceCertifyOptions& options) {
  LocalSolution answer;
  answer.u = u;
  answer.v = v;
  answer.jet = formulas.jet(u, v);
  answer.distance = norm(answer.jet.s - p);
  answer.status = Status::converged;
  const ConvergenceCriteria criteria = convergence_criteria(Options{}, box, kLocalMaxIterations);
  const SurfaceLocalSolve solve = [&](double u0, double v0) {
    return projected_newton(formulas, box, p, u0, v0, criteria);
  };
  return certify_surface(cells, formulas, box, p, answer, {}, solve, false, options).certificate;
}

}  // namespace footpoint::surface
