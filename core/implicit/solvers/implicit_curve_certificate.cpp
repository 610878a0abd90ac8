#include "implicit/solvers/implicit_curve_certificate.hpp"

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
#include <limits>

#include "geometry/interval_vec3.hpp"
#include "geometry/krawczyk.hpp"
#include "geometry/midpoint_radius.hpp"
#include "geometry/segment_distance.hpp"
#include "implicit/geometry/implicit_curve_differentials.hpp"
#include "implicit/solvers/foot_refinement.hpp"

namespace footpoint::curve {
namespace {

namespace iv = formula::interval;
using formula::Interval;

// Sub-boxes bounded per point beyond the compiled cells, and bisections of one cell or box.
constexpr int kBoxBudget = 600;
constexpr int kMaxDepth = 48;
// The absolute gap in ulps of the coordinates (projection/certificate.hpp).
constexpr double kGapUlps = 256.0;

IntervalVector<3> as_vector(const IVec3& v) { return {v[0], v[1], v[2]}; }

Box3 around(Vec3 m, double r, const Box3& within) {
  Box3 z;
  for (int k = 0; k < 3; ++k) {
    z.lo[k] = std::max(within.lo[k], formula::down(m[k] - r, 1));
    z.hi[k] = std::min(within.hi[k], formula::up(m[k] + r, 1));
  }
  return z;
}

// The nodes of a depth-first walk of the cell tree still to visit. The tree splits at medians
// (implicit/seeding/curve_cell_tree), so its depth is at most log2 of its items + 1 < 32, and a walk holds
// at most one pending sibling per level.
class NodeStack {
 public:
  bool empty() const { return size_ == 0; }
  void push(std::int32_t node) { nodes_[size_++] = node; }
  std::size_t pop() { return static_cast<std::size_t>(nodes_[--size_]); }

 private:
  std::array<std::int32_t, 64> nodes_;  // [0, size_) pushed before read
  std::size_t size_ = 0;
};

class Certifier {
 public:
  Certifier(const ImplicitEquations& eq, const Box3& box, const CurveDiscovery& d, Vec3 p, Vec3 foot,
            double distance)
      : eq_(eq), box_(box), d_(d), p_(p), foot_(foot), distance_(distance) {}

  Certificate run() {
    Certificate c;
    c.computed = true;
    c.absolute_gap = implicit_absolute_gap(p_, foot_);
    gap_ = std::fmax(Certificate::kRelativeGap * distance_, c.absolute_gap);
    threshold_ = distance_ - gap_;
    threshold2_ = threshold_ > 0.0 ? square_upper_bound(threshold_) : 0.0;
    const auto& nodes = d_.tree.nodes();
    const auto& items = d_.tree.items();
    NodeStack stack;
    if (!nodes.empty()) stack.push(0);
    while (!stack.empty()) {
      const CurveCellTree::Node& node = nodes[stack.pop()];
      if (far_enough(node.box)) continue;
      if (node.left >= 0) {
        stack.push(node.left);
        stack.push(node.right);
        continue;
      }
      for (std::int32_t i = node.first; i < node.first + node.count; ++i)
        item(items[static_cast<std::size_t>(i)]);
    }
    bound_near_cells();
    if (far2_ < std::numeric_limits<double>::infinity())
      contribute(formula::next_down(std::sqrt(far2_)), CertificateReason::gap_met);
    contribute(far_arcs_, CertificateReason::gap_met);
    // Every part was bounded, so lower_ is finite unless nothing is left at all; below the
    // answer's own distance it stays a lower bound.
    c.lower_bound = std::fmin(lower_, distance_);
    c.boxes = boxes_;
    c.certified = Certificate::meets_gap(distance_, lower_, c.absolute_gap);
    c.reason = c.certified ? CertificateReason::gap_met : reason_;
    return c;
  }

 private:
  void contribute(double bound, CertificateReason why) {
    if (bound < lower_) {
      lower_ = bound;
      reason_ = why == CertificateReason::gap_met ? CertificateReason::budget_exhausted : why;
    }
  }

  // True when the whole box is at least the threshold away (its bound is kept for the end).
  bool far_enough(const Box3& b) {
    const double d2 = distance2_lower_bound(p_, b);
    if (!(d2 >= threshold2_)) return false;
    if (d2 < far2_) far2_ = d2;
    return true;
  }

  // True when every arc of the cell is at least the threshold away by its capsule (the least such
  // bound is kept for the end).
  bool arcs_far_enough(std::size_t cell) {
    double lower = std::numeric_limits<double>::infinity();
    for (const ArcCapsule& c : d_.cells.arc_capsules(cell)) {
      const double bound = segment_distance_lower_bound(p_, c.a, c.b) - c.radius;
      if (!(bound >= threshold_)) return false;
      if (bound < lower) lower = bound;
    }
    if (lower < std::numeric_limits<double>::infinity()) keep_far_arc(lower);
    return true;
  }

  // A capsule bound at least the threshold (never NaN), kept for the end rounded down.
  void keep_far_arc(double bound) {
    const double lowered = formula::next_down(bound);
    if (lowered < far_arcs_) far_arcs_ = lowered;
  }

  void item(const CellItem& it) {
    if (far_enough(it.box)) return;
    switch (it.kind) {
      case CellItemKind::box_face:
        contribute(distance_lower_bound(p_, it.box), CertificateReason::budget_exhausted);
        return;
      case CellItemKind::unproved: {
        const UnprovedBox& u = d_.cells.unproved[static_cast<std::size_t>(it.index)];
        unproved(u.box, u.reason == UnprovedReason::not_smooth ? CertificateReason::non_finite
                                                               : CertificateReason::singular);
        return;
      }
      case CellItemKind::proved_cell:
        if (!arcs_far_enough(static_cast<std::size_t>(it.index))) near_cell(it);
        return;
    }
  }

  // A proved cell its capsules do not rule out: kept until the walk has met the foot's cell (the
  // first whose box holds the foot point), or bounded at once when there is no room left.
  void near_cell(const CellItem& it) {
    const ProvedCell& cell = d_.cells.cells[static_cast<std::size_t>(it.index)];
    if (!foot_cell_ && cell.box.contains(foot_)) foot_cell_ = &cell;
    if (!near_bounded_ && near_count_ < near_cells_.size()) {
      near_cells_[near_count_++] = &it;
      return;
    }
    bound_near_cells();
    proved(it);
  }

  // The kept cells, after Krawczyk's test over the foot cell's enlarged box, which may settle
  // them all.
  void bound_near_cells() {
    if (near_bounded_) return;
    near_bounded_ = true;
    if (foot_cell_) {
      foot_cell_edge_ = foot_cell_->box.max_edge();
      foot_enlarged();
    }
    for (std::size_t i = 0; i < near_count_; ++i) proved(*near_cells_[i]);
  }

  IVec3 from_p(const Box3& b) const { return ivec::sub(ivec::of_point(p_), ivec::of_box(b)); }

  // G = (f1, f2, F) at the foot point, enclosed; false when the formulas are not smooth there.
  bool foot_values(IntervalVector<3>& g) {
    if (!foot_done_) {
      foot_done_ = true;
      foot_ok_ = values_at(foot_, foot_g_);
    }
    g = foot_g_;
    return foot_ok_;
  }

  // G = (f1, f2, F) at a point m near a zero of G, enclosed; false when the formulas are not
  // smooth there. Krawczyk's box about m is about ‖Y G(m)‖: the widths of f1, f2 over |∇f_i|,
  // divided by the sine of the angle between ∇f1 and ∇f2. Where that exceeds a quarter of the gap
  // (two nearly tangent surfaces), f1 and f2 are enclosed to the rounding of their values
  // instead (ImplicitEquations::accurate_values).
  bool values_at(Vec3 m, IntervalVector<3>& g) {
    ++boxes_;
    const ImplicitIntervalJet j = eq_.point_gradient(m);
    if (!j.smooth) return false;
    g = {j.f[0], j.f[1], ivec::dot(j.tangent(), from_p({m, m}))};
    std::array<Interval, 2> f;
    if (position_spread(j) > 0.25 * gap_ && eq_.accurate_values(m, f)) {
      g[0] = f[0];
      g[1] = f[1];
    }
    return true;
  }

  // How far the point may move for the widths of the enclosures of f1 and f2 (see values_at).
  static double position_spread(const ImplicitIntervalJet& j) {
    Vec3 n[2];
    double spread = 0.0;
    for (int i = 0; i < 2; ++i) {
      n[i] = {iv::mid(j.grad[i][0]), iv::mid(j.grad[i][1]), iv::mid(j.grad[i][2])};
      spread = std::fmax(spread, iv::rad(j.f[i]) / norm(n[i]));
    }
    return spread * norm(n[0]) * norm(n[1]) / norm(cross(n[0], n[1]));
  }

  // ∇F over a box from enclosures of T and ∂T/∂x_j over it: ∂_j F = Σ_i ∂_j T_i (p - x)_i - T_j
  // ([Curve] eq. (7)), in midpoint-radius form (an exact 0 stays exact: the z-column of a planar
  // curve, which Krawczyk's test needs exact).
  static IVec3 gradient_of_f(const IVec3& t, const IMat3& dt, const IVec3& pb) {
    IVec3 g;
    for (int j = 0; j < 3; ++j) g[j] = midrad::dot_minus(dt[j], pb, t[j]);
    return g;
  }

  // Every zero of G in `box` lies in the returned box (empty: none), by Krawczyk's test about m.
  // False when the test does not contract (‖I - Y G'‖ >= 1, then written to *contraction).
  bool zeros_about(const Box3& box, Vec3 m, const IntervalVector<3>& gm, const IntervalMatrix<3>& jac,
                   Box3& zeros, double* contraction = nullptr) {
    const KrawczykResult<3> k = krawczyk<3>(as_vector(ivec::of_box(box)), {m.x, m.y, m.z}, gm, jac);
    if (k.verdict == KrawczykVerdict::no_zero) {
      zeros = {{1, 1, 1}, {0, 0, 0}};
      return true;
    }
    if (!(k.contraction < 1.0)) {
      if (contraction) *contraction = k.contraction;
      return false;
    }
    zeros = around(m, k.radius, box);
    return true;
  }

  static IntervalMatrix<3> jacobian(const std::array<IVec3, 2>& grad, const IVec3& grad_f) {
    IntervalMatrix<3> a{};
    for (int j = 0; j < 3; ++j) {
      a[0][j] = grad[0][j];
      a[1][j] = grad[1][j];
      a[2][j] = grad_f[j];
    }
    return a;
  }

  // A few Newton steps on G from x (double jets); true when they stay finite.
  bool newton_on_g(Vec3& x) const {
    for (int n = 0; n < 6; ++n) {
      const ImplicitJet j = eq_.jet(x);
      Vec3 step;
      if (!critical_point_step(j, x, p_, j.f, step)) return false;
      x += step;
      if (!is_finite(x)) return false;
    }
    refine_foot(eq_, p_, x);  // on two nearly tangent surfaces (foot_refinement.hpp)
    return true;
  }

  void contribute_zeros(const Box3& zeros) {
    if (!zeros.empty()) contribute(distance_lower_bound(p_, zeros), CertificateReason::budget_exhausted);
  }

  // The box about the foot point in which Krawczyk's test with fresh interval jets proved every
  // zero of G to lie within a few ulps of the foot (computed once per point, when first needed).
  // Its radius is half the edge of the foot's cell, halved while the test does not contract; where
  // the test over the foot cell's enlarged box (2 edges wide) found ‖I - Y J‖ = c >= 1, the first
  // radius is 0.9 / c edges instead (at most one edge): c grows about in proportion to the box's
  // width, and the widest box that contracts settles the most of the cells next to the foot.
  bool foot_box() {
    if (!foot_box_tried_) {
      foot_box_tried_ = true;
      IntervalVector<3> g{};
      const double first = enlarged_contraction_ >= 1.0 && enlarged_contraction_ < 16.0
                               ? std::fmin(1.0, 0.9 / enlarged_contraction_)
                               : 0.5;
      if (foot_cell_edge_ > 0.0 && foot_values(g))
        for (double radius = first * foot_cell_edge_; radius >= 0.06 * foot_cell_edge_ && !foot_box_ok_;
             radius *= 0.5) {
          const Box3 b = around(foot_, radius, box_);
          ++boxes_;
          const ImplicitIntervalJet j = eq_.interval_jet(b);
          if (!j.smooth) continue;
          Box3 zeros;
          if (zeros_about(b, foot_, g,
                          jacobian(j.grad, gradient_of_f(j.tangent(), j.tangent_derivatives(), from_p(b))),
                          zeros)) {
            foot_box_ = b;
            foot_zeros_ = zeros;
            foot_box_ok_ = true;
          }
        }
    }
    return foot_box_ok_;
  }

  // A box about the foot point holding every zero of G in some region, from Krawczyk's test over
  // that region: its radius is ‖Y G(foot)‖ / (1 - c), and c, from enclosures over the whole
  // region, may be near 1 where ∇f1 and ∇f2 are nearly parallel. When it is too wide to meet the
  // gap and lies in foot_box(), the zeros are those of the foot box's test (fresh jets over a
  // smaller box, a smaller c).
  Box3 tightened(const Box3& zeros) {
    if (zeros.empty() || distance_lower_bound(p_, zeros) >= threshold_) return zeros;
    return foot_box() && foot_box_.contains(zeros) ? foot_zeros_ : zeros;
  }

  // Krawczyk's test over the foot cell's enlarged box about the foot point: when it contracts,
  // every zero of G in that box lies within a few ulps of the foot, and the cells inside it need
  // nothing more.
  void foot_enlarged() {
    const EnlargedBounds& e = foot_cell_->around;
    IntervalVector<3> g{};
    if (!e.valid || !foot_values(g)) return;
    const IntervalMatrix<3> jac =
        jacobian(e.grad, gradient_of_f(e.tangent, e.tangent_derivatives, from_p(e.box)));
    Box3 zeros;
    if (!zeros_about(e.box, foot_, g, jac, zeros, &enlarged_contraction_)) return;
    foot_region_ = e.box;
    foot_region_zeros_ = tightened(zeros);
    foot_region_ok_ = true;
  }

  // Where the compiled enclosures of `cell` leave a zero of G possible in `part`: nowhere, or a
  // box about m (part's centre, G(m) from the enclosures) that every zero in part lies in.
  bool zeros_in_part(const ProvedCell& cell, const Box3& part, Box3& zeros) {
    const CellBounds& b = cell.bounds;
    const Vec3 m = part.center();
    const IVec3 from_center = ivec::sub(ivec::of_point(m), ivec::of_point(b.center));
    IVec3 t_m = b.tangent_center;
    for (int j = 0; j < 3; ++j) t_m = ivec::add(t_m, ivec::scale(from_center[j], b.tangent_derivatives[j]));
    const IntervalVector<3> gm{iv::add(b.f_center[0], ivec::dot(b.grad[0], from_center)),
                               iv::add(b.f_center[1], ivec::dot(b.grad[1], from_center)),
                               ivec::dot(t_m, from_p({m, m}))};
    const IVec3 pb = from_p(part);
    return zeros_about(part, m, gm, jacobian(b.grad, gradient_of_f(b.tangent, b.tangent_derivatives, pb)),
                       zeros);
  }

  // Krawczyk's test over the cell's enlarged box (compiled enclosures): about the foot point when
  // it lies there (the answer is then the only critical point there, to rounding), else about the
  // centre, where K(X) ∩ cell holds every zero in the cell. False when the test does not settle
  // the cell (no enclosures, no contraction, or a critical point of its own left wide).
  bool enlarged(const ProvedCell& cell, const Interval& f_center) {
    const EnlargedBounds& e = cell.around;
    if (!e.valid) return false;
    const IntervalMatrix<3> jac =
        jacobian(e.grad, gradient_of_f(e.tangent, e.tangent_derivatives, from_p(e.box)));
    const IntervalVector<3> x = as_vector(ivec::of_box(e.box));
    IntervalVector<3> g{};
    Box3 zeros;
    if (e.box.contains(foot_) && foot_values(g)) {
      if (!zeros_about(e.box, foot_, g, jac, zeros)) return false;
      contribute_zeros(intersection(tightened(zeros), cell.box));
      return true;
    }
    const Vec3 c = cell.bounds.center;
    const KrawczykResult<3> k =
        krawczyk<3>(x, {c.x, c.y, c.z}, {cell.bounds.f_center[0], cell.bounds.f_center[1], f_center}, jac);
    if (k.verdict == KrawczykVerdict::no_zero) return true;
    zeros = intersection(cell.box, ivec::to_box({k.image[0], k.image[1], k.image[2]}));
    if (k.contraction < 1.0) zeros = intersection(zeros, around(c, k.radius, e.box));
    if (zeros.empty() || distance_lower_bound(p_, zeros) >= threshold_) {
      contribute_zeros(zeros);
      return true;
    }
    // A critical point of its own (a farther local minimum, a maximum): about its Newton point,
    // enclosed by fresh interval jets, the box shrinks to rounding.
    Vec3 m = zeros.center();
    if (!newton_on_g(m) || !e.box.contains(m)) return false;
    IntervalVector<3> gm{};
    if (!values_at(m, gm) || !zeros_about(e.box, m, gm, jac, zeros)) return false;
    contribute_zeros(intersection(zeros, cell.box));
    return true;
  }

  // A proved cell (its item: the cell and the part of it its arcs' capsules reach).
  void proved(const CellItem& it) {
    const auto index = static_cast<std::size_t>(it.index);
    const ProvedCell& cell = d_.cells.cells[index];
    const CellBounds& b = cell.bounds;
    // Where the foot's region holds every arc of the cell, every zero of G there is the foot
    // point's, whose box is all there is to bound (the box comparison first: cheaper than F's
    // range).
    if (foot_region_ok_ && foot_region_.contains(it.box))
      return contribute_zeros(intersection(foot_region_zeros_, it.box));
    const IVec3 pb = from_p(cell.box);
    if (ivec::dot(b.tangent, pb).excludes_zero()) return;
    const IVec3 offset = ivec::sub(ivec::of_box(cell.box), ivec::of_point(b.center));
    const IVec3 grad_f = gradient_of_f(b.tangent, b.tangent_derivatives, pb);
    const Interval f_center = ivec::dot(b.tangent_center, from_p({b.center, b.center}));
    if (iv::add(f_center, ivec::dot(grad_f, offset)).excludes_zero()) return;
    // The foot cell's own enlarged test is foot_enlarged()'s, which settled the cell above or
    // failed.
    if (&cell != foot_cell_ && enlarged(cell, f_center)) return;
    // Without a foot region, the foot box may hold every arc of the cell.
    if (!foot_region_ok_ && foot_box() && foot_box_.contains(it.box))
      return contribute_zeros(intersection(foot_zeros_, it.box));
    const IntervalMatrix<3> jac = jacobian(b.grad, grad_f);
    IntervalVector<3> g{};
    Box3 zeros = cell.box;
    if (cell.box.contains(foot_) && foot_values(g)) {
      // The answer's own cell: its zero is the foot point, to rounding, when the test contracts.
      if (zeros_about(cell.box, foot_, g, jac, zeros)) return contribute_zeros(tightened(zeros));
    } else if (zeros_about(cell.box, b.center, {b.f_center[0], b.f_center[1], f_center}, jac, zeros)) {
      if (zeros.empty() || distance_lower_bound(p_, zeros) >= threshold_) return contribute_zeros(zeros);
      if (foot_box() && foot_box_.contains(intersection(zeros, it.box))) return contribute_zeros(foot_zeros_);
      // A critical point of its own (a farther local minimum, a maximum): about its Newton point,
      // enclosed by fresh interval jets, the box shrinks to rounding.
      Vec3 x = zeros.center();
      IntervalVector<3> gx{};
      Box3 tight;
      if (newton_on_g(x) && zeros.contains(x) && values_at(x, gx) && zeros_about(cell.box, x, gx, jac, tight))
        return contribute_zeros(tight);
    }
    // Every zero of G left in the cell lies on one of its arcs, so in that arc's capsule box: the
    // boxes are bisected (those that overlap as their hull), thin beside the arcs, not the cell.
    std::array<Box3, 8> parts;
    std::size_t n = 0;
    for (const ArcCapsule& arc : d_.cells.arc_capsules(index)) {
      const double lower = segment_distance_lower_bound(p_, arc.a, arc.b) - arc.radius;
      if (lower >= threshold_) {
        keep_far_arc(lower);
        continue;
      }
      Box3 part = intersection(zeros, capsule_box(arc));
      if (part.empty()) continue;
      for (std::size_t i = 0; i < n;)
        if (parts[i].intersects(part)) {
          part = hull(part, parts[i]);
          parts[i] = parts[--n];
          i = 0;
        } else {
          ++i;
        }
      if (n == parts.size()) part = hull(part, parts[--n]);
      parts[n++] = part;
    }
    for (std::size_t i = 0; i < n; ++i) cell_parts(cell, parts[i]);
  }

  // Bisects `start` until every part is far enough, settled by `settle` (true: nothing more to
  // bound there), or beyond the budget (its box distance is then the bound, for `why`).
  template <class Settle>
  void bisect_parts(const Box3& start, CertificateReason why, Settle&& settle) {
    struct Part {
      Box3 box;
      int depth;
    };
    std::vector<Part> stack{{start, 0}};
    while (!stack.empty()) {
      const Part y = stack.back();
      stack.pop_back();
      if (far_enough(y.box)) continue;
      if (++boxes_ > kBoxBudget || y.depth >= kMaxDepth) {
        contribute(distance_lower_bound(p_, y.box), why);
        continue;
      }
      if (settle(y.box, y.depth)) continue;
      for (const Box3& half : bisect(y.box)) stack.push_back({half, y.depth + 1});
    }
  }

  // Bisection of the part of a proved cell that may hold a zero of G, with its compiled
  // enclosures; the part holding the foot point gets fresh interval jets.
  void cell_parts(const ProvedCell& cell, const Box3& start) {
    const CellBounds& b = cell.bounds;
    bisect_parts(start, CertificateReason::budget_exhausted, [&](const Box3& y, int depth) {
      if (foot_box() && foot_box_.contains(y)) {
        contribute_zeros(foot_zeros_);
        return true;
      }
      const IVec3 from_center = ivec::sub(ivec::of_box(y), ivec::of_point(b.center));
      if (iv::add(b.f_center[0], ivec::dot(b.grad[0], from_center)).excludes_zero() ||
          iv::add(b.f_center[1], ivec::dot(b.grad[1], from_center)).excludes_zero())
        return true;
      Box3 zeros;
      if (zeros_in_part(cell, y, zeros)) {
        if (zeros.empty() || distance_lower_bound(p_, zeros) >= threshold_) {
          contribute_zeros(zeros);
          return true;
        }
        if (foot_box_ok_ && foot_box_.contains(zeros)) {
          contribute_zeros(foot_zeros_);
          return true;
        }
      }
      // The compiled enclosures do not shrink with the part: its own range of f1, f2.
      const std::array<Interval, 2> f = eq_.value_enclosure(y);
      if (f[0].excludes_zero() || f[1].excludes_zero()) return true;
      return depth > 0 && fresh_part(y);
    });
  }

  // A part of a cell bounded with fresh interval jets over it: F's range, then Krawczyk's test
  // about the foot point when the part holds it, else about its centre (G there from fresh
  // interval gradients). True when that settled the part.
  bool fresh_part(const Box3& part) {
    ++boxes_;
    const ImplicitIntervalJet j = eq_.interval_jet(part);
    if (!j.smooth) return false;
    const IVec3 pb = from_p(part);
    const IVec3 t = j.tangent();
    if (ivec::dot(t, pb).excludes_zero()) return true;
    const IntervalMatrix<3> jac = jacobian(j.grad, gradient_of_f(t, j.tangent_derivatives(), pb));
    IntervalVector<3> g{};
    Box3 zeros;
    if (part.contains(foot_) && foot_values(g)) {
      if (!zeros_about(part, foot_, g, jac, zeros)) return false;
      contribute_zeros(zeros);
      return true;
    }
    const Vec3 m = part.center();
    ++boxes_;
    const ImplicitIntervalJet jm = eq_.point_gradient(m);
    if (!jm.smooth) return false;
    const KrawczykResult<3> k = krawczyk<3>(as_vector(ivec::of_box(part)), {m.x, m.y, m.z},
                                            {jm.f[0], jm.f[1], ivec::dot(jm.tangent(), from_p({m, m}))}, jac);
    if (k.verdict == KrawczykVerdict::no_zero) return true;
    if (!(k.contraction < 1.0)) return false;
    zeros = intersection(intersection(part, ivec::to_box({k.image[0], k.image[1], k.image[2]})),
                         around(m, k.radius, part));
    if (!zeros.empty() && distance_lower_bound(p_, zeros) < threshold_ &&
        zeros.max_edge() > 1e-3 * part.max_edge())
      return false;
    contribute_zeros(zeros);
    return true;
  }

  // Bisection of an unproved box with fresh interval jets.
  void unproved(const Box3& start, CertificateReason why) {
    bisect_parts(start, why, [&](const Box3& y, int) {
      const std::array<Interval, 2> f = eq_.value_enclosure(y);
      if (f[0].excludes_zero() || f[1].excludes_zero()) return true;
      const ImplicitIntervalJet j = eq_.interval_jet(y);
      if (!j.smooth || touches_box_faces(y)) return false;
      // Every point of the curve here where T ≠ 0 is a regular point; the minimum is a zero of G.
      const IVec3 pb = from_p(y);
      if (ivec::dot(j.tangent(), pb).excludes_zero()) return true;
      IntervalVector<3> g{};
      Box3 zeros;
      if (!y.contains(foot_) || !foot_values(g) ||
          !zeros_about(y, foot_, g, jacobian(j.grad, gradient_of_f(j.tangent(), j.tangent_derivatives(), pb)),
                       zeros))
        return false;
      contribute_zeros(zeros);
      return true;
    });
  }

  bool touches_box_faces(const Box3& b) const {
    for (int k = 0; k < 3; ++k)
      if (box_.hi[k] > box_.lo[k] && (b.lo[k] <= box_.lo[k] || b.hi[k] >= box_.hi[k])) return true;
    return false;
  }

  // The two halves of b across its longest side.
  static std::array<Box3, 2> bisect(const Box3& b) {
    int k = 0;
    for (int a = 1; a < 3; ++a)
      if (b.hi[a] - b.lo[a] > b.hi[k] - b.lo[k]) k = a;
    const double m = 0.5 * (b.lo[k] + b.hi[k]);
    Box3 lo = b, hi = b;
    lo.hi[k] = m;
    hi.lo[k] = m;
    return {lo, hi};
  }

  const ImplicitEquations& eq_;
  Box3 box_;
  const CurveDiscovery& d_;
  Vec3 p_, foot_;
  double distance_;
  double gap_ = 0.0, threshold_ = 0.0, threshold2_ = 0.0;
  double far2_ = std::numeric_limits<double>::infinity();      // the least squared bound of far boxes
  double far_arcs_ = std::numeric_limits<double>::infinity();  // the least bound of far capsules
  double lower_ = std::numeric_limits<double>::infinity();
  CertificateReason reason_ = CertificateReason::gap_met;
  int boxes_ = 0;
  bool foot_done_ = false, foot_ok_ = false;
  IntervalVector<3> foot_g_{};
  bool foot_box_tried_ = false, foot_box_ok_ = false;
  Box3 foot_box_, foot_zeros_;
  double foot_cell_edge_ = 0.0;
  double enlarged_contraction_ = 0.0;           // ‖I - Y J‖ over the foot cell's enlarged box, where >= 1
  const ProvedCell* foot_cell_ = nullptr;       // a proved cell holding the foot point, if one is near
  std::array<const CellItem*, 64> near_cells_;  // [0, near_count_) written before read
  std::size_t near_count_ = 0;
  bool near_bounded_ = false;
  bool foot_region_ok_ = false;
  Box3 foot_region_, foot_region_zeros_;
};

}  // namespace

double implicit_absolute_gap(Vec3 p, Vec3 foot) {
  double m = 0.0;
  for (int k = 0; k < 3; ++k) m = std::fmax(m, std::fmax(std::fabs(p[k]), std::fabs(foot[k])));
  return kGapUlps * DBL_EPSILON * std::fmax(m, DBL_MIN);
}

Certificate certify_implicit_curve_answer(const ImplicitEquations& equations, const Box3& box,
                                          const CurveDiscovery& discovery, Vec3 p, Vec3 foot,
                                          double distance) {
  return Certifier(equations, box, discovery, p, foot, distance).run();
}

Certificate certify_implicit_curve_answer(std::span<const DiscoveredCurve* const> factors, const Box3& box,
                                          Vec3 p, Vec3 foot, double distance) {
  Certificate all;
  for (const DiscoveredCurve* f : factors) {
    const Certificate c = Certifier(f->equations, box, f->discovery, p, foot, distance).run();
    // Each is below the answer's distance; the least is the union's, with its reason.
    if (!all.computed || c.lower_bound < all.lower_bound) {
      const int boxes = all.boxes;
      all = c;
      all.boxes = boxes;
    }
    all.boxes += c.boxes;
  }
  all.certified = Certificate::meets_gap(distance, all.lower_bound, all.absolute_gap);
  if (all.certified) all.reason = CertificateReason::gap_met;
  return all;
}

}  // namespace footpoint::curve
