// Closed intervals [lo, hi] with outward rounding, for rigorous range bounds of a formula over a
// box (exclusion tests: a box where 0 is outside the range of f cannot contain a point of f = 0).
#pragma once

namespace footpoint::formula {

struct Interval {
  double lo = 0.0;
  double hi = 0.0;
  // Some points of the box lie outside the expression's domain (its value is NaN there, e.g. sqrt
  // of a negative number). [lo, hi] encloses the values at the other points. Operations that turn a
  // NaN into a number (comparisons, min/max, sign, ?:) widen their result to cover that case.
  bool partial = false;
  // True when the interval certainly does not contain zero (NaN bounds never exclude).
  bool excludes_zero() const { return lo > 0.0 || hi < 0.0; }
};

}  // namespace footpoint::formula
