#include "implicit/solvers/implicit_curve_auto.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "implicit/geometry/implicit_curve_differentials.hpp"
#include "implicit/solvers/curve_descent.hpp"
#include "implicit/solvers/foot_refinement.hpp"
#include "implicit/solvers/implicit_curve_certificate.hpp"
#include "implicit/solvers/implicit_curve_summary.hpp"
#include "implicit/solvers/lagrange_newton.hpp"
#include "solvers/answer_multiplicity.hpp"
#include "solvers/auto_result.hpp"

namespace footpoint::curve {
namespace {

struct Found {
  Vec3 x;
  double distance = kInfinity;
  int iterations = 0;
  double step = 0.0;
  bool valid = false;
  bool singular = false;     // a singular point found at discovery
  bool met = false;          // its residuals meet the tolerance
  std::int32_t sample = -1;  // the sample it was solved from
  ImplicitJet jet;           // at x
  Summary residuals;         // at x for p (fill_residuals)
};

// What the search reads: the curve's equations and box, its samples and their k-d tree.
struct Curve {
  const ImplicitEquations& equations;
  const Box3& box;
  const CurveDiscovery& discovery;
  const CurveSampleIndex& index;
};

// Residuals at a singular point: no orthogonality to measure, not on a face.
void mark_singular(Summary& s) {
  s.location = Location::singular_point;
  s.orthogonality = {0.0, 0.0};
  s.on_boundary = false;
}

// The residuals of f.x from its jets, where a singular point found at discovery is one whatever
// the angle between the normals says (planar curves: grad f = 0, but grad f2 = e_z).
void fill_residuals(const ImplicitEquations& equations, const Box3& box, Vec3 p, Found& f) {
  fill_implicit_residuals(f.jet, equations.planar(), box, p, f.x, f.residuals);
  if (f.singular) mark_singular(f.residuals);
}

// The local minimum belonging to sample i.
Found solve_from(const Curve& curve, Vec3 p, std::int32_t i, const IterationControl& control,
                 std::vector<std::array<double, 3>>* trace) {
  const CurveSamples& s = curve.discovery.samples;
  const Vec3 start = s.points[static_cast<std::size_t>(i)];
  const double start_distance = norm(p - start);
  Found f;
  f.sample = i;
  const SampleKind kind = s.kind[static_cast<std::size_t>(i)];
  if (kind == SampleKind::box_face || kind == SampleKind::singular_point) {
    f.x = start;
    f.jet = curve.equations.jet(start);
    f.distance = start_distance;
    f.valid = true;
    f.singular = kind == SampleKind::singular_point;
    // A singular point is its own answer. A box-face crossing is one too, but the distance may
    // still fall along the curve into the box, to a minimum nearer than the next sample inside
    // (which then is no candidate of its own): a local solve from the crossing finds it.
    if (kind == SampleKind::singular_point) return f;
  }
  const Box3& box = curve.box;
  const double h = s.spacing;
  IterationControl c = control;
  c.trace = trace;
  // Accept a minimum inside the box, no farther than the start (it belongs to this sample's
  // basin), with non-negative second variation along the curve.
  const double slack = 1e-12 * std::max({1.0, norm(start), start_distance});
  auto acceptable = [&](const LocalMinimum& m) {
    return m.converged && box.contains(m.x, slack) && norm(p - m.x) <= start_distance + slack &&
           m.second_variation >= -1e-9 * std::max(1.0, start_distance);
  };
  LocalMinimum m = lagrange_newton(curve.equations, p, start, 2.0 * h, c);
  if (!acceptable(m)) {
    if (trace) trace->clear();
    m = curve_descent(curve.equations, p, start, h, c);
    if (!acceptable(m)) return f;
  }
  if (f.valid && !(norm(p - m.x) < f.distance - slack)) {
    if (trace) trace->clear();
    return f;  // the crossing stays the answer
  }
  f.x = m.x;
  f.jet = m.jet;
  f.distance = norm(p - m.x);
  f.iterations = m.iterations;
  f.step = m.step;
  f.valid = true;
  return f;
}

// The factor curves in order of their distance bounds from p (ties in the order given), without
// storage: the next after (bound, index) `after` is the least greater one. -1 when none is left.
std::ptrdiff_t next_factor(std::span<const DiscoveredCurve* const> factors, Vec3 p, double after_bound,
                           std::ptrdiff_t after, double& bound) {
  std::ptrdiff_t next = -1;
  for (std::ptrdiff_t i = 0; i < std::ssize(factors); ++i) {
    const double b = factors[static_cast<std::size_t>(i)]->distance_lower_bound(p);
    const bool later = b > after_bound || (b == after_bound && i > after);
    if (later && (next < 0 || b < bound)) {
      next = i;
      bound = b;
    }
  }
  return next;
}

// True when x, within d of p, lies on another factor curve than `on` to the tolerance of its
// residuals: a point where two factor curves meet is a singular point of their union.
bool on_another_factor(std::span<const DiscoveredCurve* const> factors, const DiscoveredCurve* on, Vec3 p,
                       Vec3 x, double d, const Box3& box, const IterationControl& control) {
  for (const DiscoveredCurve* f : factors) {
    if (f == on || f->distance_lower_bound(p) > d) continue;
    Summary other;
    fill_implicit_residuals(f->equations, box, p, x, other);
    if (implicit_residuals_met(other, x, control, false)) return true;
  }
  return false;
}

ProjectionResult search(std::span<const DiscoveredCurve* const> factors, const Box3& box, Vec3 p,
                        const Options& options) {
  ProjectionResult r;
  r.dim = factors.front()->equations.planar() ? 2 : 3;
  r.num_params = 0;
  r.summary.method = "auto";
  r.summary.starts = 0;

  const IterationControl control = make_control(options, 60, nullptr);
  double scale = 0.0;
  for (const DiscoveredCurve* f : factors) scale = std::max(scale, f->discovery.scale);
  double slack = -1.0;  // set by the first factor curve's nearest sample

  // The nearest candidate whose residuals meet the tolerance, and the nearest of all. A local
  // solve that stopped short of the tolerance (next to a singular point the Lagrange system is
  // singular and the descent stalls in the last digits) loses to a converged candidate at the
  // same distance, e.g. the singular point itself, refined at discovery.
  Found best, best_met;
  const DiscoveredCurve *best_on = nullptr, *best_met_on = nullptr;
  std::vector<std::array<double, 3>> trace, best_trace, best_met_trace;
  std::vector<Minimum> minima;
  std::vector<ReachedFoot> found;  // every minimum solved, for the multiplicity
  int starts = 0;
  // The sample with the least bound d0 - h/2 of the distance to its stretch of curve.
  const DiscoveredCurve* lowest_on = nullptr;
  Vec3 lowest_sample;
  double lowest = kInfinity;
  // The factor curves nearest first by the boxes that hold them: once a minimum is found, a factor
  // curve whose box is farther holds no nearer point (factor curves with no point in the box have
  // no box and no part here).
  double bound = -kInfinity;
  for (std::ptrdiff_t i = -1; (i = next_factor(factors, p, bound, i, bound)) >= 0;) {
    if (!options.all_minima && bound > best.distance + std::max(slack, 0.0)) break;
    const DiscoveredCurve* f = factors[static_cast<std::size_t>(i)];
    const Curve curve{f->equations, box, f->discovery, f->index};
    const CurveSamples& s = f->discovery.samples;
    const double h = s.spacing;
    // The nearest sample and the candidates in one pass; with all_minima every discrete local
    // minimum of the samples is a candidate, else only those that can hold the nearest point.
    SampleCandidates candidates;
    double d0sq = 0.0;
    const std::int32_t nearest =
        f->index.nearest_and_local_minima(p, options.all_minima ? kInfinity : 0.5 * h, candidates, d0sq);
    if (nearest < 0) continue;
    const double d0 = std::sqrt(d0sq);
    if (slack < 0.0) slack = 1e-12 * std::max({1.0, d0, scale});
    if (d0 - 0.5 * h < lowest) {
      lowest = d0 - 0.5 * h;
      lowest_on = f;
      lowest_sample = s.points[static_cast<std::size_t>(nearest)];
    }
    // Every point of this curve is farther than max_distance (the h/2 bound).
    if (d0 - 0.5 * h > options.max_distance) continue;
    for (int k = 0; k < candidates.count; ++k) {
      const SampleCandidate& c = candidates.items[static_cast<std::size_t>(k)];
      const double dc = std::sqrt(c.distance2);
      // Nothing within h/2 of this sample's stretch of curve can beat the best any more.
      if (!options.all_minima && dc - 0.5 * h > best.distance + slack) break;
      ++starts;
      trace.clear();
      Found fd = solve_from(curve, p, c.index, control, options.trace ? &trace : nullptr);
      if (!fd.valid) continue;
      fill_residuals(curve.equations, box, p, fd);
      const Summary& fs = fd.residuals;
      fd.met = implicit_residuals_met(fs, fd.x, control);
      found.push_back({fd.x, fd.distance});
      if (options.all_minima) {
        add_distinct_minimum(minima, fd.x, 1e-8 * std::max(1.0, scale),
                             {{fd.x.x, fd.x.y, curve.equations.planar() ? 0.0 : fd.x.z},
                              {0.0, 0.0},
                              fd.distance,
                              fs.location});
      }
      if (fd.met && fd.distance < best_met.distance) {
        best_met = fd;
        best_met_on = f;
        if (options.trace) best_met_trace = trace;
      }
      if (fd.distance < best.distance) {
        best = fd;
        best_on = f;
        if (options.trace) best_trace.swap(trace);
      }
    }
  }
  if (!lowest_on) {
    // No point of the curve in the box.
    r.summary.status = Status::degenerate;
    return r;
  }
  if (!best.valid && lowest > options.max_distance) {
    // Every curve point is farther than max_distance (the h/2 bound).
    r = implicit_result(lowest_on->equations, box, p, lowest_sample, "auto");
    withhold_answer(r);
    r.summary.starts = 0;
    return r;
  }
  if (!best.valid) {
    // No local solve succeeded (should not happen): the nearest sample, not converged.
    r = implicit_result(lowest_on->equations, box, p, lowest_sample, "auto");
    r.summary.status = Status::degenerate;
    r.summary.starts = starts;
    return r;
  }
  if (best_met.valid && !(best.distance < best_met.distance - slack)) {
    best = best_met;
    best_on = best_met_on;
    best_trace.swap(best_met_trace);
  }
  // Where the surfaces are nearly tangent (at the sample it was solved from, an angle below twice
  // the refinement's), the foot refined to its coordinates' rounding (foot_refinement); a foot on
  // a face of the box (or next to one) stays as it is.
  if (!best.singular && best_on->sines[static_cast<std::size_t>(best.sample)] < 2.0 * kRefineSine) {
    const double margin = 1e-9 * (1.0 + norm(best.x));
    Vec3 x = best.x;
    if (box.contains(best.x, -margin) && refine_foot(best_on->equations, p, x) && box.contains(x, -margin)) {
      best.x = x;
      best.jet = best_on->equations.jet(x);
      best.distance = norm(p - x);
      fill_residuals(best_on->equations, box, p, best);
    }
  }
  if (factors.size() > 1 &&
      on_another_factor(factors, best_on, p, best.x, best.distance + slack, box, control)) {
    best.singular = true;
    mark_singular(best.residuals);
  }
  r = implicit_result(best_on->equations.planar(), p, best.x, "auto", best.residuals);
  // flat to second order (solvers/answer_multiplicity.hpp): with the arc length s, the unit
  // tangent T and the curvature vector κ of [Curve] eq. (16), φ(s) = ½|X(s) - p|^2 has
  // φ'' = <T, T> + <κ, X - p> = 1 + <κ, X - p>, which vanishes when p is the centre of the
  // osculating circle: the centre of a circle, or a point of a sphere's and a plane's circle of
  // intersection's axis. The search solves every sample's minimum that may beat the best by the
  // samples' bound, so a tie within the gap is among `found`.
  const auto flat = [&] {
    Vec3 kappa;
    return curvature_vector(best.jet, kappa) &&
           std::abs(1.0 + dot(kappa, Vec3{r.foot[0], r.foot[1], r.foot[2]} - p)) <= kFlatMinimum;
  };
  r.summary.multiplicity =
      answer_multiplicity(r, p, flat, found, [](const ReachedFoot& f) { return f.foot; });
  // a continuum of nearest points: the answer stands for all of them, no arbitrary sample
  if (r.summary.multiplicity.kind == Multiplicity::continuum)
    minima.assign(1, {r.foot, r.params, r.distance, r.summary.location});
  finish_auto_result(r, best.met, best.iterations, best.step, starts, options, std::move(minima),
                     std::move(best_trace));
  return r;
}

}  // namespace

ProjectionResult implicit_curve_auto(std::span<const DiscoveredCurve* const> factors, const Box3& box, Vec3 p,
                                     const Options& options) {
  ProjectionResult r = search(factors, box, p, options);
  if (options.certify.value_or(true) && std::isfinite(r.distance))
    r.summary.certificate = certify_implicit_curve_answer(
        factors, box, p, {r.foot[0], r.foot[1], r.dim == 2 ? 0.0 : r.foot[2]}, r.distance);
  return r;
}

}  // namespace footpoint::curve
