// Whether a parametric curve closes, c(tmin) = c(tmax) (a circle over [0, 2π], a trefoil knot),
// decided once per geometry at compile time. A closed curve's ends are no ends: the search treats
// tmin and tmax as one interior parameter, the mesh closes the polyline.
//
// How it is decided (detect_curve_closure), as for surfaces (surface_closure.hpp):
//  - The tolerance, at rounding level: 256 ε (M + S T), ε = 2^-52, M the largest coordinate
//    magnitude of 34 samples of the curve (its ends and 32 inside, closure_sampling.hpp), S the
//    largest |c'| there and T = max(|tmin|, |tmax|) (the rounding of the parameters themselves:
//    the double nearest 2π is not 2π).
//  - Closed when |c(tmax) - c(tmin)| <= tolerance, both defined. Smooth when besides the unit
//    tangents c'/|c'| at the two ends agree within 1e-6 (a circle); a closed curve whose tangents
//    differ there, or vanish, closes with a corner (a teardrop), `smooth` false.
//  - Declared periodic (the definition's "periodic": ["t"]): accepted when the ends are within
//    max(tolerance, 1e-6 x the size of the samples' bounding box), else GeometryError
//    `not_periodic`.
// What is proven: `gap_bound` bounds |c(tmax) - c(tmin)| rigorously (the interval enclosures of the
// formulas at the two end parameters, Program::intervals): a bound on the formulas' exact values
// at the double end parameters, at rounding level for a circle. Here the one pair of points is all
// there is to compare, so nothing is left to sampling but the smoothness.
#pragma once
#include <limits>

#include "parametric/geometry/parametric_curve.hpp"

namespace footpoint {

struct CurveClosure {
  bool closed = false;    // c(tmin) = c(tmax)
  bool smooth = false;    // closed, and the unit tangents at the ends agree (else a corner)
  bool declared = false;  // the definition declares t periodic (and it is accepted)
  double gap = 0.0;       // |c(tmax) - c(tmin)| as evaluated
  // A rigorous bound of |c(tmax) - c(tmin)| (infinite when there is none).
  double gap_bound = std::numeric_limits<double>::infinity();
  double tolerance = 0.0;  // the rounding-level distance under which points are one
};

// Whether c closes over `domain`; declared_periodic is the definition's "periodic": ["t"]. Throws
// GeometryError (code not_periodic, field "periodic") for a declared curve whose ends do not meet.
CurveClosure detect_curve_closure(const CurveFormulas& formulas, const ParamInterval& domain,
                                  bool declared_periodic = false);

}  // namespace footpoint
