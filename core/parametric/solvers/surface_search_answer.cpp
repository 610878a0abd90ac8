#include <algorithm>
#include <cmath>
#include <limits>

#include "parametric/solvers/surface_certificate.hpp"
#include "parametric/solvers/surface_result.hpp"
#include "parametric/solvers/surface_search.hpp"
#include "solvers/answer_multiplicity.hpp"

namespace footpoint::surface {

ProjectionResult SurfaceSearch::result() {
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

ProjectionResult SurfaceSearch::answer(const LocalSolution& s) const {
  ProjectionResult r = surface_result("auto", p_, s.u, s.v, s.jet.s, s.jet.su, s.jet.sv, box_, &closure_);
  r.summary.status = s.status;
  r.summary.iterations = s.iterations;
  r.summary.step_norm = s.step_norm;
  if (s.kink) {
    // on an edge or at a corner the location stays that
    if (!r.summary.on_boundary) r.summary.location = Location::kink;
    // zero lies in the hull of the one-sided gradients (plus the box's normal cone)
    r.summary.orthogonality = {0.0, 0.0};
  }
  return r;
}

ProjectionResult SurfaceSearch::no_answer() const {
  ProjectionResult r;
  r.dim = 3;
  r.num_params = 2;
  r.summary.method = "auto";
  withhold_answer(r);
  const bool some_finite = std::any_of(cells_.cells().begin(), cells_.cells().end(),
                                       [](const SurfaceCell& c) { return c.finite; });
  if (!(some_finite && std::isfinite(options_.max_distance))) r.summary.status = Status::non_finite;
  return r;
}

void SurfaceSearch::certify(ProjectionResult& r, bool within) {
  // the minimisers at the answer's distance (its copies on a periodic or folded
  // parametrisation: each needs its own bound) and near it
  std::vector<Params<2>> known;
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
  SurfaceCertifyOptions certify_options;
  certify_options.threshold = !within;
  const SurfaceCertification c =
      certify_surface(cells_, formulas_, box_, p_, target, known, solve, true, certify_options);
  if (c.improved && c.better.distance <= options_.max_distance) {
    const int starts = r.summary.starts;
    r = answer(c.better);
    r.summary.starts = starts;
    record_solution(c.better);
  }
  r.summary.certificate = c.certificate;
}

AnswerMultiplicity SurfaceSearch::multiplicity(const ProjectionResult& r) const {
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
  if (!pole && smallest <= kFlatMinimum * scale && r.distance > 0.0) {
    AnswerMultiplicity m;
    m.computed = true;
    m.kind = Multiplicity::continuum;
    return m;
  }
  TiedFeet ties(r, p_, j.s);
  auto consider = [&](const Vec3& foot, double distance) {
    if (ties.ties(distance)) ties.add(foot);
  };
  for (int i = 0; i < minimisers_count_; ++i) {
    const Minimiser& k = minimisers_[i];
    if (k.complete) {
      consider(k.foot, k.distance);
    } else if (k.distance <= r.distance + ties.gap()) {
      // A basin left early whose lower bound does not exclude a tie: solved to the end, unless
      // its predicted minimiser is a copy of a foot already listed (a periodic or self-covering
      // parametrisation reaches one foot from many (u, v)): the prediction is Newton's from 1-3
      // steps, within kCopyOfFoot of its minimiser's foot, where distinct tied feet are far apart.
      const Vec3 predicted = formulas_.point(k.u, k.v);
      const double near = kCopyOfFoot * (1.0 + norm(predicted));
      const bool copy =
          std::any_of(ties.feet().begin(), ties.feet().end(), [&](const std::array<double, 3>& f) {
            return norm2(Vec3{f[0], f[1], f[2]} - predicted) <= near * near;
          });
      if (copy) continue;
      const LocalSolution t = solve_across_seams(k.u, k.v);
      if (t.status == Status::converged) consider(t.jet.s, t.distance);
    }
  }
  for (const Found& f : all_) consider(f.sol.jet.s, f.sol.distance);
  return ties.settle();
}

std::vector<Params<2>> SurfaceSearch::parameter_copies(std::vector<Params<2>> seeds, bool* truncated) const {
  // A seam's two edges are one curve: (umin, v) is (umax, v), or (umax, vmin + vmax - v) reversed.
  const std::size_t solved = seeds.size();
  for (std::size_t i = 0; i < solved; ++i) {
    for (int d = 0; d < 2; ++d) {
      const SurfaceSeam& seam = closure_.seams[static_cast<std::size_t>(d)];
      if (!seam.closed) continue;
      const double lo = d == 0 ? box_.umin : box_.vmin, hi = d == 0 ? box_.umax : box_.vmax;
      const double olo = d == 0 ? box_.vmin : box_.umin, ohi = d == 0 ? box_.vmax : box_.umax;
      const double tol = 1e-9 * (1.0 + std::abs(lo) + std::abs(hi));
      Params<2> t = seeds[i];
      double& x = t[static_cast<std::size_t>(d)];
      double& y = t[static_cast<std::size_t>(1 - d)];
      if (std::abs(x - lo) <= tol) {
        x = hi;
      } else if (std::abs(x - hi) <= tol) {
        x = lo;
      } else {
        continue;
      }
      if (seam.reversed) y = olo + ohi - y;
      seeds.push_back(t);
    }
  }
  return cells_.covering().copies(box_, seeds, options_.minima_cap(), truncated);
}

std::vector<Minimum> SurfaceSearch::minima(const ProjectionResult& r, bool* truncated) const {
  std::vector<const Found*> order;
  for (const Found& f : all_)
    if (f.sol.status == Status::converged && f.sol.distance <= options_.max_distance) order.push_back(&f);
  std::stable_sort(order.begin(), order.end(),
                   [](const Found* a, const Found* b) { return a->sol.distance < b->sol.distance; });
  const bool continuum = r.summary.multiplicity.kind == Multiplicity::continuum;
  const double gap = std::fmax(Certificate::kRelativeGap * r.distance,
                               Certificate::absolute_gap_at(p_, Vec3{r.foot[0], r.foot[1], r.foot[2]}));
  const std::size_t cap = options_.minima_cap();
  std::vector<Minimum> out;
  // the parameters solved for each entry of out: its copies' seeds
  std::vector<std::vector<Params<2>>> solved;
  *truncated = false;
  if (continuum) {
    Minimum m;
    m.foot = r.foot;
    m.params = r.params;
    m.distance = r.distance;
    m.location = r.summary.location;
    out.push_back(m);
    solved.push_back({r.params});
  }
  for (const Found* f : order) {
    const Vec3& s = f->sol.jet.s;
    if (continuum && std::abs(f->sol.distance - r.distance) <= gap) continue;
    const double tol = kDistinctFoot * (1.0 + norm(s));
    const auto same = std::find_if(out.begin(), out.end(), [&](const Minimum& m) {
      return norm2(Vec3{m.foot[0], m.foot[1], m.foot[2]} - s) <= tol * tol;
    });
    if (same != out.end()) {
      solved[static_cast<std::size_t>(same - out.begin())].push_back({f->sol.u, f->sol.v});
      continue;
    }
    if (out.size() == cap) {
      *truncated = true;
      continue;  // the listed minima may still gain copies
    }
    Minimum m;
    m.foot = {s.x, s.y, s.z};
    m.params = seam_representative(box_, f->sol.u, f->sol.v, &closure_);
    m.distance = f->sol.distance;
    m.location = location_in(box_, f->sol.u, f->sol.v, &closure_);
    out.push_back(m);
    solved.push_back({m.params});
  }
  // A pole's parameters are the whole edge: its entry names one.
  for (std::size_t i = 0; i < out.size(); ++i)
    if (out[i].location != Location::pole)
      out[i].copies = parameter_copies(solved[i], &out[i].copies_truncated);
  return out;
}

}  // namespace footpoint::surface
