// Interval vectors in space (formula/interval.hpp's outward-rounded intervals, three at a time):
// boxes as interval vectors, the dot and cross products that enclose ⟨a, b⟩ and a × b for every
// a, b in the operands, and a rigorous lower bound of the distance from a point to a box. They
// carry the enclosures of the implicit curves' tangent T = ∇f1 × ∇f2 and of the orthogonality
// function F = ⟨T, p - X⟩ ([Curve] eqs. (7)) over boxes.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "formula/interval.hpp"
#include "geometry/box3.hpp"
#include "geometry/vec.hpp"

namespace footpoint {

using formula::Interval;
using IVec3 = std::array<Interval, 3>;
using IMat3 = std::array<IVec3, 3>;  // rows

namespace ivec {

inline IVec3 of_box(const Box3& b) { return {{{b.lo.x, b.hi.x}, {b.lo.y, b.hi.y}, {b.lo.z, b.hi.z}}}; }
inline IVec3 of_point(Vec3 x) { return {{{x.x, x.x}, {x.y, x.y}, {x.z, x.z}}}; }
inline Box3 to_box(const IVec3& a) { return {{a[0].lo, a[1].lo, a[2].lo}, {a[0].hi, a[1].hi, a[2].hi}}; }
inline Vec3 mid(const IVec3& a) {
  return {formula::interval::mid(a[0]), formula::interval::mid(a[1]), formula::interval::mid(a[2])};
}
inline IVec3 add(const IVec3& a, const IVec3& b) {
  using formula::interval::add;
  return {add(a[0], b[0]), add(a[1], b[1]), add(a[2], b[2])};
}
inline IVec3 sub(const IVec3& a, const IVec3& b) {
  using formula::interval::sub;
  return {sub(a[0], b[0]), sub(a[1], b[1]), sub(a[2], b[2])};
}
inline IVec3 scale(const Interval& s, const IVec3& a) {
  using formula::interval::mul;
  return {mul(s, a[0]), mul(s, a[1]), mul(s, a[2])};
}
inline Interval dot(const IVec3& a, const IVec3& b) {
  using formula::interval::add;
  using formula::interval::mul;
  return add(add(mul(a[0], b[0]), mul(a[1], b[1])), mul(a[2], b[2]));
}
// Each component a_i b_j - a_j b_i uses each operand interval once: its interval is the exact range
// over the operands' box up to the outward rounding (no dependency widening).
inline IVec3 cross(const IVec3& a, const IVec3& b) {
  using formula::interval::mul;
  using formula::interval::sub;
  return {sub(mul(a[1], b[2]), mul(a[2], b[1])), sub(mul(a[2], b[0]), mul(a[0], b[2])),
          sub(mul(a[0], b[1]), mul(a[1], b[0]))};
}
inline IVec3 intersect(const IVec3& a, const IVec3& b) {
  using formula::interval::intersect;
  return {intersect(a[0], b[0]), intersect(a[1], b[1]), intersect(a[2], b[2])};
}
// m v for an interval matrix (rows) and an interval vector.
inline IVec3 apply(const IMat3& m, const IVec3& v) { return {dot(m[0], v), dot(m[1], v), dot(m[2], v)}; }

}  // namespace ivec

// No point of the box is nearer to p than the square root of this. The gaps, their squares and
// their sum are computed in round to nearest: each of the at most five roundings on the way to a
// term is a factor (1 + δ), |δ| <= u = 2^-53, and rounding is monotone (a gap computed positive
// is positive), so the exact sum is at least the computed one times (1 + u)^-5 > 1 - 5u; the
// factor 1 - 2^-49 covers that and its own rounding. Sums this close to the underflow threshold,
// where the errors are absolute, count as 0.
inline double distance2_lower_bound(Vec3 p, const Box3& b) {
  double s = 0.0;
  for (int k = 0; k < 3; ++k) {
    // std::max(0, ·) last: a NaN gap counts as 0 (std::max returns its first argument unless the
    // second compares greater).
    const double g = std::max(0.0, std::max(b.lo[k] - p[k], p[k] - b.hi[k]));
    s += g * g;
  }
  if (!(s <= std::numeric_limits<double>::max()))
    return 0.5 * std::numeric_limits<double>::max();  // overflow
  return s > 0x1p-960 ? s * (1.0 - 0x1p-49) : 0.0;
}

// No point of the box is nearer to p than this (the square root rounded down).
inline double distance_lower_bound(Vec3 p, const Box3& b) {
  const double s = distance2_lower_bound(p, b);
  return s > 0.0 ? formula::next_down(std::sqrt(s)) : 0.0;
}

// An upper bound of t^2 (t >= 0): two roundings, covered by the factor 1 + 2^-50 and its own.
inline double square_upper_bound(double t) { return t * t * (1.0 + 0x1p-49); }

}  // namespace footpoint
