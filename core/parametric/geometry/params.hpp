// A point of a parametric geometry's parameter space, or a step in it: t for a curve (N = 1),
// (u, v) for a surface (N = 2). The boxes of these spaces are ParamInterval
// (parametric/geometry/parametric_curve.hpp) and ParamBox (parametric/geometry/parametric_surface.hpp);
// BoxEnclosure<N> (parametric/geometry/box_enclosure.hpp) holds a box as two Params<N>.
//
// N is never deduced from a Params<N> argument (std::type_identity_t): a function template over
// N takes it from its enclosures, or from the caller (enclose_box<2>(...)), so that a braced list
// {u, v} is accepted where Params<2> is expected.
#pragma once
#include <array>
#include <type_traits>

namespace footpoint {

template <int N>
using Params = std::type_identity_t<std::array<double, N>>;

}  // namespace footpoint
