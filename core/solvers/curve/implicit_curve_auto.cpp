#include "solvers/curve/implicit_curve_auto.hpp"

#include <algorithm>
#include <cmath>

#include "solvers/curve/auto_result.hpp"
#include "solvers/curve/curve_descent.hpp"
#include "solvers/curve/implicit_curve_certificate.hpp"
#include "solvers/curve/implicit_curve_multiplicity.hpp"
#include "solvers/curve/implicit_curve_summary.hpp"
#include "solvers/curve/lagrange_newton.hpp"

namespace footpoint::curve {
namespace {

struct Found {
  Vec3 x;
  double distance = kInfinity;
  int iterations = 0;
  double step = 0.0;
  bool valid = false;
  bool singular = false;  // a singular point found at discovery
  bool met = false;       // its residuals meet the tolerance
};

// What the search reads: the curve's equations and box, its samples and their k-d tree.
struct Curve {
  const ImplicitEquations& equations;
  const Box3& box;
  const CurveDiscovery& discovery;
  const CurveSampleIndex& index;
};

// The residuals of x, where a singular point found at discovery is one whatever the angle between
// the normals says (planar curves: grad f = 0, but grad f2 = e_z).
void fill_residuals(const Curve& curve, Vec3 p, const Found& f, Summary& s) {
  fill_implicit_residuals(curve.equations, curve.box, p, f.x, s);
  if (f.singular) {
    s.location = Location::singular_point;
    s.orthogonality = {0.0, 0.0};
    s.on_boundary = false;
  }
}

// The local minimum belonging to sample i.
Found solve_from(const Curve& curve, Vec3 p, std::int32_t i, const IterationControl& control,
                 std::vector<std::array<double, 3>>* trace) {
  const CurveSamples& s = curve.discovery.samples;
  const Vec3 start = s.points[static_cast<std::size_t>(i)];
  const double start_distance = norm(p - start);
  Found f;
  const SampleKind kind = s.kind[static_cast<std::size_t>(i)];
  if (kind == SampleKind::box_face || kind == SampleKind::singular_point) {
    f.x = start;
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
  f.distance = norm(p - m.x);
  f.iterations = m.iterations;
  f.step = m.step;
  f.valid = true;
  return f;
}

}  // namespace

namespace {

ProjectionResult search(const ImplicitEquations& eq, const Box3& box, const CurveDiscovery& discovery,
                        const CurveSampleIndex& index, Vec3 p, const Options& options) {
  const Curve curve{eq, box, discovery, index};
  const CurveSamples& s = discovery.samples;
  const double h = s.spacing;
  ProjectionResult r;
  r.dim = eq.planar() ? 2 : 3;
  r.num_params = 0;
  r.summary.method = "auto";
  r.summary.starts = 0;

  // The nearest sample and the candidates in one pass; with all_minima every discrete local
  // minimum of the samples is a candidate, else only those that can hold the nearest point.
  SampleCandidates candidates;
  double d0sq = 0.0;
  const std::int32_t nearest =
      index.nearest_and_local_minima(p, options.all_minima ? kInfinity : 0.5 * h, candidates, d0sq);
  if (nearest < 0) {
    // No point of the curve in the box.
    r.summary.status = Status::degenerate;
    return r;
  }
  const double d0 = std::sqrt(d0sq);
  const Vec3 s0 = s.points[static_cast<std::size_t>(nearest)];
  if (d0 - 0.5 * h > options.max_distance) {
    // Every curve point is farther than max_distance (the h/2 bound).
    r = implicit_result(eq, box, p, s0, "auto");
    withhold_answer(r);
    r.summary.starts = 0;
    return r;
  }
  const IterationControl control = make_control(options, 60, nullptr);
  const double slack = 1e-12 * std::max({1.0, d0, discovery.scale});

  // The nearest candidate whose residuals meet the tolerance, and the nearest of all. A local
  // solve that stopped short of the tolerance (next to a singular point the Lagrange system is
  // singular and the descent stalls in the last digits) loses to a converged candidate at the
  // same distance, e.g. the singular point itself, refined at discovery.
  Found best, best_met;
  std::vector<std::array<double, 3>> trace, best_trace, best_met_trace;
  std::vector<Minimum> minima;
  std::vector<ImplicitMinimum> found;  // every minimum solved, for the multiplicity
  int starts = 0;
  for (int k = 0; k < candidates.count; ++k) {
    const SampleCandidate& c = candidates.items[static_cast<std::size_t>(k)];
    const double dc = std::sqrt(c.distance2);
    // Nothing within h/2 of this sample's stretch of curve can beat the best any more.
    if (!options.all_minima && dc - 0.5 * h > best.distance + slack) break;
    ++starts;
    trace.clear();
    Found f = solve_from(curve, p, c.index, control, options.trace ? &trace : nullptr);
    if (!f.valid) continue;
    Summary fs;
    fill_residuals(curve, p, f, fs);
    f.met = implicit_residuals_met(fs, f.x, control);
    found.push_back({f.x, f.distance});
    if (options.all_minima) {
      add_distinct_minimum(minima, f.x, 1e-8 * std::max(1.0, discovery.scale),
                           {{f.x.x, f.x.y, eq.planar() ? 0.0 : f.x.z}, {0.0, 0.0}, f.distance, fs.location});
    }
    if (f.met && f.distance < best_met.distance) {
      best_met = f;
      if (options.trace) best_met_trace = trace;
    }
    if (f.distance < best.distance) {
      best = f;
      if (options.trace) best_trace.swap(trace);
    }
  }
  if (!best.valid) {
    // No local solve succeeded (should not happen): the nearest sample, not converged.
    r = implicit_result(eq, box, p, s0, "auto");
    r.summary.status = Status::degenerate;
    r.summary.starts = starts;
    return r;
  }
  if (best_met.valid && !(best.distance < best_met.distance - slack)) {
    best = best_met;
    best_trace.swap(best_met_trace);
  }
  r = implicit_result(eq, box, p, best.x, "auto");
  fill_residuals(curve, p, best, r.summary);
  r.summary.multiplicity = implicit_curve_multiplicity(eq, p, r, found);
  // a continuum of nearest points: the answer stands for all of them, no arbitrary sample
  if (r.summary.multiplicity.kind == Multiplicity::continuum)
    minima.assign(1, {r.foot, r.params, r.distance, r.summary.location});
  finish_auto_result(r, best.met, best.iterations, best.step, starts, options, std::move(minima),
                     std::move(best_trace));
  return r;
}

}  // namespace

ProjectionResult implicit_curve_auto(const ImplicitEquations& eq, const Box3& box,
                                     const CurveDiscovery& discovery, const CurveSampleIndex& index, Vec3 p,
                                     const Options& options) {
  ProjectionResult r = search(eq, box, discovery, index, p, options);
  if (options.certify.value_or(true) && std::isfinite(r.distance))
    r.summary.certificate = certify_implicit_curve_answer(
        eq, box, discovery, p, {r.foot[0], r.foot[1], eq.planar() ? 0.0 : r.foot[2]}, r.distance);
  return r;
}

}  // namespace footpoint::curve
