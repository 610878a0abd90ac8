#include "seeding/curve_discovery.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "geometry/compile_budget.hpp"
#include "geometry/curve_correction.hpp"
#include "geometry/geometry_error.hpp"
#include "geometry/implicit_curve.hpp"
#include "geometry/implicit_curve_differentials.hpp"
#include "geometry/singular_point.hpp"
#include "seeding/curve_enclosure.hpp"
#include "seeding/curve_tracing.hpp"

namespace footpoint {
namespace {

// Cells whose seed fails are bisected again, at most this many extra levels.
constexpr int kExtraLevels = 4;
// The walk's largest step is this fraction of the enclosure's cell edge: every cell the curve
// crosses for more than a step holds a sample.
constexpr double kStepPerCell = 0.5;
// Certification of the kept cells (after tracing). A cell is trusted when, by the jets at its
// centre c, each surface f_i = 0 is nearly flat across it: |H_i(c)|_F * diam <= kBend * |grad f_i(c)|
// * sin(angle(grad f1, grad f2)), i.e. the gradients turn by at most ~kBend rad over the cell and
// the curve inside it is one nearly straight arc (for planar curves f2 = z is flat and the sine is 1).
// Cells that fail are bisected (with the interval exclusion) at most kCertifyLevels times; the
// pieces in the certified sub-cells that no walk passed near are seeded and traced. This is a
// second-order test at one point, not an interval proof: formula::Program offers interval values
// only, no interval gradients, so monotonicity cannot be proved rigorously here.
constexpr double kBend = 0.5;
constexpr int kCertifyLevels = 6;
constexpr double kModelMargin = 4.0;
// Jets evaluated for certification before the curve is declared too intricate for its box.
constexpr std::size_t kCertifyBudget = 100000;

class Discovery {
 public:
  Discovery(const ImplicitEquations& equations, const Box3& box) : eq_(equations), box_(box) {}

  CurveDiscovery run() {
    const auto t0 = std::chrono::steady_clock::now();
    CurveEnclosure enclosure = enclose_curve(eq_, box_);
    out_.stats.levels = enclosure.levels;
    out_.stats.cells = enclosure.cells.size();
    out_.stats.interval_tests = enclosure.tests;
    out_.stats.enclosure_truncated = enclosure.truncated;
    grid_ = enclosure.grid;
    settings_.max_step = kStepPerCell * grid_.max_edge();
    settings_.min_step = 1e-7 * settings_.max_step;
    occupancy_ = std::make_unique<SampleGrid>(grid_);

    for (const CellIndex& c : enclosure.cells) examine(grid_, c, 0);
    for (const CellIndex& c : enclosure.cells) certify(grid_, c, 0, near_singular_point(grid_.cell(c)));
    finish();
    out_.stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return std::move(out_);
  }

 private:
  CurveSamples& samples() { return out_.samples; }

  std::int32_t add(Vec3 x, SampleKind kind) {
    const std::int32_t i = samples().add(x, kind);
    occupancy_->add(x, i);
    return i;
  }

  // A cell of `grid` (the enclosure's grid or a finer one): seed it unless samples already pass
  // through it; bisect it when its seed fails.
  void examine(const CellGrid& grid, const CellIndex& c, int extra) {
    CompileBudget::check();
    const Box3 cell = grid.cell(c);
    if (extra == 0 && occupancy_->occupied(c)) return;
    if (extra > 0 && occupancy_->near(samples().points, cell.center(), 0.5 * grid_.max_edge())) return;
    bool empty = false;
    nearly_flat(cell, empty);
    if (empty) return;  // the second-order model keeps f1 or f2 away from 0 (see nearly_flat)
    Vec3 x = cell.center();
    const double reach = cell.diagonal();
    if (curve::newton_onto_curve(eq_, x) && norm(x - cell.center()) <= reach &&
        box_.contains(x, 1e-12 * std::max(1.0, norm(x)))) {
      if (!occupancy_->near(samples().points, x, 0.5 * settings_.max_step)) seed(x);
      return;
    }
    if (extra >= kExtraLevels) {
      ++out_.stats.unresolved_cells;
      return;
    }
    std::vector<CellIndex> children;
    refine_cell(eq_, grid, c, children, out_.stats.interval_tests);
    const CellGrid fine = grid.refined();
    for (const CellIndex& child : children) examine(fine, child, extra + 1);
  }

  // Singular points are the one place where grad f1 x grad f2 = 0 on the curve, so no cell around
  // them can pass the flatness test at any size. An enclosure cell holding a singular point found
  // by discovery (with a margin of one cell edge) is accepted as is: the point was refined and
  // added explicitly, and the branches through it were traced to it (walks stop there) or seeded
  // from the neighbouring cells.
  bool near_singular_point(const Box3& cell) const {
    const double margin = grid_.max_edge();
    for (std::int32_t i : singular_)
      if (cell.contains(out_.samples.points[static_cast<std::size_t>(i)], margin)) return true;
    return false;
  }

  // The flatness test above, at the cell's centre. `empty` is set when the same second-order model
  // keeps f_i away from 0 over the cell with a wide margin, |f_i(c)| > kModelMargin * (|grad f_i| r +
  // |H_i|_F r^2 / 2), r = diam / 2 (Taylor to second order): interval ranges of long sums
  // overestimate so much that cells next to a near-zero extremum of f are never excluded otherwise.
  bool nearly_flat(const Box3& cell, bool& empty) const {
    const ImplicitJet j = eq_.jet(cell.center());
    const double r = 0.5 * cell.diagonal();
    empty = false;
    for (int i = 0; i < 2; ++i) {
      double h2 = 0.0;
      for (const Vec3& row : j.hess[i]) h2 += norm2(row);
      if (std::fabs(j.f[i]) > kModelMargin * (norm(j.grad[i]) * r + 0.5 * std::sqrt(h2) * r * r))
        empty = true;
    }
    if (empty) return false;
    const double g0 = norm(j.grad[0]), g1 = norm(j.grad[1]);
    if (!(g0 > 0.0 && g1 > 0.0)) return false;
    const double sine = norm(j.tangent()) / (g0 * g1);
    const double diameter = cell.diagonal();
    for (int i = 0; i < 2; ++i) {
      double h2 = 0.0;
      for (const Vec3& row : j.hess[i]) h2 += norm2(row);
      if (!(std::sqrt(h2) * diameter <= kBend * norm(j.grad[i]) * sine)) return false;
    }
    return true;
  }

  // Certifies a kept cell of `grid` (`level` bisections below the enclosure), bisecting it while
  // it fails; certified sub-cells are examined (seeded when no walk passed near). Throws
  // geometry_too_complex when a cell stays uncertified at the finest level or the budget is spent.
  void certify(const CellGrid& grid, const CellIndex& c, int level, bool singular_nearby) {
    CompileBudget::check();
    const Box3 cell = grid.cell(c);
    if (++out_.stats.certification_tests > kCertifyBudget) too_complex();
    bool empty = false;
    if (nearly_flat(cell, empty)) {
      if (level > 0) seed_flat_cell(cell);
      return;
    }
    if (empty) return;
    if (singular_nearby) return;
    if (level >= kCertifyLevels) too_complex();
    std::vector<CellIndex> children;
    refine_cell(eq_, grid, c, children, out_.stats.interval_tests);
    const CellGrid fine = grid.refined();
    for (const CellIndex& child : children) certify(fine, child, level + 1, false);
  }

  // A certified sub-cell: the linear model of f1, f2 is good across it, so Newton from its centre
  // finds the arc inside it when there is one; a cell where it fails holds none.
  void seed_flat_cell(const Box3& cell) {
    if (occupancy_->near(samples().points, cell.center(), 0.5 * grid_.max_edge())) return;
    Vec3 x = cell.center();
    if (curve::newton_onto_curve(eq_, x) && norm(x - cell.center()) <= cell.diagonal() &&
        box_.contains(x, 1e-12 * std::max(1.0, norm(x))) &&
        !occupancy_->near(samples().points, x, 0.5 * settings_.max_step))
      seed(x);
  }

  [[noreturn]] void too_complex() const {
    throw GeometryError("geometry_too_complex", "domain", -1,
                        "the curve is too intricate to resolve in this box (its pieces bend or crowd within "
                        "cells the subdivision budget cannot split further); shrink the box");
  }

  void add_singular_point(Vec3 s) {
    // At a degenerate singular point (a tacnode) Newton stalls where the rounding of grad f
    // swamps it, ~1e-8 from the point; copies closer than 1e-6 are one point.
    const double same = 1e-6 * std::max(1.0, norm(s));
    for (std::int32_t i : singular_)
      if (norm(samples().points[static_cast<std::size_t>(i)] - s) <= same) return;
    singular_.push_back(add(s, SampleKind::singular_point));
    ++out_.stats.singular_points;
  }

  // Appends a walk's points to the samples, linked in walking order after `from`.
  std::int32_t append(std::int32_t from, const std::vector<Vec3>& points) {
    std::int32_t last = from;
    for (const Vec3& x : points) {
      const std::int32_t i = add(x, SampleKind::regular);
      samples().link(last, i);
      last = i;
    }
    return last;
  }

  // A walk that stalled or ran into earlier samples may have stopped next to a singular point: a
  // cusp, or a crossing whose branches come closer than h / 2 (for planar curves the angle between
  // the normals says nothing, grad f2 = e_z), so Newton for a singular point starts at its end.
  void look_for_singular_point(const TraceOutcome& w, Vec3 end) {
    if (w.end != TraceEnd::joined && w.end != TraceEnd::stalled) return;
    Vec3 s = end;
    if (curve::refine_singular_point(eq_, s) && norm(s - end) <= 4.0 * settings_.max_step &&
        box_.contains(s, 1e-12 * std::max(1.0, norm(s))))
      add_singular_point(s);
  }

  // The end of a walk: a face crossing is linked as the last sample, a singular point is kept
  // apart (several branches meet there).
  void finish_end(std::int32_t last, const TraceOutcome& w) {
    for (const Vec3& s : w.singular_points) add_singular_point(s);
    if (w.end == TraceEnd::box_face) {
      const std::int32_t f = add(w.end_point, SampleKind::box_face);
      samples().link(last, f);
      ++out_.stats.face_crossings;
    } else if (w.end == TraceEnd::singular_point) {
      add_singular_point(w.end_point);
    }
  }

  // Traces the curve through the seed x in both directions.
  void seed(Vec3 x) {
    const ImplicitJet j = eq_.jet(x);
    const Vec3 t = curve::unit_tangent(j);
    const double d = norm(j.grad[0]) * norm(j.grad[1]);
    if (!(norm(j.tangent()) > settings_.singular_sine * d)) {
      // The seed sits at (or next to) a singular point: keep the point; branches leaving it are
      // seeded from the neighbouring cells.
      Vec3 s = x;
      if (curve::refine_singular_point(eq_, s)) {
        add_singular_point(s);
        return;
      }
      if (norm2(t) == 0.0) return;
    }
    ++out_.stats.traces;
    const std::int32_t first = add(x, SampleKind::regular);
    const TraceOutcome forward = trace_curve(eq_, box_, x, t, x, settings_, *occupancy_, samples(), first);
    const std::int32_t forward_last = append(first, forward.points);
    if (forward.end == TraceEnd::closed) {
      samples().link(forward_last, first);
      for (const Vec3& s : forward.singular_points) add_singular_point(s);
      return;
    }
    finish_end(forward_last, forward);
    look_for_singular_point(forward, samples().points[static_cast<std::size_t>(forward_last)]);
    // Ran into the end of an earlier walk: link them when that end is free on the matching side.
    if (forward.end == TraceEnd::joined && samples().prev[static_cast<std::size_t>(forward.joined_to)] < 0)
      samples().link(forward_last, forward.joined_to);
    // The other way; on a loop whose first walk stopped early it closes on that walk's end.
    const Vec3 close_on = samples().points[static_cast<std::size_t>(forward_last)];
    const TraceOutcome backward =
        trace_curve(eq_, box_, x, -t, close_on, settings_, *occupancy_, samples(), first);
    // Link the backward points before the seed: walking order reversed.
    std::int32_t after = first;
    for (const Vec3& p : backward.points) {
      const std::int32_t i = add(p, SampleKind::regular);
      samples().link(i, after);
      after = i;
    }
    if (backward.end == TraceEnd::closed && forward.end != TraceEnd::box_face) {
      samples().link(forward_last, after);
      for (const Vec3& s : backward.singular_points) add_singular_point(s);
      return;
    }
    for (const Vec3& s : backward.singular_points) add_singular_point(s);
    look_for_singular_point(backward, samples().points[static_cast<std::size_t>(after)]);
    if (backward.end == TraceEnd::joined && samples().next[static_cast<std::size_t>(backward.joined_to)] < 0)
      samples().link(backward.joined_to, after);
    if (backward.end == TraceEnd::box_face) {
      const std::int32_t f = add(backward.end_point, SampleKind::box_face);
      samples().link(f, after);
      ++out_.stats.face_crossings;
    } else if (backward.end == TraceEnd::singular_point) {
      add_singular_point(backward.end_point);
    }
  }

  // Spacing (largest linked chord, plus the arc's excess over the chord for turns <= max_turn)
  // and scale.
  void finish() {
    CurveSamples& s = samples();
    double longest = 0.0;
    Vec3 lo{}, hi{};
    for (std::size_t i = 0; i < s.size(); ++i) {
      if (s.next[i] >= 0)
        longest = std::max(longest, norm(s.points[static_cast<std::size_t>(s.next[i])] - s.points[i]));
      for (int k = 0; k < 3; ++k) {
        lo[k] = i == 0 ? s.points[i][k] : std::min(lo[k], s.points[i][k]);
        hi[k] = i == 0 ? s.points[i][k] : std::max(hi[k], s.points[i][k]);
      }
    }
    s.spacing = 1.01 * std::max(longest, settings_.max_step);
    out_.scale = std::max(norm(hi - lo), 1e-300);
  }

  const ImplicitEquations& eq_;
  Box3 box_;
  CellGrid grid_;
  TraceSettings settings_;
  std::unique_ptr<SampleGrid> occupancy_;
  std::vector<std::int32_t> singular_;
  CurveDiscovery out_;
};

}  // namespace

CurveDiscovery discover_implicit_curve(const ImplicitEquations& equations, const Box3& box) {
  return Discovery(equations, box).run();
}

}  // namespace footpoint
