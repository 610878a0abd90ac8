// Following an implicit curve from a point on it: a predictor-corrector walk. Predictor: a step of
// length h along the unit tangent T = grad f1 x grad f2 / |.|; corrector: Newton back onto the
// curve in the plane orthogonal to T. A step is accepted only when the corrector converged, the
// chord and the new tangent turn by at most max_turn from the old tangent (so the walk neither
// jumps to another branch nor skips a bend) - otherwise h is halved - and h grows again after easy
// steps. The walk ends when it closes on its start, leaves the box (the exact face crossing is
// added), comes within reach of samples traced before, reaches a singular point, or stalls.
#pragma once
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "geometry/implicit_curve.hpp"
#include "seeding/curve_enclosure.hpp"
#include "seeding/curve_samples.hpp"

namespace footpoint {

// Sample indices bucketed by the cells of a grid, for "is there a sample near x".
class SampleGrid {
 public:
  explicit SampleGrid(CellGrid grid) : grid_(grid) {}
  void add(Vec3 x, std::int32_t index) { buckets_[CellGrid::key(grid_.index_of(x))].push_back(index); }
  bool occupied(const CellIndex& c) const { return buckets_.count(CellGrid::key(c)) != 0; }
  // True when some sample lies within `radius` of x (radius at most one cell edge).
  bool near(const std::vector<Vec3>& points, Vec3 x, double radius) const;
  // The nearest sample within `radius` of x (at most one cell edge) that ends a walk (a regular
  // sample with a free neighbour slot) and has an index below `below`; -1 when there is none.
  std::int32_t nearest_end(const CurveSamples& samples, Vec3 x, double radius, std::int32_t below) const;

 private:
  // visit(i) for every sample in x's cell and the 26 around it (false from visit stops: true then)
  template <class Visit>
  bool any_nearby(Vec3 x, Visit&& visit) const {
    const CellIndex c = grid_.index_of(x);
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          const CellIndex n{c[0] + dx, c[1] + dy, c[2] + dz};
          if (n[0] < 0 || n[1] < 0 || n[2] < 0) continue;
          const auto it = buckets_.find(CellGrid::key(n));
          if (it == buckets_.end()) continue;
          for (std::int32_t i : it->second)
            if (visit(i)) return true;
        }
    return false;
  }

  CellGrid grid_;
  std::unordered_map<std::uint64_t, std::vector<std::int32_t>> buckets_;
};

struct TraceSettings {
  double max_step = 0.0;  // h: the largest step (chord)
  double min_step = 0.0;  // below this the walk has stalled
  // 0.15 rad between consecutive tangents: the arc exceeds the chord by at most 1e-3, and a bend
  // of the distance function between two samples is resolved.
  double max_turn = 0.15;
  // sin of the angle between grad f1 and grad f2 below which a singular point is looked for.
  double singular_sine = 0.02;
  std::size_t max_points = 2000000;
};

enum class TraceEnd { closed, box_face, singular_point, joined, stalled, budget };

struct TraceOutcome {
  std::vector<Vec3> points;  // after the start, in walking order
  TraceEnd end = TraceEnd::stalled;
  Vec3 end_point;                     // the face crossing or singular point (box_face / singular_point)
  std::vector<Vec3> singular_points;  // singular points passed on the way (refined)
  std::int32_t joined_to = -1;        // the walk end it ran into (end == joined)
};

// Walks from `start` (on the curve) along `direction` (+T or -T) until one of the ends above.
// `close_on` is where a loop closes: the start itself for the first walk from a seed, the end of
// the first walk for the second one (the other way round the same loop). `existing` buckets the
// samples so far: coming within max_step / 2 of the end of an earlier seed's walk (indices below
// `own_first`) ends this walk (joined: the same branch, walked from the other side). Samples
// inside earlier walks do not end it: a different branch may pass that close (two branches
// touching, a tacnode), and each branch needs samples of its own.
TraceOutcome trace_curve(const ImplicitEquations& equations, const Box3& box, Vec3 start, Vec3 direction,
                         Vec3 close_on, const TraceSettings& settings, const SampleGrid& existing,
                         const CurveSamples& samples, std::int32_t own_first);

}  // namespace footpoint
