// How many points of an implicit curve are nearest to p (projection/projection_result.hpp,
// AnswerMultiplicity), for auto's answer:
//  - a continuum where the distance along the curve is flat to second order at a regular foot X
//    inside the box: with the arc length s, the unit tangent T and the curvature vector κ of
//    [Curve] eq. (16), φ(s) = ½|X(s) - p|^2 has φ'' = <T, T> + <κ, X - p> = 1 + <κ, X - p>, which
//    vanishes (to 1e-8) when p is the centre of the osculating circle: the centre of a circle, or
//    a point of a sphere's and a plane's circle of intersection's axis;
//  - tied: the distinct feet (more than 1e-8 (1 + |foot|) apart) among the minima the search
//    solved whose distance is within the certificate's gap of the answer's, the answer's first
//    (the search solves every sample's minimum that may beat the best by the samples' bound, so a
//    tie within the gap is among them);
//  - unique otherwise.
#pragma once
#include <vector>

#include "implicit/geometry/implicit_curve.hpp"
#include "projection/projection_result.hpp"
#include "solvers/auto_result.hpp"

namespace footpoint::curve {

using ImplicitMinimum = ReachedFoot;

// at_answer: the jets at r's foot.
AnswerMultiplicity implicit_curve_multiplicity(const ImplicitJet& at_answer, Vec3 p,
                                               const ProjectionResult& r,
                                               const std::vector<ImplicitMinimum>& found);

}  // namespace footpoint::curve
