#include "parametric/solvers/curve_multiplicity.hpp"

#include <cmath>

#include "projection/certificate.hpp"

namespace footpoint::curve {

namespace {
constexpr double kFlat = 1e-8;  // φ'' relative to |c'|^2
}  // namespace

AnswerMultiplicity curve_multiplicity(const CurveFormulas& formulas, Vec3 p, const ProjectionResult& r,
                                      const std::vector<CurveMinimum>& found) {
  AnswerMultiplicity m;
  m.computed = true;
  const double t = r.params[0];
  const CurveJet j = formulas.jet(t);
  const Vec3 d = j.c - p;
  const double speed2 = dot(j.d1, j.d1);
  const double second = speed2 + dot(d, j.d2);
  if (r.summary.location == Location::interior && r.distance > 0.0 && std::abs(second) <= kFlat * speed2) {
    m.kind = Multiplicity::continuum;
    return m;
  }
  const Vec3 answer{r.foot[0], r.foot[1], r.foot[2]};
  const double gap =
      std::fmax(Certificate::kRelativeGap * r.distance, Certificate::absolute_gap_at(p, answer));
  m.feet.push_back(r.foot);
  for (const CurveMinimum& f : found) {
    if (!(std::abs(f.distance - r.distance) <= gap)) continue;
    const Vec3 foot = formulas.point(f.t);
    m.add_distinct({foot.x, foot.y, foot.z}, kDistinctFoot * (1.0 + norm(foot)));
  }
  m.settle();
  return m;
}

}  // namespace footpoint::curve
