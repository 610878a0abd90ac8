#include "parametric/geometry/curve_closure.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "formula/interval.hpp"
#include "geometry/geometry_error.hpp"
#include "parametric/geometry/closure_sampling.hpp"

namespace footpoint {

namespace {

// Unit tangents of the two ends differing by more than this make a corner.
constexpr double kTangentMismatch = 1e-6;

Vec3 unit_or_zero(Vec3 v) {
  const double length = norm(v);
  return length > 0.0 && std::isfinite(length) ? v / length : Vec3{};
}

// A rigorous bound of |c(b) - c(a)|: the largest distance between the enclosures of c at a and b.
double gap_bound(const CurveFormulas& formulas, double a, double b) {
  const int dim = formulas.dim();
  formula::Interval ta{a, a}, tb{b, b}, ca[3], cb[3];
  formulas.program().intervals(&ta, ca);
  formulas.program().intervals(&tb, cb);
  double far[3] = {0.0, 0.0, 0.0};
  for (int c = 0; c < dim; ++c) {
    for (const formula::Interval& x : {ca[c], cb[c]})
      if (x.partial || !(std::isfinite(x.lo) && std::isfinite(x.hi)))
        return std::numeric_limits<double>::infinity();
    far[c] = std::max(closure_sampling::difference_bound(ca[c].hi, cb[c].lo),
                      closure_sampling::difference_bound(cb[c].hi, ca[c].lo));
  }
  return closure_sampling::norm_bound(far[0], far[1], far[2]);
}

}  // namespace

CurveClosure detect_curve_closure(const CurveFormulas& formulas, const ParamInterval& domain,
                                  bool declared_periodic) {
  CurveClosure closure;
  closure_sampling::Extent extent;
  double speed = 0.0;
  for (double t : closure_sampling::samples(domain.tmin, domain.tmax)) {
    const CurveJet j = formulas.jet(t);
    if (!is_finite(j.c)) continue;
    extent.add(j.c);
    if (is_finite(j.d1)) speed = std::max(speed, norm(j.d1));
  }
  const double t_magnitude = std::max(std::abs(domain.tmin), std::abs(domain.tmax));
  closure.tolerance = closure_sampling::rounding_tolerance(extent.magnitude + speed * t_magnitude);
  const CurveJet first = formulas.jet(domain.tmin), last = formulas.jet(domain.tmax);
  const bool defined = is_finite(first.c) && is_finite(last.c);
  closure.gap = defined ? norm(last.c - first.c) : std::numeric_limits<double>::infinity();
  closure.closed = defined && closure.gap <= closure.tolerance && std::isfinite(closure.tolerance);
  if (declared_periodic) {
    const double limit = closure_sampling::declared_limit(closure.tolerance, extent.size());
    if (!closure.closed && !(closure.gap <= limit && std::isfinite(limit)))
      throw GeometryError(
          "not_periodic", "periodic", -1,
          "t is declared periodic, but " +
              (defined ? "the ends c(tmin) and c(tmax) are " + closure_sampling::format(closure.gap) +
                             " apart (a periodic curve needs them within " + closure_sampling::format(limit) +
                             ", 1e-6 of the curve's size " + closure_sampling::format(extent.size()) + ")"
                       : std::string("the formulas are not defined at both ends")));
    closure.closed = closure.declared = true;
  }
  if (!closure.closed) return closure;
  const Vec3 a = unit_or_zero(first.d1), b = unit_or_zero(last.d1);
  closure.smooth = norm2(a) > 0.0 && norm2(b) > 0.0 && norm(a - b) <= kTangentMismatch;
  closure.gap_bound = gap_bound(formulas, domain.tmin, domain.tmax);
  return closure;
}

}  // namespace footpoint
