// The certificate of an answer on an implicit curve (projection/certificate.hpp): a rigorous lower
// bound L of the distance from p to the curve inside its box, from the certified subdivision that
// discovery left (implicit/seeding/curve_discovery) and interval arithmetic at p.
//
// Why a lower bound needs only a few places. The curve C in the closed box D is compact, so the
// distance from p attains its minimum at some X. Either X lies on a face of D (a box-face
// crossing: located at compile time, each in a small enclosure, or inside an unproved box), or X
// is a singular point (T = ∇f1 × ∇f2 = 0, inside an unproved box), or C is a smooth curve around X
// and X is a critical point of the distance along it: X solves
//   G(X) = (f1(X), f2(X), F(X)) = 0,   F(X) = ⟨T(X), p - X⟩          ([Curve] eqs. (5), (7)).
// So L = the least of: the distances to the box-face enclosures; bounds over the unproved boxes;
// and, over each proved cell B, a bound of |p - X| over the zeros of G in B. A part of D farther
// than d - gap (d the answer's distance) needs no more than its box distance, and a proved cell
// whose arcs are that far no more than their capsules' distance (the distance to a segment less
// a radius, implicit/seeding/curve_cell_proof: ArcCapsule), far closer to the arcs' own than its box's.
//
// Over a proved cell B (enclosures kept at compile time, implicit/seeding/curve_cell_proof: ∇f1, ∇f2, T
// and ∂T/∂x_j over B, f and T at the centre c):
//  - no zero of G when the enclosure of F over B excludes 0: its range ⟨T(B), p - B⟩, or the mean
//    value form F(c) + Σ_j ∂_j F(B) (B_j - c_j) with ∂_j F = ⟨∂_j T, p - X⟩ - T_j (the gradient of
//    eq. (7), as in implicit/geometry/implicit_curve_differentials);
//  - else Krawczyk's test on G over B (geometry/krawczyk.hpp; the Jacobian's rows ∇f1(B), ∇f2(B),
//    ∇F(B)): when ‖I - Y G'(B)‖∞ < 1 every matrix of G'(B) is nonsingular, G is one-to-one on B,
//    and its only possible zero lies within ‖Y G(m)‖∞ / (1 - c) of m. With m the answer's foot
//    point (its Lagrange-Newton solution, G(m) enclosed by interval jets at m) that box is a few
//    ulps wide: the answer is proved the unique critical point of its cell, to rounding; with m
//    the centre of another cell it bounds that cell's critical point.
//  - else B is bisected: sub-boxes are dropped by the distance, by the mean value forms of f1,
//    f2 and F about their centres (from B's enclosures: T(c') ⊂ T(c) + ∂T(B) (c' - c)), and the
//    one holding the foot point by Krawczyk's test with fresh interval jets over it.
// An unproved box is bisected with fresh interval jets: dropped by the distance, by f1, f2, by F
// where the formulas are smooth and the box does not touch D's faces; what the budget leaves
// contributes its box distance (reason singular).
// Every bound is rounded outwards; F at a point is enclosed by interval jets at that point.
//
// A curve that is the union of factor curves (implicit/seeding/discovered_curve.hpp): L is the least of
// the bounds over each, each computed against the same answer (its gap and threshold).
#pragma once
#include <span>

#include "implicit/geometry/implicit_curve.hpp"
#include "implicit/seeding/curve_discovery.hpp"
#include "implicit/seeding/discovered_curve.hpp"
#include "projection/certificate.hpp"

namespace footpoint::curve {

// The gap allowed at a distance ~0: a few hundred ulps of the coordinates of p and of the foot.
double implicit_absolute_gap(Vec3 p, Vec3 foot);

// The certificate of the answer `foot` (at distance `distance` from p; `foot` need not be a
// critical point: any point of the curve, or any candidate at all, gets a rigorous L, and
// `certified` only when L meets the gap).
Certificate certify_implicit_curve_answer(const ImplicitEquations& equations, const Box3& box,
                                          const CurveDiscovery& discovery, Vec3 p, Vec3 foot,
                                          double distance);

// The same over the union of `factors`.
Certificate certify_implicit_curve_answer(std::span<const DiscoveredCurve* const> factors, const Box3& box,
                                          Vec3 p, Vec3 foot, double distance);

}  // namespace footpoint::curve
