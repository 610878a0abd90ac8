#include "solvers/surface/surface_auto.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

#include "geometry/box_quadratic.hpp"
#include "solvers/surface/projected_newton.hpp"
#include "solvers/surface/surface_certificate.hpp"
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
constexpr int kClaims = 128;
// Rule 4: a minimum found within this many cell widths of where a fine cell's model puts its
// minimum is that minimum (a fine cell's model has one minimum; a second, better one that near
// would show in it). Measured from the model's minimiser, not from the cell: a minimum one cell
// away from one the model sees inside its own cell is another one.
constexpr double kSameBasin = 1.0;
// Cells waiting for a local solve (more are solved in batches of this size).
constexpr int kCandidates = 64;

// Which face of the domain a parameter point is on: per parameter -1 (lower bound), +1 (upper),
// 0 (inside). Rule 4 only merges a candidate with a minimum on the same face.
// (No default member initializers: the search's candidate buffer is left unconstructed until
// used; Face{} is the interior.)
struct Face {
  int u, v;
  bool operator==(const Face&) const = default;
};

// The face of the domain that a box minimum is on: on the side `side` of the rectangle
// [lo, hi] where that side is the domain's bound.
Face face_of(const ParamBox& box, const std::array<int, 2>& side, const std::array<double, 2>& lo,
             const std::array<double, 2>& hi) {
  return {side[0] < 0 && lo[0] == box.umin ? -1 : (side[0] > 0 && hi[0] == box.umax ? 1 : 0),
          side[1] < 0 && lo[1] == box.vmin ? -1 : (side[1] > 0 && hi[1] == box.vmax ? 1 : 0)};
}

Face face_of(const ParamBox& box, double u, double v) {
  return {u <= box.umin ? -1 : (u >= box.umax ? 1 : 0), v <= box.vmin ? -1 : (v >= box.vmax ? 1 : 0)};
}

struct Found {
  LocalSolution sol;
  double u_start = 0.0, v_start = 0.0;
};

class Search {
  struct Candidate;

 public:
  Search(const SurfaceCells& cells, const SurfaceFormulas& formulas, const ParamBox& box,
         const SurfaceClosure& closure, const Vec3& p, const Options& options)
      : cells_(cells),
        formulas_(formulas),
        box_(box),
        closure_(closure),
        p_(p),
        options_(options),
        criteria_(convergence_criteria(options, box, kLocalMaxIterations)),
        bound_(options.max_distance) {
    if (options.all_minima) all_.reserve(8);
  }

  void run() {
    const auto& nodes = cells_.nodes();
    if (!(cells_.root_distance2(p_) < bound_ * bound_)) return;
    // options.initial: a warm start (a neighbour's foot in a sequence of points, as ICP loops
    // send them): its solve's distance bounds the walk from the start, which the global search
    // then does as always
    if (options_.initial) solve((*options_.initial)[0], (*options_.initial)[1]);
    // the leaf down the nearest boxes first: usually the answer's cell, so that the walk below
    // starts with a tight bound
    PathStep path[kStack];
    int path_length = 0, path_next = 0;
    const std::int32_t first_cell = descend(path, &path_length);
    visit(first_cell, 0.0);
    // depth first, nearest child first; squared box distances (no square roots in the walk).
    // An entry is a node (>= 0) or the leaf of cell ~entry, with its squared box distance.
    constexpr int W = SurfaceCellNode::kWidth;
    std::int32_t stack[kStack];
    double stack_lb2[kStack];
    int top = 0;
    if (!nodes.empty()) {
      stack[top] = 0;
      stack_lb2[top++] = 0.0;
    }
    while (top > 0) {
      --top;
      const double bound2 = bound_ * bound_;
      if (!(stack_lb2[top] < bound2)) continue;
      if (stack[top] < 0) {
        if (~stack[top] != first_cell) visit(~stack[top], std::sqrt(stack_lb2[top]));
        continue;
      }
      const SurfaceCellNode& node = nodes[static_cast<std::size_t>(stack[top])];
      // the nodes of the first path come in the same order (ancestors first): reuse their
      // children's distances
      double d2[W];
      if (path_next < path_length && path[path_next].node == stack[top]) {
        for (int k = 0; k < W; ++k) d2[k] = path[path_next].d2[k];
        ++path_next;
      } else {
        SurfaceCells::box_distances2(node, p_, d2);
      }
      // the children within the bound, pushed farthest first so that the nearest is taken next
      int order[W], n = 0;
      for (int k = 0; k < node.children; ++k) {
        if (!(d2[k] < bound2)) continue;
        int i = n++;
        for (; i > 0 && d2[order[i - 1]] < d2[k]; --i) order[i] = order[i - 1];
        order[i] = k;
      }
      if (top + n > kStack) continue;  // cannot happen: the tree is at most 24 nodes deep
      for (int i = 0; i < n; ++i) {
        stack[top] = node.child[order[i]];
        stack_lb2[top++] = d2[order[i]];
      }
    }
    solve_candidates();
    // Every point of the surface evaluated bounds the minimum from above. One nearer than the
    // answer means its basin was lost to a model's error: a domain corner next to an edge
    // minimum within the corner cell's model error, or a cell centre. It starts one more solve.
    // (all_minima solves from every corner: each may be a minimum of its own.)
    for (const SurfaceCorner& corner : cells_.corners()) {
      const double answer = has_best_ ? best_.sol.distance : std::min(nearest_, options_.max_distance);
      if (corner.finite && (options_.all_minima || norm(corner.jet.s - p_) < answer))
        solve(corner.u, corner.v);
    }
    if (nearest_cell_ >= 0 && (!has_best_ || nearest_ < best_.sol.distance)) {
      const SurfaceCell& c = cells_.cells()[static_cast<std::size_t>(nearest_cell_)];
      solve(c.uc(), c.vc());
    }
  }

  ProjectionResult result() {
    ProjectionResult r;
    const bool within = has_best_ && best_.sol.distance <= options_.max_distance;
    if (within) {
      r = answer(best_.sol);
      if (options_.trace) solve_across_seams(best_.u_start, best_.v_start, &r.trace);
    } else {
      r = no_answer();
    }
    r.summary.starts = solves_;
    if (options_.certify.value_or(true) && (within || r.summary.status == Status::beyond_max_distance))
      certify(r, within);
    if (std::isfinite(r.distance)) r.summary.multiplicity = multiplicity(r);
    if (options_.all_minima) r.minima = minima(r, &r.minima_truncated);
    return r;
  }

 private:
  // The local solve (solvers/surface/projected_newton.hpp) on the surface rather than on its
  // parameter box: a solve that stops on a bound of a closed direction because the distance still
  // decreases across it (the gradient <s - p, s_u> of ½|s - p|^2 points out of the box, by more
  // than rounding) goes on from the opposite bound, the same points of the surface
  // (geometry/surface_closure.hpp); at most kSeamCrossings times.
  LocalSolution solve_across_seams(double u, double v, std::vector<std::array<double, 3>>* trace = nullptr,
                                   const EarlyStop* early = nullptr,
                                   const SurfaceJet* start_jet = nullptr) const {
    LocalSolution s = projected_newton(formulas_, box_, p_, u, v, criteria_, trace, early, start_jet);
    for (int crossing = 0; crossing < kSeamCrossings && !s.abandoned && std::isfinite(s.distance);
         ++crossing) {
      const Vec3 d = s.jet.s - p_;
      auto across = [&](int k, double t, double lo, double hi, const Vec3& tangent) {
        if (!closure_.periodic(k)) return t;
        const double slope = dot(d, tangent), size = kSeamSlope * norm(d) * norm(tangent);
        if (t == lo && slope > size) return hi;  // s comes nearer as t decreases below lo
        if (t == hi && slope < -size) return lo;
        return t;
      };
      const double nu = across(0, s.u, box_.umin, box_.umax, s.jet.su);
      const double nv = across(1, s.v, box_.vmin, box_.vmax, s.jet.sv);
      if (nu == s.u && nv == s.v) break;
      LocalSolution t = projected_newton(formulas_, box_, p_, nu, nv, criteria_, trace, early);
      if (t.abandoned) return t;
      if (!(t.distance <= s.distance)) break;
      s = t;
    }
    return s;
  }
  static constexpr int kSeamCrossings = 4;
  static constexpr double kSeamSlope = 1e-10;

  // The result at a local solve's minimiser.
  ProjectionResult answer(const LocalSolution& s) const {
    ProjectionResult r = surface_result("auto", p_, s.u, s.v, s.jet.s, s.jet.su, s.jet.sv, box_, &closure_);
    r.summary.status = s.status;
    r.summary.iterations = s.iterations;
    r.summary.step_norm = s.step_norm;
    return r;
  }

  // No point of the surface within options.max_distance (or none finite): no foot point,
  // parameters or distance (null in JSON), never an intermediate point.
  ProjectionResult no_answer() const {
    constexpr double nan = std::numeric_limits<double>::quiet_NaN();
    ProjectionResult r;
    r.dim = 3;
    r.num_params = 2;
    r.foot = {nan, nan, nan};
    r.params = {nan, nan};
    r.summary.method = "auto";
    r.summary.location = Location::unknown;
    const bool some_finite = std::any_of(cells_.cells().begin(), cells_.cells().end(),
                                         [](const SurfaceCell& c) { return c.finite; });
    r.summary.status = some_finite && std::isfinite(options_.max_distance) ? Status::beyond_max_distance
                                                                           : Status::non_finite;
    return r;
  }

 private:
  // The certificate of the answer (solvers/surface/surface_certificate.hpp), from every minimiser
  // the search found; where it finds a nearer minimum (the search's estimates lost its basin), that
  // one is the answer. Without an answer within options.max_distance, the certificate proves that
  // none is nearer than it (a lower bound of at least max_distance, to the gap) - or finds one.
  void certify(ProjectionResult& r, bool within) {
    // the minimisers at the answer's distance (its copies on a periodic or folded
    // parametrisation: each needs its own bound) and near it
    std::vector<std::array<double, 2>> known;
    LocalSolution target;
    if (within) {
      target = best_.sol;
    } else {  // the point of the surface at max_distance to certify against: none nearer
      const SurfaceCell& c = cells_.cells()[static_cast<std::size_t>(descend())];
      target.u = c.uc();
      target.v = c.vc();
      target.jet = c.centre;
      target.distance = options_.max_distance;
    }
    const double near_best = target.distance * (1.0 + 1e-6) + 1e-12;
    for (int i = 0; i < minimisers_count_; ++i)
      if (minimisers_[i].distance <= near_best) known.push_back({minimisers_[i].u, minimisers_[i].v});
    for (const Found& f : all_)
      if (f.sol.distance <= near_best) known.push_back({f.sol.u, f.sol.v});
    const SurfaceLocalSolve solve = [&](double u, double v) { return solve_across_seams(u, v); };
    const SurfaceCertification c = certify_surface(cells_, formulas_, box_, p_, target, known, solve, true);
    if (c.improved && c.better.distance <= options_.max_distance) {
      const int starts = r.summary.starts;
      r = answer(c.better);
      r.summary.starts = starts;
      record_solution(c.better);
    }
    r.summary.certificate = c.certificate;
  }

  // How many feet are nearest (geometry/projection_result.hpp): a continuum where the Hessian of
  // f = ½|s - p|^2 at the answer, over the parameters free there, is singular to rounding (a
  // direction along which the distance stays); else the distinct feet among the minima solved to
  // the end at the answer's distance within the certificate's gap.
  AnswerMultiplicity multiplicity(const ProjectionResult& r) const {
    AnswerMultiplicity m;
    m.computed = true;
    const double u = r.params[0], v = r.params[1];
    const SurfaceJet j = formulas_.jet(u, v);
    const Vec3 d = j.s - p_;
    const double h[2][2] = {{dot(j.su, j.su) + dot(d, j.suu), dot(j.su, j.sv) + dot(d, j.suv)},
                            {dot(j.su, j.sv) + dot(d, j.suv), dot(j.sv, j.sv) + dot(d, j.svv)}};
    // a parameter on a bound that is no seam is held there; at a pole every parameter along the
    // pole gives the one foot (not a continuum in space)
    const bool free_u = !((u == box_.umin || u == box_.umax) && !closure_.periodic(0));
    const bool free_v = !((v == box_.vmin || v == box_.vmax) && !closure_.periodic(1));
    const bool pole = r.summary.location == Location::pole;
    const double scale = std::abs(h[0][0]) + std::abs(h[1][1]) + 2.0 * std::abs(h[0][1]) + 1e-300;
    double smallest = scale;
    if (free_u && free_v) {
      const double a = h[0][0], b = h[0][1], c = h[1][1];
      smallest = 0.5 * (a + c) - std::sqrt(0.25 * (a - c) * (a - c) + b * b);
    } else if (free_u) {
      smallest = h[0][0];
    } else if (free_v) {
      smallest = h[1][1];
    }
    if (!pole && smallest <= 1e-8 * scale && r.distance > 0.0) {
      m.kind = Multiplicity::continuum;
      return m;
    }
    const double gap =
        std::fmax(Certificate::kRelativeGap * r.distance, Certificate::absolute_gap_at(p_, j.s));
    m.feet.push_back(r.foot);
    auto consider = [&](const Vec3& foot, double distance) {
      if (!(std::abs(distance - r.distance) <= gap)) return;
      const double same = kDistinctFoot * (1.0 + norm(foot));
      for (const auto& f : m.feet)
        if (norm2(Vec3{f[0], f[1], f[2]} - foot) <= same * same) return;
      m.feet.push_back({foot.x, foot.y, foot.z});
    };
    for (int i = 0; i < minimisers_count_; ++i) {
      const Minimiser& m = minimisers_[i];
      if (m.complete) {
        consider(m.foot, m.distance);
      } else if (m.distance <= r.distance + gap) {
        // a basin left early whose lower bound does not exclude a tie: solved to the end
        const LocalSolution t = solve_across_seams(m.u, m.v);
        if (t.status == Status::converged) consider(t.jet.s, t.distance);
      }
    }
    for (const Found& f : all_) consider(f.sol.jet.s, f.sol.distance);
    m.count = static_cast<int>(m.feet.size());
    if (m.count > 1) {
      m.kind = Multiplicity::tied;
    } else {
      m.feet.clear();
    }
    return m;
  }

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
    // 2. the rectangle in the tangent plane that holds the tangent parallelogram (rule 2's
    //    model): the cell is within ρ of it, so its distance less ρ is a lower bound, and a cell
    //    whose rectangle is at least bound + ρ away needs no more (coordinates of r in the frame
    //    e1, e2, n)
    double lb = box_lb;
    if (c.resolved && c.framed) {
      const double out1 = std::max(std::abs(dot(r, c.e1)) - c.half1, 0.0);
      const double out2 = std::max(std::abs(dot(r, c.e2)) - c.half2, 0.0);
      const double h = dot(r, c.unit_normal), reach = bound_ + c.rho;
      const double rect2 = h * h + out1 * out1 + out2 * out2;
      if (std::isfinite(reach) && rect2 >= reach * reach) return;
      lb = std::max(box_lb, std::sqrt(rect2) - c.rho);
    }
    if (!(lb < bound_)) return;
    const double uc = c.uc(), vc = c.vc();
    BoxQuadratic q;
    q.g = {dot(r, j.su), dot(r, j.sv)};
    q.H = {{{c.E, c.F}, {c.F, c.G}}};
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
    const Face model_face = face_of(box_, m.side, {glo[0], glo[1]}, {ghi[0], ghi[1]});
    // Rule 3: the model's minimum on the grown cell's border, inside the domain, claims that the
    // distance decreases into a neighbour, whose model answers for this cell. Next to the
    // boundary a model can miss an edge or corner minimum (far points see a flat landscape).
    const bool on_border = (m.side[0] < 0 && glo[0] > box_.umin) || (m.side[0] > 0 && ghi[0] < box_.umax) ||
                           (m.side[1] < 0 && glo[1] > box_.vmin) || (m.side[1] > 0 && ghi[1] < box_.vmax);
    if (c.resolved && on_border) {
      // The claim must beat the model's error in f = ½|s - p|^2, about |s - p| ρ2: the model
      // must fall from the cell into the neighbour by more than that. Else the cell answers for
      // itself, from its model's minimiser over the cell:
      //  - next to the boundary, also from the model's best point on the boundary, on its edge or
      //    corner (rule 4 merges that one only with a minimum found on the same edge or corner,
      //    never with the interior minimum the claim points to; a coarse cell's are not merged at
      //    all);
      //  - inside the domain, when the cell may hold a point nearer than the best known (f is at
      //    least ½|r|^2 + the model's least value over the cell - its error): a claim the model
      //    cannot back can point past a minimum in the cell itself - next to a fold, or for a
      //    point nearer the surface than the model's error, where claims can lead from the
      //    nearest minimum to a worse one, or into a neighbour no nearer than the best and so
      //    never visited. A coarse cell's candidate is merged with a minimum found in the grown
      //    cell (where the claim points), no farther than the model's foot.
      const bool touches_boundary =
          c.u0 == box_.umin || c.u1 == box_.umax || c.v0 == box_.vmin || c.v1 == box_.vmax;
      const double model_error = 2.0 * (dc + c.extent) * c.rho2;
      const double lo0 = c.u0 - uc, hi0 = c.u1 - uc, lo1 = c.v0 - vc, hi1 = c.v1 - vc;
      const BoxMinimum own = minimize_on_box(q, {lo0, lo1}, {hi0, hi1});
      if (!(own.value - m.value > model_error)) {
        const Face own_face = face_of(box_, own.side, {c.u0, c.v0}, {c.u1, c.v1});
        if (touches_boundary) {
          add_candidate(c, q, own.delta[0], own.delta[1], lb, own_face, c.fine);
          add_boundary_candidates(c, q, lb, m.value + model_error, own_face);
          return;
        }
        if (rr + 2.0 * (own.value - model_error) < bound_ * bound_) {
          const auto grown = std::array<double, 4>{glo[0], ghi[0], glo[1], ghi[1]};
          add_candidate(c, q, own.delta[0], own.delta[1], lb, own_face, true,
                        c.fine ? std::nullopt : std::optional{grown});
          return;
        }
      }
      // Claimed by a neighbour - unless that neighbour claimed this cell: then the minimum lies
      // between them, where neither model is good enough (near folds, where s_u x s_v -> 0).
      const Claim mine{glo[0], ghi[0], glo[1], ghi[1], uc + du, vc + dv};
      for (int i = 0; i < claims_count_; ++i) {
        const Claim& other = claims_[i];
        if (other.grown_contains(mine.u, mine.v) && mine.grown_contains(other.u, other.v)) {
          add_candidate(c, q, 0.5 * (mine.u + other.u) - uc, 0.5 * (mine.v + other.v) - vc, lb, Face{});
          return;
        }
      }
      if (claims_count_ == kClaims) {  // no room to check it against later claims: a candidate
        add_candidate(c, q, du, dv, lb, model_face);
        return;
      }
      claims_[claims_count_++] = mine;
      return;
    }
    add_candidate(c, q, du, dv, lb, model_face);
    // A cell on the boundary can hold minima on its sides (an edge minimum next to an interior
    // one, an edge minimum and a corner, two edges of a corner cell) that its model cannot tell
    // apart: every side whose model value is within the model's error of the model's minimum is a
    // candidate too - every side of an unresolved cell, whose model error is not known.
    if (c.u0 == box_.umin || c.u1 == box_.umax || c.v0 == box_.vmin || c.v1 == box_.vmax)
      add_boundary_candidates(
          c, q, lb,
          c.resolved ? m.value + 2.0 * (dc + c.extent) * c.rho2 : std::numeric_limits<double>::infinity(),
          model_face);
  }

  // Candidates at the model's best point on each of the cell's sides on the domain's boundary
  // whose model value is at most `threshold`, other than on `except` (a candidate already).
  void add_boundary_candidates(const SurfaceCell& c, const BoxQuadratic& q, double lb, double threshold,
                               Face except) {
    const double uc = c.uc(), vc = c.vc();
    const double lo0 = c.u0 - uc, hi0 = c.u1 - uc, lo1 = c.v0 - vc, hi1 = c.v1 - vc;
    // a side's own face, and the corner where its minimiser is at the side's end on the boundary
    auto side = [&](bool on_boundary, std::array<double, 2> lo, std::array<double, 2> hi, Face f) {
      if (!on_boundary) return;
      const BoxMinimum e = minimize_on_box(q, lo, hi);
      if (!(e.value <= threshold)) return;
      const Face at = face_of(box_, e.side, {c.u0, c.v0}, {c.u1, c.v1});
      if (f.u == 0) f.u = at.u;
      if (f.v == 0) f.v = at.v;
      if (f == except) return;
      add_candidate(c, q, e.delta[0], e.delta[1], lb, f, c.fine);
    };
    side(c.u0 == box_.umin, {lo0, lo1}, {lo0, hi1}, {-1, 0});
    side(c.u1 == box_.umax, {hi0, lo1}, {hi0, hi1}, {1, 0});
    side(c.v0 == box_.vmin, {lo0, lo1}, {hi0, lo1}, {0, -1});
    side(c.v1 == box_.vmax, {lo0, hi1}, {hi0, hi1}, {0, 1});
  }

  // A cell that may hold a better minimum, to be solved from its centre + (du, dv); `model` is
  // its Newton model (its Hessian at the centre starts the early stop's Lipschitz estimate).
  // Rule 4 may merge it with a minimum found nearby if the cell is resolved and `mergeable`;
  // `basin`, when given, is where (else around the model's minimiser, or the coarse cell itself).
  void add_candidate(const SurfaceCell& c, const BoxQuadratic& model, double du, double dv, double lb,
                     Face face, bool mergeable = true,
                     std::optional<std::array<double, 4>> basin = std::nullopt) {
    Candidate k;
    k.reference_t = {c.uc(), c.vc()};
    k.reference_H = {model.H[0][0], model.H[0][1], model.H[1][1]};
    if (!has_best_ && !options_.all_minima) {  // the first one at once: a tight bound for the walk
      k.u = std::clamp(c.uc() + du, box_.umin, box_.umax);
      k.v = std::clamp(c.vc() + dv, box_.vmin, box_.vmax);
      solve(k.u, k.v, &k);
      if (has_best_) return;
    }
    if (candidates_count_ == kCandidates) solve_candidates();  // rare: solve what we have first
    k.d_model = norm(taylor_point(c.centre, du, dv) - p_);
    k.lb = lb;
    k.u = std::clamp(c.uc() + du, box_.umin, box_.umax);
    k.v = std::clamp(c.vc() + dv, box_.vmin, box_.vmax);

    k.face = face;
    // rule 4's region: around the model's minimiser for a fine cell, the cell itself for a coarse
    // one (its model can put the minimum a cell off, and two minima can lie a cell apart, as near
    // folds where s_u x s_v -> 0)
    const double wu = kSameBasin * (c.u1 - c.u0), wv = kSameBasin * (c.v1 - c.v0);
    k.basin = basin ? *basin
                    : (c.fine ? std::array<double, 4>{k.u - wu, k.u + wu, k.v - wv, k.v + wv}
                              : std::array<double, 4>{c.u0, c.u1, c.v0, c.v1});
    k.mergeable = c.resolved && mergeable;
    candidates_[candidates_count_++] = k;
  }

  // Nearest model foot first; each solve lowers the bound, which drops the candidates whose
  // lower bound it passes, and a candidate next to a minimum already found is that minimum
  // (rule 4: within kSameBasin cells of a fine cell's model minimiser, inside a coarse cell). The
  // others are solved, and stop early once their basin is shown to be a known minimiser's
  // (solvers/surface/projected_newton.hpp).
  void solve_candidates() {
    std::sort(candidates_, candidates_ + candidates_count_,
              [](const Candidate& a, const Candidate& b) { return a.d_model < b.d_model; });
    for (int i = 0; i < candidates_count_; ++i) {
      const Candidate& k = candidates_[i];
      if (!(k.lb < bound_)) continue;
      if (k.mergeable) {
        // merged only with a minimum no farther than the model's foot: a farther one may be
        // another, however near - where the model's error is not small next to the distance
        // (near folds, points very near the surface) a fine cell can hold a second minimum a
        // cell from the first, and a coarse one two; the solve of a copy stops early (it is
        // in a known minimiser's basin)
        auto same = [&](double u, double v, double distance) {
          return u >= k.basin[0] && u <= k.basin[1] && v >= k.basin[2] && v <= k.basin[3] &&
                 face_of(box_, u, v) == k.face && distance <= k.d_model;
        };
        bool found = false;
        for (int f = 0; f < feet_count_ && !found; ++f)
          found = same(feet_[f][0], feet_[f][1], feet_distance_[f]);
        for (std::size_t f = 0; f < all_.size() && !found; ++f)
          found = same(all_[f].sol.u, all_[f].sol.v, all_[f].sol.distance);
        if (found) continue;
      }
      solve(k.u, k.v, &k);
    }
    candidates_count_ = 0;
  }

  // A local solve from (u0, v0); `from` (a candidate) gives the early stop its reference point.
  void solve(double u0, double v0, const Candidate* from = nullptr) {
    Found f;
    f.u_start = std::clamp(u0, box_.umin, box_.umax);
    f.v_start = std::clamp(v0, box_.vmin, box_.vmax);
    // A solve stops early once its basin is shown to be a known minimiser's, or - a minimum being
    // known - to hold nothing nearer (a copy of the best foot, or a worse local minimum);
    // all_minima wants every minimum, so no cutoff there.
    EarlyStop early;
    early.cutoff =
        has_best_ && !options_.all_minima ? best_.sol.distance : std::numeric_limits<double>::infinity();
    early.minimisers = feet_;
    early.minimiser_count = feet_count_;
    if (from) {
      early.reference_t = from->reference_t;
      early.reference_H = from->reference_H;
    }
    // a domain corner's jet is known (the search's candidates are clamped onto the corners exactly)
    const SurfaceJet* start_jet = nullptr;
    for (const SurfaceCorner& corner : cells_.corners())
      if (corner.u == f.u_start && corner.v == f.v_start) start_jet = &corner.jet;
    f.sol = solve_across_seams(f.u_start, f.v_start, nullptr, &early, start_jet);
    ++solves_;
    if (f.sol.abandoned) {  // its predicted minimiser still answers for its basin (rule 4)
      if (std::isfinite(f.sol.distance)) remember(f.sol.u, f.sol.v, f.sol.distance);
      return;
    }
    if (!std::isfinite(f.sol.distance)) return;
    remember(f.sol.u, f.sol.v, f.sol.distance);
    if (minimisers_count_ > 0 && f.sol.status == Status::converged) {
      minimisers_[minimisers_count_ - 1].foot = f.sol.jet.s;
      minimisers_[minimisers_count_ - 1].complete = true;
    }
    if (options_.all_minima) {
      all_.push_back(f);
    } else {
      bound_ = std::min(bound_, f.sol.distance);
    }
    if (!has_best_ || better(f.sol, best_.sol)) {
      best_ = f;
      has_best_ = true;
    }
  }

  // A minimum the certificate found: among the minima for the multiplicity and all_minima.
  void record_solution(const LocalSolution& s) {
    Found f;
    f.sol = s;
    f.u_start = s.u;
    f.v_start = s.v;
    if (options_.all_minima) all_.push_back(f);
    if (minimisers_count_ < kMinimisers)
      minimisers_[minimisers_count_++] = {s.u, s.v, s.distance, s.jet.s, s.status == Status::converged};
  }

  void remember(double u, double v, double distance) {
    if (minimisers_count_ < kMinimisers) minimisers_[minimisers_count_++] = {u, v, distance, Vec3{}, false};
    const int i = feet_count_ < kRemembered ? feet_count_++ : solves_ % kRemembered;
    feet_[i] = {u, v};
    feet_distance_[i] = distance;
  }

  // Smaller distance wins; a converged solution wins a tie with an unconverged one.
  static bool better(const LocalSolution& a, const LocalSolution& b) {
    if (a.distance != b.distance) return a.distance < b.distance;
    return a.status == Status::converged && b.status != Status::converged;
  }

  // Greedy walk to the leaf whose boxes are nearest (no solve): the first cell visited, and the
  // answer beyond max_distance. With `path`, records the nodes passed and their children's
  // squared box distances, which the walk reuses.
  struct PathStep {
    std::int32_t node;
    double d2[SurfaceCellNode::kWidth];
  };
  std::int32_t descend(PathStep* path = nullptr, int* path_length = nullptr) const {
    const auto& nodes = cells_.nodes();
    int n = 0;
    std::int32_t k = 0;
    if (nodes.empty()) k = ~0;  // a single cell
    while (k >= 0) {
      const SurfaceCellNode& node = nodes[static_cast<std::size_t>(k)];
      double d2[SurfaceCellNode::kWidth];
      SurfaceCells::box_distances2(node, p_, d2);
      if (path && n < kStack) {
        path[n].node = k;
        for (int i = 0; i < SurfaceCellNode::kWidth; ++i) path[n].d2[i] = d2[i];
        ++n;
      }
      int nearest = 0;
      for (int i = 1; i < node.children; ++i)
        if (d2[i] < d2[nearest]) nearest = i;
      k = node.child[nearest];
    }
    if (path_length) *path_length = n;
    return ~k;
  }

  // Every distinct minimum found within max_distance, best first, at most options.max_minima
  // (*truncated when more were found); a continuum at the answer's distance is its one
  // representative, the answer.
  std::vector<Minimum> minima(const ProjectionResult& r, bool* truncated) const {
    std::vector<const Found*> order;
    for (const Found& f : all_)
      if (f.sol.status == Status::converged && f.sol.distance <= options_.max_distance) order.push_back(&f);
    std::stable_sort(order.begin(), order.end(),
                     [](const Found* a, const Found* b) { return a->sol.distance < b->sol.distance; });
    const bool continuum = r.summary.multiplicity.kind == Multiplicity::continuum;
    const double gap = std::fmax(Certificate::kRelativeGap * r.distance,
                                 Certificate::absolute_gap_at(p_, Vec3{r.foot[0], r.foot[1], r.foot[2]}));
    const std::size_t cap =
        static_cast<std::size_t>(options_.max_minima > 0 ? options_.max_minima : Options::kDefaultMaxMinima);
    std::vector<Minimum> out;
    *truncated = false;
    if (continuum) {
      Minimum m;
      m.foot = r.foot;
      m.params = r.params;
      m.distance = r.distance;
      m.location = r.summary.location;
      out.push_back(m);
    }
    for (const Found* f : order) {
      const Vec3& s = f->sol.jet.s;
      if (continuum && std::abs(f->sol.distance - r.distance) <= gap) continue;
      const double tol = kDistinctFoot * (1.0 + norm(s));
      const bool seen = std::any_of(out.begin(), out.end(), [&](const Minimum& m) {
        return norm2(Vec3{m.foot[0], m.foot[1], m.foot[2]} - s) <= tol * tol;
      });
      if (seen) continue;
      if (out.size() == cap) {
        *truncated = true;
        break;
      }
      Minimum m;
      m.foot = {s.x, s.y, s.z};
      m.params = {f->sol.u, f->sol.v};
      m.distance = f->sol.distance;
      m.location = location_in(box_, f->sol.u, f->sol.v, &closure_);
      out.push_back(m);
    }
    return out;
  }

  const SurfaceCells& cells_;
  const SurfaceFormulas& formulas_;
  const ParamBox& box_;
  const SurfaceClosure& closure_;
  const Vec3 p_;
  const Options& options_;
  const ConvergenceCriteria criteria_;
  double bound_;
  double nearest_ = std::numeric_limits<double>::infinity();
  std::int32_t nearest_cell_ = -1;
  int solves_ = 0;
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
    double d_model;                     // distance to the model's foot point
    double lb;                          // lower bound (rules 1, 2)
    double u, v;                        // start of the local solve
    std::array<double, 4> basin;        // rule 4's region: u0, u1, v0, v1
    Face face;                          // the face the model's minimiser is on
    bool mergeable;                     // rule 4 applies
    std::array<double, 2> reference_t;  // the cell's centre and the Newton model's Hessian there
    std::array<double, 3> reference_H;
  };
  Candidate candidates_[kCandidates];
  int candidates_count_ = 0;
  int claims_count_ = 0;
  std::array<double, 2> feet_[kRemembered];  // minimisers found (all_minima: all_ has all of them)
  double feet_distance_[kRemembered];        // and their distances (abandoned: lower bounds)
  int feet_count_ = 0;
  std::vector<Found> all_;
  // every minimiser found (u, v, distance; abandoned solves: the predicted minimiser and a lower
  // bound), for the certificate
  static constexpr int kMinimisers = 64;
  struct Minimiser {
    double u, v, distance;
    Vec3 foot;      // when complete
    bool complete;  // solved to the end (not abandoned early)
  };
  Minimiser minimisers_[kMinimisers];
  int minimisers_count_ = 0;
};

}  // namespace

ProjectionResult project_auto(const SurfaceCells& cells, const SurfaceFormulas& formulas, const ParamBox& box,
                              const SurfaceClosure& closure, const Vec3& p, const Options& options) {
  Search search(cells, formulas, box, closure, p, options);
  search.run();
  return search.result();
}

}  // namespace footpoint::surface
