// How many points of a geometry are nearest to p (projection/projection_result.hpp,
// AnswerMultiplicity), for auto's answer on every geometry: one rule, each geometry supplying its
// second-order test and the points its search reached.
//  - a continuum where the distance on the geometry is flat to second order at a foot X inside the
//    domain (and p is not on the geometry): the Hessian of ½|x - p|^2 restricted to the geometry,
//    in an orthonormal frame of its tangent space, has a least eigenvalue that vanishes (to
//    kFlatMinimum of its value 1 at a line or a plane) when p is a centre of curvature at X: the
//    centre of a circle or a sphere, a point of a surface of revolution's axis facing its circle of
//    feet. Each geometry computes it from its own derivatives: a parametric curve as
//    φ''(t) / |c'|^2 = 1 - κ <n, p - c> (parametric_curve_auto.cpp), an implicit curve as
//    1 + <κ, X - p> with the curvature vector κ of [Curve] eq. (16) (implicit_curve_auto.cpp), an
//    implicit surface as the least eigenvalue of the Lagrangian's I + l H on the tangent plane,
//    p - X = l grad f ([NW06] Theorem 12.5; implicit_surface_auto.cpp); a parametric surface's
//    search tests the Hessian in its parameters, holding a parameter on its bound
//    (surface_search_answer.cpp), and uses TiedFeet alone;
//  - tied: the distinct feet (more than kDistinctFoot (1 + |foot|) apart) among the points the
//    search reached whose distance is within the certificate's gap of the answer's
//    (projection/certificate.hpp), the answer's first: every search solves each start that could
//    hold the nearest point, so a tie within the gap is among them, or the certificate's proof
//    would have had to exclude it;
//  - unique otherwise.
#pragma once
#include <array>
#include <cmath>
#include <vector>

#include "geometry/vec.hpp"
#include "projection/projection_result.hpp"

namespace footpoint {

// The least eigenvalue of the restricted Hessian, relative to its value at a line or a plane,
// below which the distance is flat to second order.
inline constexpr double kFlatMinimum = 1e-8;

// The tie rule: a distance within the gap of the answer's ties with it, and the tied feet are
// told apart at kDistinctFoot (1 + |foot|), the answer's foot first.
class TiedFeet {
 public:
  // r: the answer; `answer`: its foot as the geometry evaluates it (the gap's absolute part is
  // taken there).
  TiedFeet(const ProjectionResult& r, Vec3 p, Vec3 answer);
  // The gap of an answer at `distance` with foot `answer`: the certificate's (projection/certificate.hpp).
  static double gap_of(double distance, Vec3 p, Vec3 answer);
  double gap() const { return gap_; }
  bool ties(double distance) const { return std::abs(distance - distance_) <= gap_; }
  // Adds the foot unless one listed is within kDistinctFoot (1 + |foot|) of it.
  void add(Vec3 foot);
  const std::vector<std::array<double, 3>>& feet() const { return m_.feet; }
  // tied with the feet listed when there is more than one, unique otherwise
  AnswerMultiplicity settle();

 private:
  double distance_;
  double gap_;
  AnswerMultiplicity m_;
};

// The answer r's multiplicity among the points reached: `reached` holds items with a `distance`,
// `foot_of(item)` gives an item's foot (evaluated only for the items that tie).
template <class Reached, class FootOf>
AnswerMultiplicity tied_feet(const ProjectionResult& r, Vec3 p, const std::vector<Reached>& reached,
                             FootOf&& foot_of) {
  TiedFeet ties(r, p, Vec3{r.foot[0], r.foot[1], r.foot[2]});
  for (const Reached& item : reached)
    if (ties.ties(item.distance)) ties.add(foot_of(item));
  return ties.settle();
}

// A point of the geometry a search reached (a solve's end, an edge or singular point) and its
// distance to p.
struct ReachedFoot {
  Vec3 foot;
  double distance;
};
AnswerMultiplicity tied_feet(const ProjectionResult& r, Vec3 p, const std::vector<ReachedFoot>& reached);

// The whole rule: a continuum where r's foot is inside the domain, r.distance > 0 and
// `flat_at_foot()` (the geometry's second-order test against kFlatMinimum, evaluated only then)
// holds; else tied_feet.
template <class Flat, class Reached, class FootOf>
AnswerMultiplicity answer_multiplicity(const ProjectionResult& r, Vec3 p, Flat&& flat_at_foot,
                                       const std::vector<Reached>& reached, FootOf&& foot_of) {
  if (r.summary.location == Location::interior && r.distance > 0.0 && flat_at_foot()) {
    AnswerMultiplicity m;
    m.computed = true;
    m.kind = Multiplicity::continuum;
    return m;
  }
  return tied_feet(r, p, reached, foot_of);
}

}  // namespace footpoint
