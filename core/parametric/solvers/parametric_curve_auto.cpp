#include "parametric/solvers/parametric_curve_auto.hpp"

#include <algorithm>
#include <cmath>

#include "parametric/geometry/box_enclosure.hpp"
#include "parametric/solvers/kink_minimum.hpp"
#include "parametric/solvers/parametric_curve_certificate.hpp"
#include "parametric/solvers/parametric_curve_summary.hpp"
#include "parametric/solvers/parametric_newton.hpp"
#include "solvers/answer_multiplicity.hpp"
#include "solvers/auto_result.hpp"
#include "solvers/iteration_control.hpp"

namespace footpoint::curve {
namespace {

struct Found {
  double t = 0.0;
  double distance = kInfinity;
  int iterations = 0;
  double step = 0.0;
};

// g(t) = <c(t) - p, c'(t)>: the derivative of |c - p|^2 / 2.
double slope(const CurveFormulas& f, Vec3 p, double t) {
  const CurveJet j = f.jet(t);
  return dot(j.c - p, j.d1);
}

// A sign change of g from - to + in [a, b] (where g(a) < 0 and g(b) < 0, or both > 0, although
// the samples say a minimum is near: two extrema between neighbouring samples), by scanning.
bool find_bracket(const CurveFormulas& f, Vec3 p, double& a, double& b) {
  constexpr int kScan = 16;
  double ta = a, ga = slope(f, p, a);
  for (int k = 1; k <= kScan; ++k) {
    const double tb = a + (b - a) * k / kScan;
    const double gb = slope(f, p, tb);
    if (ga <= 0.0 && gb >= 0.0) {
      a = ta;
      b = tb;
      return true;
    }
    ta = tb;
    ga = gb;
  }
  return false;
}

// The local minimum of the distance near sample i (between its neighbours).
Found solve_from(const CurveFormulas& f, const CurveSamples& s, Vec3 p, std::int32_t i,
                 const IterationControl& control) {
  const auto at = [&](std::int32_t k) { return s.params[static_cast<std::size_t>(k)]; };
  const std::int32_t before = s.prev[static_cast<std::size_t>(i)];
  const std::int32_t after = s.next[static_cast<std::size_t>(i)];
  const double ti = at(i);
  Found out;
  // Bracket [a, b] of a minimum: g(a) <= 0 <= g(b).
  double a = ti, b = ti;
  const double gi = slope(f, p, ti);
  if (gi == 0.0) {
    a = b = ti;
  } else if (gi < 0.0) {
    if (after < 0) {  // tmax with g < 0: the minimum is the end itself
      out.t = ti;
      out.distance = norm(p - s.points[static_cast<std::size_t>(i)]);
      return out;
    }
    b = at(after);
    if (slope(f, p, b) < 0.0 && !find_bracket(f, p, a, b)) return out;
  } else {
    if (before < 0) {  // tmin with g > 0
      out.t = ti;
      out.distance = norm(p - s.points[static_cast<std::size_t>(i)]);
      return out;
    }
    a = at(before);
    if (slope(f, p, a) > 0.0 && !find_bracket(f, p, a, b)) return out;
  }
  const double start = (ti >= a && ti <= b) ? ti : 0.5 * (a + b);
  out.t = a == b ? ti : bracketed_newton(f, p, a, b, start, control, out.iterations, out.step);
  out.distance = norm(p - f.point(out.t));
  return out;
}

// The orthogonality residual of an answer at the rounding of its own evaluation: within four
// times the radius of the ball that encloses <p - c(t), c'(t)> (formula/ball.hpp), relative as
// the residual is. Steep formulas (a spike exp(-((t - a)/w)^2) with w small) hold the residual
// above the default tolerance at the last bit of t.
bool at_rounding_level(const CurveFormulas& formulas, Vec3 p, const ProjectionResult& r) {
  if (!(r.distance > 0.0) || r.summary.location != Location::interior) return false;
  const PointEnclosure<1> e = enclose_point<1>(formulas.program(), {r.params[0]});
  if (!e.valid) return false;
  double radius = 0.0;
  for (int k = 0; k < 3; ++k) {
    const double d = p[k] - e.s[k], dr = e.s_rad[k] + 0x1p-53 * std::abs(d);
    radius += std::abs(d) * e.ds_rad[0][k] + dr * std::abs(e.ds[0][k]) + dr * e.ds_rad[0][k];
  }
  const double denominator = r.distance * norm(e.ds[0]);
  return denominator > 0.0 && r.summary.orthogonality[0] <= 4.0 * radius / denominator;
}

}  // namespace

ProjectionResult parametric_curve_auto(const CurveFormulas& formulas, const ParamInterval& domain,
                                       const CurveSampleIndex& index, const ParametricCurveCells& cells,
                                       const CurveClosure& closure, Vec3 p, const Options& options) {
  const CurveSamples& s = index.samples();
  const double h = s.spacing;
  // The nearest sample and the candidates in one pass; with all_minima every discrete local
  // minimum of the samples is a candidate, else only those that can hold the nearest point.
  SampleCandidates candidates;
  double d0sq = 0.0;
  const std::int32_t nearest =
      index.nearest_and_local_minima(p, options.all_minima ? kInfinity : 0.5 * h, candidates, d0sq);
  if (nearest < 0 || !std::isfinite(d0sq)) {
    // no point where the formulas are finite, or p so far out (beyond about 1.3e154) that squared
    // distances overflow: no answer, as on surfaces
    ProjectionResult r;
    r.dim = formulas.dim();
    r.num_params = 1;
    r.summary.method = "auto";
    withhold_answer(r);
    r.summary.status = Status::non_finite;
    r.summary.starts = 0;
    return r;
  }
  const double d0 = std::sqrt(d0sq);
  if (d0 - 0.5 * h > options.max_distance) {
    // every curve point is farther than max_distance (the h/2 bound)
    ProjectionResult r =
        parametric_result(formulas, domain, p, s.params[static_cast<std::size_t>(nearest)], "auto", closure);
    withhold_answer(r);
    r.summary.starts = 0;
    return r;
  }
  std::vector<std::array<double, 3>> trace;
  const IterationControl control = make_control(options, 100, options.trace ? &trace : nullptr);
  const double slack = 1e-12 * std::max(1.0, d0);

  Found best;
  std::vector<double> solved;       // every minimiser found, for the certificate
  std::vector<CurveMinimum> found;  // and their distances, for the multiplicity
  std::vector<std::array<double, 3>> best_trace;
  std::vector<Minimum> minima;
  int starts = 0;
  for (int k = 0; k < candidates.count; ++k) {
    const SampleCandidate& c = candidates.items[static_cast<std::size_t>(k)];
    if (!options.all_minima && std::sqrt(c.distance2) - 0.5 * h > best.distance + slack) break;
    ++starts;
    trace.clear();
    const Found f = solve_from(formulas, s, p, c.index, control);
    if (!(f.distance < kInfinity)) continue;
    solved.push_back(f.t);
    found.push_back({f.t, f.distance});
    if (options.all_minima) {
      const Vec3 x = formulas.point(f.t);
      const bool end = (f.t <= domain.tmin || f.t >= domain.tmax) && !joins_smoothly(closure);
      add_distinct_minimum(minima, x, 1e-8 * std::max(1.0, norm(x)),
                           {{x.x, x.y, x.z},
                            {closed_representative(domain, f.t, closure), 0.0},
                            f.distance,
                            end ? Location::endpoint : Location::interior});
    }
    if (f.distance < best.distance) {
      best = f;
      if (options.trace) best_trace.swap(trace);
    }
  }
  Certificate certificate;
  if (best.distance < kInfinity && options.certify.value_or(true)) {
    const CurveLocalSolve descend = [&](double t0) { return descend_on_interval(formulas, domain, p, t0); };
    const CurveCertification c =
        certify_parametric_curve(cells, formulas, p, {best.t, best.distance}, solved, descend, true);
    certificate = c.certificate;
    if (c.improved) {
      found.push_back(c.better);
      best.t = c.better.t;
      best.distance = c.better.distance;
      best.iterations = 0;
      best.step = 0.0;
    }
  }
  ProjectionResult r = parametric_result(formulas, domain, p, best.t, "auto", closure);
  bool met =
      best.distance < kInfinity && (parametric_residual_met(r, control) || at_rounding_level(formulas, p, r));
  double kink = best.t;
  if (!met && best.distance < kInfinity && r.summary.location == Location::interior &&
      kink_minimum(formulas, p, domain.tmax - domain.tmin, kink) && domain.contains(kink)) {
    r = parametric_result(formulas, domain, p, kink, "auto", closure);
    r.summary.location = Location::kink;
    r.summary.orthogonality[0] = 0.0;  // zero lies between the one-sided slopes
    met = true;
  }
  if (best.distance < kInfinity) {
    // flat to second order (solvers/answer_multiplicity.hpp): φ''(t) = |c'|^2 + <c - p, c''> =
    // |c'|^2 (1 - κ <n, p - c>) vanishes to kFlatMinimum of |c'|^2, p at the centre of the
    // osculating circle. The minima are the local solves' (every sample that could hold the
    // nearest point starts one) and the certificate's; only those that tie have their foot evaluated.
    const auto flat = [&] {
      const CurveJet j = formulas.jet(r.params[0]);
      const double speed2 = dot(j.d1, j.d1);
      return std::abs(speed2 + dot(j.c - p, j.d2)) <= kFlatMinimum * speed2;
    };
    r.summary.multiplicity =
        answer_multiplicity(r, p, flat, found, [&](const CurveMinimum& f) { return formulas.point(f.t); });
    // a continuum of nearest points: the answer stands for all of them, no arbitrary sample
    if (r.summary.multiplicity.kind == Multiplicity::continuum)
      minima.assign(1, {r.foot, r.params, r.distance, r.summary.location});
  }
  finish_auto_result(r, met, best.iterations, best.step, starts, options, std::move(minima),
                     std::move(best_trace));
  r.summary.certificate = certificate;
  return r;
}

}  // namespace footpoint::curve
