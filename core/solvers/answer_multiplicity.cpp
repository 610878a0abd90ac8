#include "solvers/answer_multiplicity.hpp"

#include <cmath>

#include "projection/certificate.hpp"

namespace footpoint {

double TiedFeet::gap_of(double distance, Vec3 p, Vec3 answer) {
  return std::fmax(Certificate::kRelativeGap * distance, Certificate::absolute_gap_at(p, answer));
}

TiedFeet::TiedFeet(const ProjectionResult& r, Vec3 p, Vec3 answer)
    : distance_(r.distance), gap_(gap_of(r.distance, p, answer)) {
  m_.computed = true;
  m_.feet.push_back(r.foot);
}

void TiedFeet::add(Vec3 foot) {
  m_.add_distinct({foot.x, foot.y, foot.z}, kDistinctFoot * (1.0 + norm(foot)));
}

AnswerMultiplicity TiedFeet::settle() {
  m_.settle();
  return m_;
}

AnswerMultiplicity tied_feet(const ProjectionResult& r, Vec3 p, const std::vector<ReachedFoot>& reached) {
  return tied_feet(r, p, reached, [](const ReachedFoot& f) { return f.foot; });
}

}  // namespace footpoint
