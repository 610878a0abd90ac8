#include "implicit/seeding/curve_discovery.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>

#include "implicit/geometry/curve_correction.hpp"
#include "implicit/geometry/implicit_curve.hpp"
#include "implicit/geometry/singular_point.hpp"
#include "implicit/seeding/curve_arc_samples.hpp"
#include "implicit/seeding/curve_enclosure.hpp"

namespace footpoint {
namespace {

// Samples at most this fraction of the enclosure's cell edge apart along the curve.
constexpr double kStepPerCell = 0.5;

// The clusters of unproved boxes that touch (union-find), as lists of box indices.
std::vector<std::vector<std::size_t>> clusters(const std::vector<UnprovedBox>& boxes) {
  std::vector<std::size_t> parent(boxes.size());
  std::iota(parent.begin(), parent.end(), std::size_t{0});
  auto root = [&](std::size_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  for (std::size_t i = 0; i < boxes.size(); ++i)
    for (std::size_t j = i + 1; j < boxes.size(); ++j)
      if (boxes[i].box.intersects(boxes[j].box)) parent[root(i)] = root(j);
  std::vector<std::vector<std::size_t>> out;
  std::vector<std::ptrdiff_t> slot(boxes.size(), -1);
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    const std::size_t r = root(i);
    if (slot[r] < 0) {
      slot[r] = static_cast<std::ptrdiff_t>(out.size());
      out.emplace_back();
    }
    out[static_cast<std::size_t>(slot[r])].push_back(i);
  }
  return out;
}

Box3 hull(const std::vector<UnprovedBox>& boxes, const std::vector<std::size_t>& members) {
  Box3 h = boxes[members.front()].box;
  for (std::size_t i : members)
    for (int k = 0; k < 3; ++k) {
      h.lo[k] = std::min(h.lo[k], boxes[i].box.lo[k]);
      h.hi[k] = std::max(h.hi[k], boxes[i].box.hi[k]);
    }
  return h;
}

// Where a cluster meets a face of the curve's box, the point where the curve crosses that face
// (Newton on the face from the cluster's centre): an exact box-face point, a candidate of its own.
void sample_box_faces(const ImplicitEquations& eq, const Box3& box, const Box3& h, double slack,
                      CurveSamples& samples) {
  for (int a = 0; a < (eq.planar() ? 2 : 3); ++a)
    for (const double v : {box.lo[a], box.hi[a]}) {
      if (h.lo[a] > v || h.hi[a] < v) continue;
      Vec3 inside = h.center(), outside = inside;
      inside[a] = std::clamp(inside[a], box.lo[a], box.hi[a]);
      outside[a] =
          v + (v == box.lo[a] ? -1.0 : 1.0) * std::max(h.max_edge(), 1e-12 * std::max(1.0, std::fabs(v)));
      Vec3 x;
      if (curve::locate_face_crossing(eq, box, inside, outside, x) && h.contains(x, slack))
        samples.add(x, SampleKind::box_face);
    }
}

// A sample for each cluster of unproved boxes: its singular point (isolated by Krawczyk's test
// where it is a regular zero of the singular system), else a point of the curve in it; and its
// crossings of the box's faces.
void sample_unproved(const ImplicitEquations& eq, const Box3& box, CurveDiscovery& out) {
  for (const auto& members : clusters(out.cells.unproved)) {
    const Box3 h = hull(out.cells.unproved, members);
    const double slack = h.diagonal() + 1e-12 * std::max(1.0, norm(h.center()));
    sample_box_faces(eq, box, h, slack, out.samples);
    Vec3 s = h.center();
    if (curve::refine_singular_point(eq, s) && h.contains(s, slack) &&
        box.contains(s, 1e-12 * std::max(1.0, norm(s)))) {
      out.samples.add(s, SampleKind::singular_point);
      ++out.stats.singular_points;
      if (const auto e =
              curve::isolate_singular_point(eq, s, std::max(h.max_edge(), 1e-9 * std::max(1.0, norm(s))))) {
        out.singular_enclosures.push_back(*e);
        ++out.stats.isolated_singular_points;
      }
      continue;
    }
    Vec3 x = h.center();
    if (curve::newton_onto_curve(eq, x) && h.contains(x, slack) &&
        box.contains(x, 1e-12 * std::max(1.0, norm(x))))
      out.samples.add(x, SampleKind::regular);
  }
}

}  // namespace

std::size_t CurveDiscovery::memory_bytes() const {
  return samples.memory_bytes() + cells.cells.capacity() * sizeof(ProvedCell) +
         cells.crossings.capacity() * sizeof(FaceCrossing) + cells.capsules.capacity() * sizeof(ArcCapsule) +
         cells.unproved.capacity() * sizeof(UnprovedBox) + tree.memory_bytes() +
         singular_enclosures.capacity() * sizeof(Box3);
}

CurveDiscovery discover_implicit_curve(const ImplicitEquations& equations, const Box3& box,
                                       CompileBudget& budget) {
  const auto t0 = std::chrono::steady_clock::now();
  CurveDiscovery out;
  const CurveEnclosure enclosure = enclose_curve(equations, box, budget);
  out.stats.levels = enclosure.levels;
  out.stats.cells = enclosure.cells.size();
  out.stats.interval_tests = enclosure.tests;
  out.stats.enclosure_truncated = enclosure.truncated;

  out.cells = subdivide_curve(equations, enclosure, budget);
  out.stats.cells_examined = out.cells.examined;
  out.stats.proved_cells = out.cells.cells.size();
  out.stats.unproved_boxes = out.cells.unproved.size();
  out.stats.evaluations = out.cells.evaluations;
  out.stats.deepest = out.cells.deepest;

  const double max_step = kStepPerCell * enclosure.grid.max_edge();
  const ArcPieces pieces = sample_proved_arcs(equations, box, out.cells, {max_step}, out.samples, budget);
  out.stats.pieces = pieces.pieces;
  out.stats.closed_pieces = pieces.closed;
  out.stats.face_crossings = pieces.face_crossings;
  sample_unproved(equations, box, out);
  out.tree = CurveCellTree(out.cells, box);

  // Spacing (largest linked chord, plus the arc's excess over the chord for turns <= max_turn)
  // and scale.
  CurveSamples& s = out.samples;
  double longest = 0.0;
  Vec3 lo{}, hi{};
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s.next[i] >= 0)
      longest = std::max(longest, norm(s.points[static_cast<std::size_t>(s.next[i])] - s.points[i]));
    for (int k = 0; k < 3; ++k) {
      lo[k] = i == 0 ? s.points[i][k] : std::min(lo[k], s.points[i][k]);
      hi[k] = i == 0 ? s.points[i][k] : std::max(hi[k], s.points[i][k]);
    }
  }
  s.spacing = 1.01 * std::max(longest, max_step);
  out.scale = std::max(norm(hi - lo), 1e-300);
  out.stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace footpoint
