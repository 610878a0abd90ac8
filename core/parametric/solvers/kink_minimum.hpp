// Minima of the distance at a kink of a parametric curve's or surface's formulas (abs, min, max):
// the one-dimensional case, a curve's parameter, and the two-dimensional one, a surface's; both
// refine a minimum along a line of parameters (the curve's; a surface's edge, where a kink curve
// meets the boundary) by the same bisection on the sign of the slope down to adjacent doubles, the
// end with the smaller distance taken.
//
// Curves. A minimum of φ(t) = ½|c(t) - p|^2 at a kink of a parametric curve's formulas (abs, min,
// max: c' jumps at t*). φ is not differentiable there and Newton does not converge: its iterates, or
// a bracket's bisection, close in on t* while φ'(t) = <c(t) - p, c'(t)> keeps its size on each side.
// t* is a local minimum when its one-sided slopes bracket zero, φ'(t*-) <= 0 <= φ'(t*+): zero lies
// in Clarke's generalised gradient, the hull of the two (F. H. Clarke, Optimization and Nonsmooth
// Analysis, Wiley 1983, Section 2.3: the stationarity of a locally Lipschitz function). That is the
// KKT condition of a kink, so its residual is zero.
//
// Test: a few units in the last place of the parameter scale on each side of t, φ' changes sign
// from <= 0 to >= 0 and jumps by more than a thousand times what φ'' allows over that width (a
// smooth minimum's φ' changes sign too, by no more than φ''; it is no kink). Refinement: bisection
// on the sign of φ' down to adjacent doubles; the one of the two with the smaller φ is t*.
//
// Surfaces. A minimum of f(t) = ½|s(t) - p|^2 on a kink curve of a parametric surface's formulas (abs, min,
// max: the partials of s jump across a curve K of the parameter plane, as for z = |u| along u = 0
// or z = |u - v^2| along u = v^2). f is not differentiable on K and Newton does not converge there:
// its iterates close in on K while the gradient keeps its size on each side.
//
// Stationarity (Clarke, Section 2.3, as for curves above): with g- and g+ the gradients of
// f on the two sides of K at a point t* of it, t* is stationary when 0 lies in their hull. As f is
// continuous across K, g+ - g- is normal to K (the derivatives along K agree), so that is: the
// derivative along K, D = <g±, τ>, vanishes, and along the normal n = (g+ - g-)/|g+ - g-| f falls
// towards K from both sides, <g-, n> <= 0 <= <g+, n>. Then the residual is zero, as for a kink of
// a curve.
//
// The solve, from the last iterate t0 of a local solve that did not converge:
//  1. Across K: the Newton step d of t0's piece crosses K (else the solve would have converged on
//     the piece). Along t0 + λd, λ in [0, 1], bisection towards the half whose change of the
//     slope <g, d> a smooth f explains least (the trapezoidal rule of its rate <d, H d>: off by
//     O(width^3) where f is smooth, by the jump across K) gives a bracket [a, b] of K, adjacent
//     doubles. It is a kink when |g(b) - g(a)| exceeds a thousand times what the Hessian allows
//     over |b - a|.
//  2. Along K: Newton on the derivative D along K from the bracket's middle, σ = -D / rate, the
//     rate <τ, H τ> at the first step and then the secant of D along K (f along a curved K bends
//     also by K's curvature times the normal slope, which H does not see); each new point is
//     brought back onto K by the bisection of step 1 along n, f not increasing, until
//     |D| <= 1e-12 |s - p| |s_τ| (the cosine residual of the orthogonality, at rounding level), at
//     most 32 steps.
//  3. The answer is the end of the last bracket with the smaller f, if <g-, n> <= 0 <= <g+, n>.
// Where the solve ended within 1e-9 of the box's size of an edge or a corner (a kink meeting the
// boundary: z = |u - v^2| at (1, ±1) over [-1,1]^2), the candidate is the corner, or on an edge the
// minimum of f along it (bisected to adjacent doubles where the slope along the edge changes sign;
// the corner where f falls along the edge all the way to its end), and it is stationary when no direction
// into the box descends: the one-sided derivative f'(t; r) = <g±, r> of the side r points into is >= 0 over
// the feasible cone (Clarke's condition with the box's normal cone: 0 in the hull of g-, g+ plus that cone).
// f' is linear on each side of K, so a fan of 65 directions across the cone tells, each read from the
// gradient a step 1e-7 of the box's size along it (off by |H| times that step, which the test allows).
// Where step 2 finds no stationary point on K (K runs into a crossing with another kink, where its
// derivative D jumps and the secant steps across it back and forth, or into the boundary), and where
// no K is found at all (a point where the formulas are not differentiable alone, a cone's tip), a
// compass search closes in on the kink point: no gradient needed, along ±K's tangent (its valley is
// too narrow for fixed directions) and eight directions turned at every level, steps halved down to
// rounding. The point is accepted when f'(t; r) >= 0 for every r, read from a fan of 64 directions
// around it (the boundary's test where it ends at the boundary): z = |u| + |v| at (0, 0), z = sqrt(u^2 +
// v^2) at its tip, z = min(u^2, v^2) along u = v up to the corner (1, 1).
#pragma once
#include "parametric/geometry/parametric_curve.hpp"
#include "parametric/geometry/parametric_surface.hpp"
#include "parametric/solvers/projected_newton.hpp"

namespace footpoint::curve {

// Whether φ has a kink minimum within a few units in the last place of `t` (the parameter scale
// `scale`: the domain's width or |t|, whichever is larger); then `t` becomes it.
bool kink_minimum(const CurveFormulas& formulas, Vec3 p, double scale, double& t);

}  // namespace footpoint::curve

namespace footpoint::surface {

// Whether a kink minimum lies where the solve `s` ended; then `s` becomes it (converged).
bool kink_minimum(const SurfaceFormulas& formulas, const ParamBox& box, const Vec3& p, LocalSolution& s);

}  // namespace footpoint::surface
