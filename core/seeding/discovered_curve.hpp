// An implicit curve with what `auto` precomputes of it: its equations, the certified subdivision
// and samples of every piece in the box (seeding/curve_discovery) and the samples' k-d tree
// (seeding/curve_sample_index). A compiled curve is the union of one or more of them, one per
// factor system of its equations (formula::Program::factor_systems).
#pragma once
#include <cstddef>
#include <limits>
#include <utility>

#include "geometry/box3.hpp"
#include "geometry/implicit_curve.hpp"
#include "geometry/interval_vec3.hpp"
#include "seeding/curve_discovery.hpp"
#include "seeding/curve_sample_index.hpp"

namespace footpoint {

struct DiscoveredCurve {
  // Runs discovery (GeometryError geometry_too_complex past its budget).
  DiscoveredCurve(ImplicitEquations eq, const Box3& box)
      : equations(std::move(eq)),
        discovery(discover_implicit_curve(equations, box)),
        index(discovery.samples) {}
  // The index points into discovery.samples: neither copied nor moved.
  DiscoveredCurve(const DiscoveredCurve&) = delete;
  DiscoveredCurve& operator=(const DiscoveredCurve&) = delete;

  // No point of the curve is nearer to p than this: the distance to the box of the cell tree's
  // root, which holds every proved cell, box-face crossing and unproved box (infinite when the
  // curve has no point in the box).
  double distance_lower_bound(Vec3 p) const {
    const auto& nodes = discovery.tree.nodes();
    return nodes.empty() ? std::numeric_limits<double>::infinity()
                         : footpoint::distance_lower_bound(p, nodes[0].box);
  }

  std::size_t memory_bytes() const {
    return sizeof(*this) + equations.program().memory_bytes() + discovery.memory_bytes() +
           index.memory_bytes();
  }

  ImplicitEquations equations;
  CurveDiscovery discovery;
  CurveSampleIndex index;
};

}  // namespace footpoint
