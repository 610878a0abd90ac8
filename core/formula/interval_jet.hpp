// Interval jets: enclosures over a box of a formula's value, gradient and Hessian, outward
// rounded (formula/interval.hpp, formula/interval_arith.hpp), for rigorous Taylor models
// (Program::interval_jets2).
//
// The contract. For a box X (each input an interval) and each formula f:
//  - `v` encloses f(x) at every x in X where f is defined (as Program::intervals does, with the
//    same `partial` flag when f is undefined at some points of X);
//  - when `lipschitz` is true, f is defined and Lipschitz continuous on X and `g` encloses Clarke's
//    generalized gradient of f at every point of X (the gradient itself where f is differentiable),
//    so the mean value inclusion f(y) - f(x) ∈ g · (y - x) holds for all x, y in X (G. Lebourg's
//    mean value theorem, F. H. Clarke, Optimization and Nonsmooth Analysis, Wiley 1983,
//    Theorem 2.3.7; the chain rule's inclusion, Theorem 2.3.9, is what the interval evaluation
//    follows: an interval vector holds the convex hulls it asks for);
//  - when `smooth` is true (it implies `lipschitz`), f restricted to X is twice continuously
//    differentiable and `h` encloses its Hessian at every point of X, so Taylor's theorem with the
//    Lagrange remainder holds on every segment in X: f(x + δ) ∈ f(x) + ∇f(x)·δ + ½ δ^T h δ.
// Where X holds a point at which an operation of the formula is not twice differentiable, the
// flags say so: abs or sign with an argument whose range straddles 0, min or max whose operands'
// ranges overlap (a switch inside X), a comparison, && or || whose truth is not constant over X
// and c ? a : b with such a condition (these jump: neither flag), sqrt, pow with a non-integer
// exponent, ln, 1/x, tan, asin, acos, acosh, atanh at or past the ends of their smooth domain
// (neither flag), abs and min/max that switch (`lipschitz` only: g then holds the hull of both
// sides' gradients). An operation that equals one smooth branch on all of X (abs of an argument
// >= 0 there, min(a, b) with a <= b there, a condition constant over X) keeps both flags. A
// derivative enclosure whose flag is false holds the whole line: callers fall back to first order
// (mean value) or to the value enclosure alone (zero order).
#pragma once
#include <array>

#include "formula/interval.hpp"

namespace footpoint::formula {

template <int N>
struct IntervalJet2 {
  Interval v;
  std::array<Interval, N> g{};
  std::array<std::array<Interval, N>, N> h{};  // symmetric
  bool lipschitz = true;
  bool smooth = true;
};

// The same without the Hessian (Program::interval_jets1): value and gradient enclosures, and the
// same flags (`smooth` still says whether f is twice continuously differentiable on the box).
// About a third of the work of IntervalJet2 for three variables.
template <int N>
struct IntervalJet1 {
  Interval v;
  std::array<Interval, N> g{};
  bool lipschitz = true;
  bool smooth = true;
};

}  // namespace footpoint::formula
