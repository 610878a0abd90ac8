// An implicit curve with what `auto` precomputes of it: its equations, the certified subdivision
// and samples of every piece in the box (implicit/seeding/curve_discovery) and the samples' k-d tree
// (seeding/curve_sample_index). A compiled curve is the union of one or more of them, one per
// factor system of its equations (formula::Program::factor_systems).
#pragma once
#include <cmath>
#include <cstddef>
#include <limits>
#include <utility>
#include <vector>

#include "geometry/box3.hpp"
#include "geometry/interval_vec3.hpp"
#include "implicit/geometry/implicit_curve.hpp"
#include "implicit/seeding/curve_discovery.hpp"
#include "seeding/curve_sample_index.hpp"

namespace footpoint {

struct DiscoveredCurve {
  // Runs discovery within `budget` (GeometryError geometry_too_complex past its cell limits).
  DiscoveredCurve(ImplicitEquations eq, const Box3& box, CompileBudget& budget)
      : equations(std::move(eq)),
        discovery(discover_implicit_curve(equations, box, budget)),
        index(discovery.samples),
        sines(sines_at_samples(equations, discovery.samples)) {}
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
           index.memory_bytes() + sines.capacity() * sizeof(float);
  }

  ImplicitEquations equations;
  CurveDiscovery discovery;
  CurveSampleIndex index;
  // The sine of the angle between ∇f1 and ∇f2 at each sample (1 for planar curves, 0 where it is
  // not a number: a singular point): small where the curve is cut by nearly tangent surfaces,
  // whose foot points the search refines (implicit/solvers/foot_refinement.hpp).
  std::vector<float> sines;

 private:
  static std::vector<float> sines_at_samples(const ImplicitEquations& eq, const CurveSamples& samples) {
    std::vector<float> out(samples.size(), 1.0F);
    if (eq.planar()) return out;
    for (std::size_t i = 0; i < samples.size(); ++i) {
      const double sine = eq.jet(samples.points[i]).normals_sine();
      out[i] = std::isnan(sine) ? 0.0F : static_cast<float>(sine);
    }
    return out;
  }
};

}  // namespace footpoint
