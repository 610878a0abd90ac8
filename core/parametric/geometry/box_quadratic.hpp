// The minimum of a 2-D quadratic q(δ) = g·δ + ½ δ^T H δ over a rectangle lo <= δ <= hi, exactly:
// the unconstrained minimiser when H is positive definite and it lies inside, else the best of the
// edges (a 1-D quadratic each, minimised in closed form) - the minimum of a quadratic over a
// rectangle is at an interior stationary point or on the boundary; for a positive definite H only
// the one or two edges its minimiser is beyond. Used by the seeding (the
// tangent-plane lower bound and the Newton model of each cell) without any allocation.
#pragma once
#include <array>

#include "parametric/geometry/params.hpp"

namespace footpoint {

struct BoxQuadratic {
  std::array<double, 2> g{};
  std::array<std::array<double, 2>, 2> H{};  // symmetric
  double value(double d0, double d1) const {
    return g[0] * d0 + g[1] * d1 + 0.5 * (H[0][0] * d0 * d0 + 2.0 * H[0][1] * d0 * d1 + H[1][1] * d1 * d1);
  }
};

struct BoxMinimum {
  Params<2> delta{};
  double value = 0.0;
  // which side of the rectangle the minimiser lies on: -1 low, +1 high, 0 strictly inside
  std::array<int, 2> side{};
};

BoxMinimum minimize_on_box(const BoxQuadratic& q, const Params<2>& lo, const Params<2>& hi);

}  // namespace footpoint
