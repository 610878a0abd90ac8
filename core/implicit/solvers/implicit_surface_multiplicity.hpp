// How many points of an implicit surface S = {f = 0} ∩ B are nearest to p (geometry/
// projection_result.hpp, AnswerMultiplicity), for auto's answer:
//  - a continuum where the distance on S is flat to second order at a regular foot X inside the
//    box: with p - X = l grad f(X) (the Lagrange condition), the Hessian of ½|x - p|^2 on S at X is
//    the Lagrangian's I + l H(X) on the tangent plane ([NW06] Theorem 12.5), whose least eigenvalue
//    vanishes (to 1e-8 of its value 1 at a plane) when p is a centre of curvature of S at X: the
//    centre of a sphere, a point on a surface of revolution's axis facing its circle of feet;
//  - tied: the distinct feet (more than 1e-8 (1 + |foot|) apart) among the points of S the search
//    reached (its solves' ends, the box's edge points, the singular points) whose distance is
//    within the certificate's gap of the answer's, the answer's first;
//  - unique otherwise.
#pragma once
#include <vector>

#include "implicit/geometry/implicit_surface.hpp"
#include "projection/projection_result.hpp"
#include "solvers/auto_result.hpp"

namespace footpoint::surface_implicit {

AnswerMultiplicity implicit_surface_multiplicity(const ImplicitSurfaceEquation& equation, Vec3 p,
                                                 const ProjectionResult& r,
                                                 const std::vector<curve::ReachedFoot>& reached);

}  // namespace footpoint::surface_implicit
