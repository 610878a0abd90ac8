// A minimum of φ(t) = ½|c(t) - p|^2 at a kink of a parametric curve's formulas (abs, min, max:
// c' jumps at t*). φ is not differentiable there and Newton does not converge: its iterates, or a
// bracket's bisection, close in on t* while φ'(t) = <c(t) - p, c'(t)> keeps its size on each side.
// t* is a local minimum when its one-sided slopes bracket zero, φ'(t*-) <= 0 <= φ'(t*+): zero lies
// in Clarke's generalised gradient, the hull of the two (F. H. Clarke, Optimization and Nonsmooth
// Analysis, Wiley 1983, Section 2.3: the stationarity of a locally Lipschitz function). That is the
// KKT condition of a kink, so its residual is zero.
//
// Test: a few units in the last place of the parameter scale on each side of t, φ' changes sign
// from <= 0 to >= 0 and jumps by more than a thousand times what φ'' allows over that width (a
// smooth minimum's φ' changes sign too, by no more than φ''; it is no kink). Refinement: bisection
// on the sign of φ' down to adjacent doubles; the one of the two with the smaller φ is t*.
#pragma once
#include "parametric/geometry/parametric_curve.hpp"

namespace footpoint::curve {

// Whether φ has a kink minimum within a few units in the last place of `t` (the parameter scale
// `scale`: the domain's width or |t|, whichever is larger); then `t` becomes it.
bool kink_minimum(const CurveFormulas& formulas, Vec3 p, double scale, double& t);

}  // namespace footpoint::curve
