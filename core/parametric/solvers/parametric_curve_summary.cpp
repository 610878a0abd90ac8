#include "parametric/solvers/parametric_curve_summary.hpp"

#include <algorithm>
#include <cmath>

namespace footpoint::curve {

ProjectionResult parametric_result(const CurveFormulas& formulas, const ParamInterval& domain, Vec3 p,
                                   double t, const char* method, const CurveClosure& closure) {
  const CurveJet j = formulas.jet(t);
  ProjectionResult r;
  r.dim = formulas.dim();
  r.num_params = 1;
  r.foot = {j.c.x, j.c.y, j.c.z};
  r.params = {closed_representative(domain, t, closure), 0.0};
  r.distance = norm(p - j.c);
  r.summary.method = method;
  const double speed = norm(j.d1);
  const Vec3 d = p - j.c;
  if (!(speed > 0.0)) {
    // c'(t) = 0: a stationary point of the parametrisation (a cusp); no tangent to be orthogonal to.
    r.summary.location = Location::singular_point;
    return r;
  }
  const double denominator = std::max(norm(d), 1e-3 * std::max(1.0, norm(j.c))) * speed;
  const double along = dot(d, j.d1);  // <p - c, c'>
  // An end of the domain (unless the curve closes smoothly there), or of the part of it where
  // the formulas are finite: the next double beyond t gives no point (sqrt(t - 0.5) at 0.5).
  const bool domain_end = (t <= domain.tmin || t >= domain.tmax) && !joins_smoothly(closure);
  const bool lower_end = (t <= domain.tmin && domain_end) ||
                         (t > domain.tmin && !is_finite(formulas.point(std::nextafter(t, -kInfinity))));
  const bool upper_end = (t >= domain.tmax && domain_end) ||
                         (t < domain.tmax && !is_finite(formulas.point(std::nextafter(t, kInfinity))));
  if (lower_end || upper_end) {
    // At a lower end the admissible direction is +c'; a minimum there needs <p - c, c'> <= 0
    // (moving inwards does not approach p), at an upper end <p - c, c'> >= 0. Only a violation is
    // a residual.
    r.summary.orthogonality[0] = (lower_end ? std::max(0.0, along) : std::max(0.0, -along)) / denominator;
    r.summary.location = Location::endpoint;
    r.summary.on_boundary = true;
  } else {
    r.summary.orthogonality[0] = std::fabs(along) / denominator;
    r.summary.location = Location::interior;
  }
  return r;
}

bool parametric_residual_met(const ProjectionResult& r, const IterationControl& control) {
  return r.summary.orthogonality[0] <= control.residual_tolerance;
}

double parametric_start(const ParamInterval& domain, const CurveSampleIndex& index, Vec3 p,
                        const Options& options) {
  if (options.initial) return (*options.initial)[0];
  double d2 = 0.0;
  const std::int32_t i = index.nearest(p, d2);
  return i >= 0 ? index.samples().params[static_cast<std::size_t>(i)] : 0.5 * (domain.tmin + domain.tmax);
}

ProjectionResult finish_parametric_result(const CurveFormulas& formulas, const ParamInterval& domain, Vec3 p,
                                          double t, const char* method, Status status, int iterations,
                                          double step, const IterationControl& control,
                                          std::vector<std::array<double, 3>> trace) {
  ProjectionResult r = parametric_result(formulas, domain, p, t, method);
  r.summary.iterations = iterations;
  r.summary.step_norm = step;
  if (status == Status::converged) {
    if (!domain.contains(t))
      status = Status::outside_domain;
    else if (!parametric_residual_met(r, control))
      status = Status::degenerate;
  }
  r.summary.status = within_max_distance(status, r.distance, control);
  r.trace = std::move(trace);
  return r;
}

}  // namespace footpoint::curve
