#include <algorithm>
#include <cmath>
#include <limits>

#include "parametric/solvers/kink_minimum.hpp"
#include "parametric/solvers/surface_search.hpp"

namespace footpoint::surface {

void SurfaceSearch::run() {
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
    // The box rule: a box farther than the best distance known (a solved foot point, or any
    // cell centre: every s(t) bounds the minimum from above) or than options.max_distance holds
    // nothing nearer; skipped with its subtree.
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
    if (corner.finite && (options_.all_minima || norm(corner.jet.s - p_) < answer)) solve(corner.u, corner.v);
  }
  if (nearest_cell_ >= 0 && (!has_best_ || nearest_ < best_.sol.distance)) {
    const SurfaceCell& c = cells_.cells()[static_cast<std::size_t>(nearest_cell_)];
    solve(c.uc(), c.vc());
  }
}

LocalSolution SurfaceSearch::solve_across_seams(double u, double v, std::vector<std::array<double, 3>>* trace,
                                                const EarlyStop* early, const SurfaceJet* start_jet) const {
  LocalSolution s = projected_newton(formulas_, box_, p_, u, v, criteria_, trace, early, start_jet);
  for (int crossing = 0; crossing < kSeamCrossings && !s.abandoned && std::isfinite(s.distance); ++crossing) {
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
  // a solve that ends short of convergence on a kink curve of the formulas: the kink's minimum
  if (!s.abandoned && s.status != Status::converged && std::isfinite(s.distance))
    kink_minimum(formulas_, box_, p_, s);
  return s;
}

void SurfaceSearch::visit(std::int32_t index, double box_lb) {
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
  // The tangent-plane rule: the cell is within its model error ρ of the rectangle in the
  // tangent plane that holds its tangent parallelogram, so that rectangle's distance less ρ is
  // a lower bound, and a cell whose rectangle is at least bound + ρ away needs no more
  // (coordinates of r in the frame e1, e2, n)
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
  // the Newton model (the second-order Taylor expansion of ½|s - p|^2 at the centre) over the
  // cell grown by kMargin, within the domain
  q.H[0][0] += dot(r, j.suu);
  q.H[0][1] += dot(r, j.suv);
  q.H[1][0] = q.H[0][1];
  q.H[1][1] += dot(r, j.svv);
  // an unresolved cell (the cell budget ran out before its model was good) is searched from
  // its model's minimiser over the cell itself, whatever the model says about its neighbours
  const double margin = c.resolved ? kMargin : 0.0;
  const double mu = margin * (c.u1 - c.u0), mv = margin * (c.v1 - c.v0);
  const Params<2> glo{std::max(c.u0 - mu, box_.umin), std::max(c.v0 - mv, box_.vmin)};
  const Params<2> ghi{std::min(c.u1 + mu, box_.umax), std::min(c.v1 + mv, box_.vmax)};
  const BoxMinimum m = minimize_on_box(q, {glo[0] - uc, glo[1] - vc}, {ghi[0] - uc, ghi[1] - vc});
  const double du = m.delta[0], dv = m.delta[1];
  const Face model_face = face_of(box_, m.side, glo, ghi);
  // The claim rule: the model's minimum on the grown cell's border, inside the domain, claims that the
  // distance decreases into a neighbour, whose model answers for this cell. Next to the
  // boundary a model can miss an edge or corner minimum (far points see a flat landscape).
  const bool on_border = (m.side[0] < 0 && glo[0] > box_.umin) || (m.side[0] > 0 && ghi[0] < box_.umax) ||
                         (m.side[1] < 0 && glo[1] > box_.vmin) || (m.side[1] > 0 && ghi[1] < box_.vmax);
  if (c.resolved && on_border) {
    // The claim must beat the model's error in f = ½|s - p|^2, about |s - p| ρ2: the model
    // must fall from the cell into the neighbour by more than that. Else the cell answers for
    // itself, from its model's minimiser over the cell:
    //  - next to the boundary, also from the model's best point on the boundary, on its edge or
    //    corner (the known-minimum rule merges that one only with a minimum found on the same edge or corner,
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

void SurfaceSearch::add_boundary_candidates(const SurfaceCell& c, const BoxQuadratic& q, double lb,
                                            double threshold, Face except) {
  const double uc = c.uc(), vc = c.vc();
  const double lo0 = c.u0 - uc, hi0 = c.u1 - uc, lo1 = c.v0 - vc, hi1 = c.v1 - vc;
  // a side's own face, and the corner where its minimiser is at the side's end on the boundary
  auto side = [&](bool on_boundary, Params<2> lo, Params<2> hi, Face f) {
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

void SurfaceSearch::add_candidate(const SurfaceCell& c, const BoxQuadratic& model, double du, double dv,
                                  double lb, Face face, bool mergeable,
                                  std::optional<std::array<double, 4>> basin) {
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
  // the known-minimum rule's region: around the model's minimiser for a fine cell, the cell itself for a
  // coarse one (its model can put the minimum a cell off, and two minima can lie a cell apart, as near folds
  // where s_u x s_v -> 0)
  const double wu = kSameBasin * (c.u1 - c.u0), wv = kSameBasin * (c.v1 - c.v0);
  k.basin = basin ? *basin
                  : (c.fine ? std::array<double, 4>{k.u - wu, k.u + wu, k.v - wv, k.v + wv}
                            : std::array<double, 4>{c.u0, c.u1, c.v0, c.v1});
  k.mergeable = c.resolved && mergeable;
  candidates_[candidates_count_++] = k;
}

void SurfaceSearch::solve_candidates() {
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

void SurfaceSearch::solve(double u0, double v0, const Candidate* from) {
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
  if (f.sol.abandoned) {  // its predicted minimiser still answers for its basin (known-minimum rule)
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

void SurfaceSearch::record_solution(const LocalSolution& s) {
  Found f;
  f.sol = s;
  f.u_start = s.u;
  f.v_start = s.v;
  if (options_.all_minima) all_.push_back(f);
  if (minimisers_count_ < kMinimisers)
    minimisers_[minimisers_count_++] = {s.u, s.v, s.distance, s.jet.s, s.status == Status::converged};
}

void SurfaceSearch::remember(double u, double v, double distance) {
  if (minimisers_count_ < kMinimisers) minimisers_[minimisers_count_++] = {u, v, distance, Vec3{}, false};
  const int i = feet_count_ < kRemembered ? feet_count_++ : solves_ % kRemembered;
  feet_[i] = {u, v};
  feet_distance_[i] = distance;
}

bool SurfaceSearch::better(const LocalSolution& a, const LocalSolution& b) {
  if (a.distance != b.distance) return a.distance < b.distance;
  return a.status == Status::converged && b.status != Status::converged;
}

std::int32_t SurfaceSearch::descend(PathStep* path, int* path_length) const {
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

}  // namespace footpoint::surface
