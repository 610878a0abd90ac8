#include "solvers/surface/surface_auto.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "solvers/surface/box_quadratic.hpp"
#include "solvers/surface/projected_newton.hpp"
#include "solvers/surface/surface_convergence.hpp"
#include "solvers/surface/surface_result.hpp"

namespace footpoint::surface {

namespace {

// The Newton model's minimiser is sought over the cell grown by this fraction of its width on
// each side, so that a minimum near a cell's border is claimed by the cells on both sides.
constexpr double kMargin = 0.25;
// Distinct minima (all_minima) have foot points farther apart than this, relative to 1 + |foot|.
constexpr double kDistinctFoot = 1e-8;
// Solutions remembered for rule 4 when not all minima are wanted.
constexpr int kRemembered = 16;
constexpr int kStack = 128;
// Claims of rule 3 remembered to find two cells that claim each other.
constexpr int kClaims = 32;
// Rule 4: a minimum found within this many cell widths of a candidate cell is its minimum (a
// resolved cell's model has one minimum; a second, better one that near would show in it).
constexpr double kSameBasin = 1.0;
// Cells waiting for a local solve (more are solved in batches of this size).
constexpr int kCandidates = 64;

// Which face of the domain a parameter point is on: per parameter -1 (lower bound), +1 (upper),
// 0 (inside). Rule 4 only merges a candidate with a minimum on the same face.
struct Face {
  int u = 0, v = 0;
  bool operator==(const Face&) const = default;
};

Face face_of(const ParamBox& box, double u, double v) {
  return {u <= box.umin ? -1 : (u >= box.umax ? 1 : 0), v <= box.vmin ? -1 : (v >= box.vmax ? 1 : 0)};
}

struct Found {
  LocalSolution sol;
  double u_start = 0.0, v_start = 0.0;
};

class Search {
 public:
  Search(const SurfaceCells& cells, const SurfaceFormulas& formulas, const ParamBox& box, const Vec3& p,
         const Options& options)
      : cells_(cells), formulas_(formulas), box_(box), p_(p), options_(options),
        criteria_(convergence_criteria(options, box, kLocalMaxIterations)),
        bound_(options.max_distance) {
    if (options.all_minima) all_.reserve(8);
  }

  void run() {
    const auto& nodes = cells_.nodes();
    std::int32_t stack[kStack];
    double stack_lb[kStack];
    int top = 0;
    const double root_lb = SurfaceCells::box_distance(nodes[0], p_);
    if (!(root_lb < bound_)) return;
    // the leaf down the nearest boxes first: usually the answer's cell, so that the walk below
    // starts with a tight bound
    first_leaf_ = descend();
    visit(first_leaf_, 0.0);
    stack[top] = 0;
    stack_lb[top++] = root_lb;
    while (top > 0) {
      --top;
      if (!(stack_lb[top] < bound_)) continue;
      const SurfaceCellNode& node = nodes[static_cast<std::size_t>(stack[top])];
      if (node.leaf()) {
        if (node.cell != first_leaf_) visit(node.cell, stack_lb[top]);
        continue;
      }
      const std::int32_t a = node.child[0], b = node.child[1];
      double la = SurfaceCells::box_distance(nodes[static_cast<std::size_t>(a)], p_);
      double lb = SurfaceCells::box_distance(nodes[static_cast<std::size_t>(b)], p_);
      // push the farther child first so that the nearer one is taken next
      std::int32_t first = a, second = b;
      if (la < lb) {
        std::swap(first, second);
        std::swap(la, lb);
      }
      if (top + 2 > kStack) continue;  // cannot happen for trees shallower than kStack / 2
      if (la < bound_) {
        stack[top] = first;
        stack_lb[top++] = la;
      }
      if (lb < bound_) {
        stack[top] = second;
        stack_lb[top++] = lb;
      }
    }
    solve_candidates();
    if (solves_ == 0 && nearest_cell_ >= 0) {
      const SurfaceCell& c = cells_.cells()[static_cast<std::size_t>(nearest_cell_)];
      solve(c.uc(), c.vc());
    }
  }

  ProjectionResult result() {
    ProjectionResult r;
    if (has_best_) {
      const LocalSolution& s = best_.sol;
      r = surface_result("auto", p_, s.u, s.v, s.jet.s, s.jet.su, s.jet.sv, box_);
      r.summary.status = s.status;
      r.summary.iterations = s.iterations;
      r.summary.step_norm = s.step_norm;
      if (!(s.distance <= options_.max_distance)) r.summary.status = Status::beyond_max_distance;
      if (options_.trace) projected_newton(formulas_, box_, p_, best_.u_start, best_.v_start, criteria_, &r.trace);
    } else {
      // No solve: every box is beyond max_distance (or no cell is finite). Report the centre of
      // the cell reached by walking down the nearest boxes, without solving.
      const SurfaceCell& c = cells_.cells()[static_cast<std::size_t>(descend())];
      r = surface_result("auto", p_, c.uc(), c.vc(), c.centre.s, c.centre.su, c.centre.sv, box_);
      r.summary.status = c.finite && options_.max_distance < std::numeric_limits<double>::infinity()
                             ? Status::beyond_max_distance
                             : Status::non_finite;
    }
    r.summary.starts = solves_;
    if (options_.all_minima) r.minima = minima();
    return r;
  }

 private:
  void visit(std::int32_t index, double box_lb) {
    const SurfaceCell& c = cells_.cells()[static_cast<std::size_t>(index)];
    if (!c.finite) return;
    const SurfaceJet& j = c.centre;
    const Vec3 r = j.s - p_;
    const double rr = norm2(r);
    // every cell centre is a point of the surface: an upper bound on the least distance
    const double dc = std::sqrt(rr);
    if (dc < nearest_) {
      nearest_ = dc;
      nearest_cell_ = index;
    }
    if (!options_.all_minima) bound_ = std::min(bound_, dc);

    const double uc = c.uc(), vc = c.vc();
    const double E = dot(j.su, j.su), F = dot(j.su, j.sv), G = dot(j.sv, j.sv);
    BoxQuadratic q;
    q.g = {dot(r, j.su), dot(r, j.sv)};
    // 2. the tangent-plane model: min over the cell of |r + s_u δu + s_v δv|, less ρ
    q.H = {{{E, F}, {F, G}}};
    const BoxMinimum lin = minimize_on_box(q, {c.u0 - uc, c.v0 - vc}, {c.u1 - uc, c.v1 - vc});
    const double lb =
        c.resolved ? std::max(box_lb, std::sqrt(std::max(rr + 2.0 * lin.value, 0.0)) - c.rho) : box_lb;
    if (!(lb < bound_)) return;
    // 3. the Newton model over the grown cell, within the domain
    q.H[0][0] += dot(r, j.suu);
    q.H[0][1] += dot(r, j.suv);
    q.H[1][0] = q.H[0][1];
    q.H[1][1] += dot(r, j.svv);
    // an unresolved cell (the cell budget ran out before its model was good) is searched from
    // its model's minimiser over the cell itself, whatever the model says about its neighbours
    const double margin = c.resolved ? kMargin : 0.0;
    const double mu = margin * (c.u1 - c.u0), mv = margin * (c.v1 - c.v0);
    const double glo[2] = {std::max(c.u0 - mu, box_.umin), std::max(c.v0 - mv, box_.vmin)};
    const double ghi[2] = {std::min(c.u1 + mu, box_.umax), std::min(c.v1 + mv, box_.vmax)};
    const BoxMinimum m = minimize_on_box(q, {glo[0] - uc, glo[1] - vc}, {ghi[0] - uc, ghi[1] - vc});
    const double du = m.delta[0], dv = m.delta[1];
    const Face model_face{m.side[0] < 0 && glo[0] == box_.umin ? -1 : (m.side[0] > 0 && ghi[0] == box_.umax ? 1 : 0),
                          m.side[1] < 0 && glo[1] == box_.vmin ? -1 : (m.side[1] > 0 && ghi[1] == box_.vmax ? 1 : 0)};
    // Rule 3. Next to the domain's boundary the claim is trusted only where the model falls from
    // the cell into the neighbour by more than its own error in f = ½|s - p|^2, about |s - p| ρ2:
    // there a model can miss an edge or corner minimum (far points see a flat landscape). Inside
    // the domain the neighbour's model answers for it.
    const bool on_border = (m.side[0] < 0 && glo[0] > box_.umin) || (m.side[0] > 0 && ghi[0] < box_.umax) ||
                           (m.side[1] < 0 && glo[1] > box_.vmin) || (m.side[1] > 0 && ghi[1] < box_.vmax);
    if (c.resolved && on_border) {
      const bool touches_boundary =
          c.u0 == box_.umin || c.u1 == box_.umax || c.v0 == box_.vmin || c.v1 == box_.vmax;
      if (touches_boundary) {
        const BoxMinimum own = minimize_on_box(q, {c.u0 - uc, c.v0 - vc}, {c.u1 - uc, c.v1 - vc});
        if (!(own.value - m.value > 2.0 * (dc + c.extent) * c.rho2)) {
          add_candidate(c, own.delta[0], own.delta[1], lb,
                        {own.side[0] < 0 && c.u0 == box_.umin ? -1 : (own.side[0] > 0 && c.u1 == box_.umax ? 1 : 0),
                         own.side[1] < 0 && c.v0 == box_.vmin ? -1 : (own.side[1] > 0 && c.v1 == box_.vmax ? 1 : 0)});
          return;
        }
      }
      // Claimed by a neighbour - unless that neighbour claimed this cell: then the minimum lies
      // between them, where neither model is good enough (near folds, where s_u x s_v -> 0).
      const Claim mine{glo[0], ghi[0], glo[1], ghi[1], uc + du, vc + dv};
      for (int i = 0; i < claims_count_; ++i) {
        const Claim& other = claims_[i];
        if (other.grown_contains(mine.u, mine.v) && mine.grown_contains(other.u, other.v)) {
          add_candidate(c, 0.5 * (mine.u + other.u) - uc, 0.5 * (mine.v + other.v) - vc, lb, Face{});
          return;
        }
      }
      if (claims_count_ < kClaims) claims_[claims_count_++] = mine;
      return;
    }
    add_candidate(c, du, dv, lb, model_face);
  }

  // A cell that may hold a better minimum, to be solved from its centre + (du, dv).
  void add_candidate(const SurfaceCell& c, double du, double dv, double lb, Face face) {
    if (!has_best_ && !options_.all_minima) {  // the first one at once: a tight bound for the walk
      solve(std::clamp(c.uc() + du, box_.umin, box_.umax), std::clamp(c.vc() + dv, box_.vmin, box_.vmax));
      if (has_best_) return;
    }
    if (candidates_count_ == kCandidates) solve_candidates();  // rare: solve what we have first
    Candidate& k = candidates_[candidates_count_++];
    const SurfaceJet& j = c.centre;
    const Vec3 foot = j.s + j.su * du + j.sv * dv + 0.5 * (j.suu * (du * du) + 2.0 * j.suv * (du * dv) + j.svv * (dv * dv));
    k.d_model = norm(foot - p_);
    k.lb = lb;
    k.u = std::clamp(c.uc() + du, box_.umin, box_.umax);
    k.v = std::clamp(c.vc() + dv, box_.vmin, box_.vmax);
    k.face = face;
    const double wu = kSameBasin * (c.u1 - c.u0), wv = kSameBasin * (c.v1 - c.v0);
    k.basin = {c.u0 - wu, c.u1 + wu, c.v0 - wv, c.v1 + wv};
    k.resolved = c.resolved;
  }

  // Nearest model foot first; each solve lowers the bound, which drops the candidates whose
  // lower bound it passes, and a candidate next to a minimum already found is that
  // minimum (rule 4: within kSameBasin cells of it).
  void solve_candidates() {
    std::sort(candidates_, candidates_ + candidates_count_,
              [](const Candidate& a, const Candidate& b) { return a.d_model < b.d_model; });
    for (int i = 0; i < candidates_count_; ++i) {
      const Candidate& k = candidates_[i];
      if (!(k.lb < bound_)) continue;
      if (k.resolved) {
        auto same = [&](double u, double v) {
          return u >= k.basin[0] && u <= k.basin[1] && v >= k.basin[2] && v <= k.basin[3] &&
                 face_of(box_, u, v) == k.face;
        };
        bool found = false;
        for (int f = 0; f < feet_count_ && !found; ++f) found = same(feet_[f].u, feet_[f].v);
        for (std::size_t f = 0; f < all_.size() && !found; ++f) found = same(all_[f].sol.u, all_[f].sol.v);
        if (found) continue;
      }
      solve(k.u, k.v);
    }
    candidates_count_ = 0;
  }

  void solve(double u0, double v0) {
    Found f;
    f.u_start = std::clamp(u0, box_.umin, box_.umax);
    f.v_start = std::clamp(v0, box_.vmin, box_.vmax);
    f.sol = projected_newton(formulas_, box_, p_, f.u_start, f.v_start, criteria_);
    ++solves_;
    if (!std::isfinite(f.sol.distance)) return;
    if (options_.all_minima) {
      all_.push_back(f);
    } else {
      feet_[feet_count_ < kRemembered ? feet_count_++ : solves_ % kRemembered] = {f.sol.u, f.sol.v, f.sol.distance};
      bound_ = std::min(bound_, f.sol.distance);
    }
    if (!has_best_ || better(f.sol, best_.sol)) {
      best_ = f;
      has_best_ = true;
    }
  }

  // Smaller distance wins; a converged solution wins a tie with an unconverged one.
  static bool better(const LocalSolution& a, const LocalSolution& b) {
    if (a.distance != b.distance) return a.distance < b.distance;
    return a.status == Status::converged && b.status != Status::converged;
  }

  // Greedy walk to the leaf whose boxes are nearest (no solve): for an answer beyond max_distance.
  std::int32_t descend() const {
    const auto& nodes = cells_.nodes();
    std::size_t k = 0;
    while (!nodes[k].leaf()) {
      const auto a = static_cast<std::size_t>(nodes[k].child[0]), b = static_cast<std::size_t>(nodes[k].child[1]);
      k = SurfaceCells::box_distance(nodes[a], p_) <= SurfaceCells::box_distance(nodes[b], p_) ? a : b;
    }
    return nodes[k].cell;
  }

  std::vector<Minimum> minima() const {
    std::vector<const Found*> order;
    for (const Found& f : all_)
      if (f.sol.status == Status::converged && f.sol.distance <= options_.max_distance) order.push_back(&f);
    std::stable_sort(order.begin(), order.end(),
                     [](const Found* a, const Found* b) { return a->sol.distance < b->sol.distance; });
    std::vector<Minimum> out;
    for (const Found* f : order) {
      const Vec3& s = f->sol.jet.s;
      const double tol = kDistinctFoot * (1.0 + norm(s));
      const bool seen = std::any_of(out.begin(), out.end(), [&](const Minimum& m) {
        return norm2(Vec3{m.foot[0], m.foot[1], m.foot[2]} - s) <= tol * tol;
      });
      if (seen) continue;
      Minimum m;
      m.foot = {s.x, s.y, s.z};
      m.params = {f->sol.u, f->sol.v};
      m.distance = f->sol.distance;
      m.location = location_in(box_, f->sol.u, f->sol.v);
      out.push_back(m);
    }
    return out;
  }

  const SurfaceCells& cells_;
  const SurfaceFormulas& formulas_;
  const ParamBox& box_;
  const Vec3 p_;
  const Options& options_;
  const ConvergenceCriteria criteria_;
  double bound_;
  double nearest_ = std::numeric_limits<double>::infinity();
  std::int32_t nearest_cell_ = -1;
  int solves_ = 0;
  std::int32_t first_leaf_ = -1;
  Found best_;
  bool has_best_ = false;
  // A cell whose model puts the minimum in a neighbour: its grown rectangle and that point.
  struct Claim {
    double u0, u1, v0, v1;
    double u, v;
    bool grown_contains(double x, double y) const { return x >= u0 && x <= u1 && y >= v0 && y <= v1; }
  };
  Claim claims_[kClaims];
  struct Candidate {
    double d_model;             // distance to the model's foot point
    double lb;                  // lower bound (rules 1, 2)
    double u, v;                // start of the local solve
    std::array<double, 4> basin;  // rule 4's region: u0, u1, v0, v1
    Face face;                    // the face the model's minimiser is on
    bool resolved;
  };
  Candidate candidates_[kCandidates];
  int candidates_count_ = 0;
  int claims_count_ = 0;
  struct Foot {
    double u, v, distance;
  };
  Foot feet_[kRemembered];  // minima found (all_minima: all_ has them)
  int feet_count_ = 0;
  std::vector<Found> all_;
};

}  // namespace

ProjectionResult project_auto(const SurfaceCells& cells, const SurfaceFormulas& formulas, const ParamBox& box,
                              const Vec3& p, const Options& options) {
  Search search(cells, formulas, box, p, options);
  search.run();
  return search.result();
}

}  // namespace footpoint::surface
