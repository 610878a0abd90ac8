#include "parametric/geometry/box_quadratic.hpp"

#include <algorithm>

namespace footpoint {

namespace {
// Minimum over x in [lo, hi] of a x + ½ c x^2.
double minimize_1d(double a, double c, double lo, double hi) {
  if (c > 0.0) return std::clamp(-a / c, lo, hi);
  // concave or linear: an end point
  const double flo = a * lo + 0.5 * c * lo * lo, fhi = a * hi + 0.5 * c * hi * hi;
  return flo <= fhi ? lo : hi;
}

int side_of(double x, double lo, double hi) { return x <= lo ? -1 : (x >= hi ? 1 : 0); }
}  // namespace

BoxMinimum minimize_on_box(const BoxQuadratic& q, const Params<2>& lo, const Params<2>& hi) {
  BoxMinimum best;
  const double a = q.H[0][0], b = q.H[0][1], c = q.H[1][1];
  const double det = a * c - b * b;
  bool first = true;
  auto consider = [&](double d0, double d1) {
    const double f = q.value(d0, d1);
    if (first || f < best.value) {
      first = false;
      best.delta = {d0, d1};
      best.value = f;
    }
  };
  if (a > 0.0 && det > 0.0) {
    const double d0 = (-q.g[0] * c + q.g[1] * b) / det;
    const double d1 = (-q.g[1] * a + q.g[0] * b) / det;
    const bool beyond0 = !(d0 > lo[0] && d0 < hi[0]), beyond1 = !(d1 > lo[1] && d1 < hi[1]);
    if (!beyond0 && !beyond1) {
      best.delta = {d0, d1};
      best.value = q.value(d0, d1);
      return best;
    }
    // H positive definite, its minimiser d outside: the box's minimiser x is on a side that d
    // is beyond. Were x inside a side x1 = hi1 with d1 < hi1, say, then with e = x - d, e1 > 0,
    // the first-order conditions ∂0 = a e0 + b e1 = 0 and ∂1 = b e0 + c e1 <= 0 would give
    // ∂1 = e1 (ac - b^2)/a > 0; were x a corner with d beyond neither of its sides, the outward
    // gradient there would give e^T H e = e·∇f(x) <= 0. Likewise for the other sides.
    if (beyond0) {
      const double d = d0 <= lo[0] ? lo[0] : hi[0];
      consider(d, minimize_1d(q.g[1] + b * d, c, lo[1], hi[1]));
    }
    if (beyond1) {
      const double d = d1 <= lo[1] ? lo[1] : hi[1];
      consider(minimize_1d(q.g[0] + b * d, a, lo[0], hi[0]), d);
    }
  } else {
    // edges δ0 = lo/hi: minimise over δ1 of (g1 + b δ0) δ1 + ½ c δ1^2; likewise for δ1 fixed
    for (double d0 : {lo[0], hi[0]}) consider(d0, minimize_1d(q.g[1] + b * d0, c, lo[1], hi[1]));
    for (double d1 : {lo[1], hi[1]}) consider(minimize_1d(q.g[0] + b * d1, a, lo[0], hi[0]), d1);
  }
  best.side = {side_of(best.delta[0], lo[0], hi[0]), side_of(best.delta[1], lo[1], hi[1])};
  return best;
}

}  // namespace footpoint
