// What a branch-and-bound certificate keeps while it closes boxes (parametric/solvers/
// surface_certificate.hpp, parametric/solvers/parametric_curve_certificate.hpp): the target the boxes' lower
// bounds must reach for the answer's distance d (d - gap/2, gap = max(1e-9 d, the absolute gap of
// projection/certificate.hpp)), the least bound of the boxes closed or left open, and why it
// stopped; at the end, the Certificate.
#pragma once
#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/vec.hpp"
#include "projection/certificate.hpp"

namespace footpoint {

class CertificateLedger {
 public:
  CertificateLedger(double distance, double absolute_gap) { retarget(distance, absolute_gap); }

  // The answer became a nearer one (its distance, and the absolute gap at its foot).
  void retarget(double distance, double absolute_gap) {
    distance_ = distance;
    absolute_gap_ = std::max(absolute_gap_, absolute_gap);
    target_ = distance - 0.5 * gap();
    // a lower bound of f = ½ d^2 at least this gives a distance bound at least the target
    target_f_ = target_ > 0.0 ? 0.5 * target_ * target_ * (1.0 + 16.0 * 0x1p-53) : 0.0;
  }
  // The gap is measured from the point the answer's parameters name: s within s_rad of the
  // computed one (a rigorous point enclosure). Where that point is farther from p than the
  // answer's distance says, its largest distance is the one certified - whatever produced the
  // answer, `certified` speaks of the point at its parameters.
  void measure_from(const Vec3& s, const Vec3& s_rad, const Vec3& p) {
    const double far = farthest(s, s_rad, p);
    if (far > distance_) retarget(far, absolute_gap_);
  }
  double gap() const { return std::fmax(Certificate::kRelativeGap * distance_, absolute_gap_); }
  double target() const { return target_; }
  double target_f() const { return target_f_; }
  bool reaches(double lb) const { return lb >= target_; }

  void close(double lb) { lower_ = std::min(lower_, lb); }
  // a subtree whose box is beyond the target, closed without its bounds
  void skip() { skipped_ = true; }
  void leave_open(double lb, bool bounded) {
    lower_ = std::min(lower_, lb);
    unclosed_ = true;
    unbounded_ = unbounded_ || !bounded;
  }
  void refute() { refuted_ = true; }
  bool refuted() const { return refuted_; }

  // A point s of the geometry (each coordinate within s_rad) is nearer to p than the answer by
  // more than the gap.
  bool nearer_than_answer(const Vec3& s, const Vec3& s_rad, const Vec3& p) const {
    return farthest(s, s_rad, p) < distance_ - gap();
  }

  Certificate finish(int boxes) const {
    Certificate c;
    c.computed = true;
    c.absolute_gap = absolute_gap_;
    c.boxes = boxes;
    c.lower_bound = std::max(
        std::min({lower_, skipped_ ? target_ : std::numeric_limits<double>::infinity(), distance_}), 0.0);
    c.certified = !refuted_ && !unclosed_ && Certificate::meets_gap(distance_, c.lower_bound, absolute_gap_);
    c.reason = c.certified  ? CertificateReason::gap_met
               : refuted_   ? CertificateReason::nearer_point
               : unbounded_ ? CertificateReason::non_finite
                            : CertificateReason::budget_exhausted;
    return c;
  }

 private:
  // An upper bound of |s - p| for every point within s_rad of s (per coordinate), rounded up.
  static double farthest(const Vec3& s, const Vec3& s_rad, const Vec3& p) {
    double far2 = 0.0;
    for (int k = 0; k < 3; ++k) {
      const double d = std::abs(s[k] - p[k]) + s_rad[k];
      far2 += d * d;
    }
    return std::sqrt(far2) * (1.0 + 4.0 * 0x1p-53);
  }

  double distance_ = 0.0;
  double absolute_gap_ = 0.0;
  double target_ = 0.0, target_f_ = 0.0;
  double lower_ = std::numeric_limits<double>::infinity();
  bool skipped_ = false, unclosed_ = false, unbounded_ = false, refuted_ = false;
};

}  // namespace footpoint
