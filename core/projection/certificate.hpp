// The proof that comes with an answer: a rigorous lower bound L on the distance from p to the
// geometry over its whole closed domain, and whether it meets the answer's distance d.
//
// L is computed with outward-rounded interval arithmetic on the compiled formulas (interval
// values and jets over parameter or space boxes, formula/interval_jet.hpp) plus explicit bounds
// on the floating-point rounding of the point evaluations it combines them with: no point of the
// geometry is nearer to p than L. Every exclusion the search makes is such a bound; sampled
// estimates only order the search.
//
// certified is true when d - L <= max(kRelativeGap d, absolute_gap): kRelativeGap = 1e-9, and
// absolute_gap a few hundred units in the last place of the coordinates involved (|p| and the
// size of the geometry near the foot point): the rounding level at which a distance of ~0 (p on
// the geometry) can be resolved at all. An answer whose search ran out of budget, or met a part
// of the domain where the formulas are not finite, is still answered, with certified = false,
// the best L reached and the reason.
#pragma once
#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/vec.hpp"

namespace footpoint {

enum class CertificateReason {
  gap_met,           // certified: d - L within the gap
  budget_exhausted,  // the search's box budget ran out before every part was bounded near d
  non_finite,        // a part of the domain where the formulas are not finite (or not defined)
                     // could not be bounded
  singular,          // a singular point's enclosure is too large to bound the distance near d
  nearer_point,      // certifying a given answer (a local method's): a point of the geometry nearer
                     // than it by more than the gap was found - it is no global minimum
  not_requested,     // certification was not asked for (a local method without options.certify)
};
const char* to_string(CertificateReason r);

struct Certificate {
  static constexpr double kRelativeGap = 1e-9;
  bool computed = false;      // false: no certificate (serialized as null)
  bool certified = false;     // d - lower_bound <= the gap
  double lower_bound = 0.0;   // rigorous: no point of the geometry is nearer than this
  double absolute_gap = 0.0;  // the gap allowed at d ~ 0 (see above)
  CertificateReason reason = CertificateReason::not_requested;
  int boxes = 0;  // parameter (or space) boxes bounded for this point beyond the compiled cells

  // The absolute gap for an answer at `foot`: 512 u (the largest |coordinate| of p and the foot).
  static double absolute_gap_at(const Vec3& p, const Vec3& foot) {
    const double m = std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z), std::abs(foot.x),
                               std::abs(foot.y), std::abs(foot.z), std::numeric_limits<double>::min()});
    return 512.0 * 0x1p-53 * m;
  }
  // The verdict for an answer at distance d.
  static bool meets_gap(double d, double lower_bound, double absolute_gap) {
    return d - lower_bound <= std::fmax(kRelativeGap * d, absolute_gap);
  }
};

}  // namespace footpoint
