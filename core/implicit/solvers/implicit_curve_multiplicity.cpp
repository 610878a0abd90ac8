#include "implicit/solvers/implicit_curve_multiplicity.hpp"

#include <cmath>

#include "implicit/geometry/implicit_curve_differentials.hpp"

namespace footpoint::curve {

namespace {
constexpr double kFlat = 1e-8;  // φ'' (arc length) against its value 1 at a straight curve
}  // namespace

AnswerMultiplicity implicit_curve_multiplicity(const ImplicitJet& at_answer, Vec3 p,
                                               const ProjectionResult& r,
                                               const std::vector<ImplicitMinimum>& found) {
  AnswerMultiplicity m;
  m.computed = true;
  const Vec3 answer{r.foot[0], r.foot[1], r.foot[2]};
  Vec3 kappa;
  if (r.summary.location == Location::interior && r.distance > 0.0 && curvature_vector(at_answer, kappa) &&
      std::abs(1.0 + dot(kappa, answer - p)) <= kFlat) {
    m.kind = Multiplicity::continuum;
    return m;
  }
  return tied_feet(r, p, found);
}

}  // namespace footpoint::curve
