#include "implicit/seeding/curve_arc_samples.hpp"

#include <cmath>
#include <limits>
#include <map>
#include <utility>

#include "geometry/compile_budget.hpp"
#include "implicit/geometry/curve_correction.hpp"
#include "implicit/geometry/implicit_curve_differentials.hpp"

namespace footpoint {
namespace {

// Bisections of an arc's x_k-range before it is left as it is (a cell ~2^-40 of the curve).
constexpr int kMaxDepth = 40;

double angle_between(Vec3 a, Vec3 b) { return std::atan2(norm(cross(a, b)), dot(a, b)); }

// The axis of the cell's face that the crossing lies on (its enclosure is flat there), or -1.
int face_axis(const FaceCrossing& c, const Box3& cell, int dims) {
  for (int a = 0; a < dims; ++a)
    if (c.enclosure.lo[a] == c.enclosure.hi[a] &&
        (c.enclosure.lo[a] == cell.lo[a] || c.enclosure.lo[a] == cell.hi[a]))
      return a;
  return -1;
}

class ArcChains {
 public:
  ArcChains(const ImplicitEquations& eq, const Box3& box, const CurveCells& cells,
            const ArcSampling& settings, CurveSamples& samples, CompileBudget& budget)
      : eq_(eq), box_(box), cells_(cells), settings_(settings), samples_(samples), budget_(budget) {}

  ArcPieces run() {
    join_crossings();
    collect_arcs();
    // Paths from their free ends first, then the loops that are left.
    for (std::size_t v = 0; v < nodes_.size(); ++v)
      if (nodes_[v].arcs.size() == 1 && !visited_[static_cast<std::size_t>(nodes_[v].arcs[0])])
        walk(v, false);
    for (std::size_t v = 0; v < nodes_.size(); ++v)
      for (int e : nodes_[v].arcs)
        if (!visited_[static_cast<std::size_t>(e)]) walk(v, true);
    return pieces_;
  }

 private:
  struct Node {
    Vec3 point;
    bool box_face = false;
    std::vector<int> arcs;  // at most two: one end of an arc on each side of a face
    std::int32_t sample = -1;
  };
  struct Arc {
    int from, to;  // nodes
    std::int32_t cell;
  };
  struct ChainPoint {
    Vec3 x;
    int node = -1;           // the arc end it is, or -1 for a sample between ends
    Vec3 tangent{};          // unit, either orientation
    std::int32_t cell = -1;  // the cell of the arc from the chain's previous point to this one
    bool forced = false;     // kept whatever the thinning says
  };

  // Crossings on the box's faces are path ends; the others meet their twin across the face.
  void join_crossings() {
    const int dims = eq_.planar() ? 2 : 3;
    const std::size_t n = cells_.crossings.size();
    node_of_.assign(n, -1);
    std::map<std::pair<int, double>, std::vector<std::int32_t>> planes;
    cell_of_.assign(n, -1);
    for (std::size_t c = 0; c < cells_.cells.size(); ++c) {
      const ProvedCell& cell = cells_.cells[c];
      for (std::int32_t i = cell.first_crossing; i < cell.first_crossing + cell.crossing_count; ++i) {
        cell_of_[static_cast<std::size_t>(i)] = static_cast<std::int32_t>(c);
        const FaceCrossing& x = cells_.crossings[static_cast<std::size_t>(i)];
        const int a = face_axis(x, cell.box, dims);
        const double v = a >= 0 ? x.enclosure.lo[a] : 0.0;
        if (a >= 0 && (v == box_.lo[a] || v == box_.hi[a])) {
          node_of_[static_cast<std::size_t>(i)] = new_node(x.point, true);
          ++pieces_.face_crossings;
        } else {
          planes[{a, v}].push_back(i);
        }
      }
    }
    for (const auto& [plane, list] : planes) {
      for (std::size_t i = 0; i < list.size(); ++i) {
        const auto ci = static_cast<std::size_t>(list[i]);
        if (node_of_[ci] >= 0) continue;
        node_of_[ci] = new_node(cells_.crossings[ci].point, false);
        for (std::size_t j = i + 1; j < list.size(); ++j) {
          const auto cj = static_cast<std::size_t>(list[j]);
          if (node_of_[cj] < 0 && cell_of_[cj] != cell_of_[ci] &&
              cells_.crossings[cj].enclosure.intersects(cells_.crossings[ci].enclosure)) {
            node_of_[cj] = node_of_[ci];
            break;
          }
        }
      }
    }
  }

  int new_node(Vec3 x, bool box_face) {
    nodes_.push_back({x, box_face, {}, -1});
    return static_cast<int>(nodes_.size() - 1);
  }

  void collect_arcs() {
    for (std::size_t c = 0; c < cells_.cells.size(); ++c) {
      const ProvedCell& cell = cells_.cells[c];
      for (std::int32_t i = 0; i + 1 < cell.crossing_count; i += 2) {
        const int a = node_of_[static_cast<std::size_t>(cell.first_crossing + i)];
        const int b = node_of_[static_cast<std::size_t>(cell.first_crossing + i + 1)];
        arcs_.push_back({a, b, static_cast<std::int32_t>(c)});
        nodes_[static_cast<std::size_t>(a)].arcs.push_back(static_cast<int>(arcs_.size() - 1));
        nodes_[static_cast<std::size_t>(b)].arcs.push_back(static_cast<int>(arcs_.size() - 1));
      }
    }
    visited_.assign(arcs_.size(), false);
    for (const Node& v : nodes_)
      if (v.arcs.size() == 1 && !v.box_face) ++pieces_.open_ends;
  }

  std::int32_t sample_of(std::size_t v) {
    Node& node = nodes_[v];
    if (node.sample < 0)
      node.sample = samples_.add(node.point, node.box_face ? SampleKind::box_face : SampleKind::regular);
    return node.sample;
  }

  // Follows the chain from node `start` along unvisited arcs: its points in walking order (the
  // arcs' ends and the samples between them), thinned, then added and linked.
  void walk(std::size_t start, bool loop) {
    ++pieces_.pieces;
    chain_.clear();
    chain_.push_back(chain_point(nodes_[start].point, static_cast<int>(start)));
    std::size_t v = start;
    for (;;) {
      int next = -1;
      for (int e : nodes_[v].arcs)
        if (!visited_[static_cast<std::size_t>(e)]) {
          next = e;
          break;
        }
      if (next < 0) break;
      visited_[static_cast<std::size_t>(next)] = true;
      const Arc& arc = arcs_[static_cast<std::size_t>(next)];
      const auto w = static_cast<std::size_t>(arc.from == static_cast<int>(v) ? arc.to : arc.from);
      const ProvedCell& cell = cells_.cells[static_cast<std::size_t>(arc.cell)];
      const ChainPoint end = chain_point(nodes_[w].point, static_cast<int>(w));
      const std::size_t arc_first = chain_.size();
      between(chain_.back(), end, cell, 0);
      chain_.push_back(end);
      for (std::size_t i = arc_first; i < chain_.size(); ++i) chain_[i].cell = arc.cell;
      if (w == start && loop) {
        ++pieces_.closed;
        break;
      }
      v = w;
    }
    thin_chain();
    std::int32_t last = -1;
    for (const ChainPoint& c : thinned_) {
      const std::int32_t i =
          c.node >= 0 ? sample_of(static_cast<std::size_t>(c.node)) : samples_.add(c.x, SampleKind::regular);
      if (last >= 0) samples_.link(last, i);
      last = i;
    }
  }

  // Keeps the chain's ends and, greedily from the first, the farthest point that the last kept one
  // reaches within max_step while the tangents at both and at every point between stay within
  // max_turn of the chord: the sampling's own criterion (between), over the points it replaces.
  // The crossings of cell faces are points of the chain like the others: small cells need not
  // mean dense samples. Where the farthest point in reach falls short of max_step by more than
  // a tenth and the next one is too far, a point of the curve on the stretch between them is
  // kept instead, at 0.97 max_step from the last kept (place_on_stretch): the chain's points are
  // no finer grid of the curve than its cells, and keeping only them would leave chords of about
  // two thirds of max_step. Within max_step of an end next to an unproved box (a singular point)
  // more are kept (keep_near_end): there the curvature may grow without bound (a cusp), beyond
  // what the tangents at the points tell, and the distance from p along the last stretch may dip
  // between them (a minimum that `auto` finds only from a discrete local minimum of its own).
  void thin_chain() {
    const std::size_t n = chain_.size();
    for (ChainPoint& c : chain_) c.forced = false;
    chain_.front().forced = chain_.back().forced = true;
    if (open_end(chain_.front())) keep_near_end(0, 1);
    if (open_end(chain_.back())) keep_near_end(n - 1, -1);
    thinned_.assign(1, chain_.front());
    std::size_t first = 1;  // the chain's points after thinned_.back()
    for (std::size_t x = 1; x < n;) {
      if (reaches(thinned_.back(), first, x, chain_[x])) {
        if (chain_[x].forced) {
          thinned_.push_back(chain_[x]);
          first = x + 1;
        }
        ++x;
        continue;
      }
      if (x == first) {
        // Not even the next point is in reach (the bisection in between() stopped short).
        thinned_.push_back(chain_[x]);
        first = ++x;
        continue;
      }
      ChainPoint m;
      thinned_.push_back(place_on_stretch(thinned_.back(), first, x, m) ? m : chain_[x - 1]);
      first = x;
    }
  }

  // A point m of the curve on the stretch from chain point x - 1 to x (one arc of one cell) at
  // about 0.97 max_step from `from`, which the chord from `from` reaches over the chain's points
  // [first, x - 1]; false when x - 1 is already within a tenth of max_step of that, when x is not
  // beyond max_step (the turn, not the length, stops the chord), or when the point is not found
  // inside the stretch.
  bool place_on_stretch(const ChainPoint& from, std::size_t first, std::size_t x, ChainPoint& m) const {
    const ChainPoint& a = chain_[x - 1];
    const ChainPoint& b = chain_[x];
    const double reach = 0.97 * settings_.max_step;
    const Vec3 u = a.x - from.x, v = b.x - a.x;
    if (!(norm(u) < 0.9 * settings_.max_step && norm(u + v) > settings_.max_step) || b.cell < 0) return false;
    // |u + lambda v| = reach, the root in (0, 1): |u| < reach < |u + v|.
    const double vv = dot(v, v), uv = dot(u, v);
    const double lambda = (-uv + std::sqrt(std::fmax(0.0, uv * uv - vv * (dot(u, u) - reach * reach)))) / vv;
    if (!(lambda > 0.0 && lambda < 1.0)) return false;
    const ProvedCell& cell = cells_.cells[static_cast<std::size_t>(b.cell)];
    const int k = cell.axis;
    Vec3 normal{};
    normal[k] = 1.0;
    Vec3 z;
    int iterations = 0;
    if (!curve::correct_in_normal_plane(eq_, a.x + lambda * v, normal, z, iterations) ||
        !cell.box.contains(z, 1e-12 * std::max(1.0, norm(z))) ||
        !(std::fmin(a.x[k], b.x[k]) < z[k] && z[k] < std::fmax(a.x[k], b.x[k])))
      return false;
    m = chain_point(z, -1);
    m.cell = b.cell;
    return reaches(from, first, x, m);
  }

  // An end of a chain that is no face crossing of the box and no point of a loop.
  bool open_end(const ChainPoint& c) const {
    if (c.node < 0) return false;
    const Node& node = nodes_[static_cast<std::size_t>(c.node)];
    return !node.box_face && node.arcs.size() == 1;
  }

  // Keeps, within path length max_step of chain point `end` (walking in direction `step`), every
  // chain point whose successor lies more than twice as far from it as the last kept point: the
  // kept path lengths at most double from one to the next where the chain's points allow (two
  // neighbours of the chain further apart than that stay so), and as near to a cusp as the chain
  // reaches, the samples resolve a dip of the distance at every scale the chain holds.
  void keep_near_end(std::size_t end, std::ptrdiff_t step) {
    const auto n = std::ssize(chain_);
    const auto at = [&](std::ptrdiff_t i) { return chain_[static_cast<std::size_t>(i)].x; };
    double length = 0.0, last = 0.0;  // path lengths from the end: of point i, of the last kept
    for (auto i = static_cast<std::ptrdiff_t>(end) + step; i >= 0 && i < n; i += step) {
      length += norm(at(i) - at(i - step));
      if (length > settings_.max_step) return;
      const double next = i + step >= 0 && i + step < n ? length + norm(at(i + step) - at(i))
                                                        : std::numeric_limits<double>::infinity();
      if (last == 0.0 || next > 2.0 * last) {
        chain_[static_cast<std::size_t>(i)].forced = true;
        last = length;
      }
    }
  }

  // True when the chord from a to b stands for the chain's points [first, end) between them.
  bool reaches(const ChainPoint& a, std::size_t first, std::size_t end, const ChainPoint& b) const {
    const Vec3 chord = b.x - a.x;
    if (!(norm(chord) <= settings_.max_step)) return false;
    auto along = [&](const ChainPoint& c) { return dot(c.tangent, chord) < 0.0 ? -c.tangent : c.tangent; };
    const Vec3 ta = along(a), tb = along(b);
    if (!(angle_between(ta, tb) <= settings_.max_turn) || !(angle_between(ta, chord) <= settings_.max_turn) ||
        !(angle_between(tb, chord) <= settings_.max_turn))
      return false;
    for (std::size_t i = first; i < end; ++i)
      if (!(angle_between(along(chain_[i]), chord) <= settings_.max_turn)) return false;
    return true;
  }

  // A point of the chain with its unit tangent (node: the arc end it is, or -1).
  ChainPoint chain_point(Vec3 x, int node) const { return {x, node, curve::unit_tangent(eq_.jet(x))}; }

  // Appends to the chain the samples strictly between its arc points a and b of `cell`, in order
  // from a to b.
  void between(ChainPoint a, ChainPoint b, const ProvedCell& cell, int depth) {
    budget_.check();
    const Vec3 chord = b.x - a.x;
    Vec3 ta = a.tangent, tb = b.tangent;
    if (dot(ta, chord) < 0.0) ta = -ta;
    if (dot(tb, chord) < 0.0) tb = -tb;
    if (norm(chord) <= settings_.max_step && angle_between(ta, tb) <= settings_.max_turn &&
        angle_between(ta, chord) <= settings_.max_turn && angle_between(tb, chord) <= settings_.max_turn)
      return;
    if (depth >= kMaxDepth) return;
    const int k = cell.axis;
    Vec3 y = 0.5 * (a.x + b.x);
    Vec3 normal{};
    normal[k] = 1.0;
    Vec3 m;
    int iterations = 0;
    if (!curve::correct_in_normal_plane(eq_, y, normal, m, iterations) ||
        !cell.box.contains(m, 1e-12 * std::max(1.0, norm(m))))
      return;
    const ChainPoint middle = chain_point(m, -1);
    between(a, middle, cell, depth + 1);
    chain_.push_back(middle);
    between(middle, b, cell, depth + 1);
  }

  const ImplicitEquations& eq_;
  Box3 box_;
  const CurveCells& cells_;
  ArcSampling settings_;
  CurveSamples& samples_;
  std::vector<int> node_of_;
  std::vector<std::int32_t> cell_of_;
  std::vector<Node> nodes_;
  std::vector<Arc> arcs_;
  std::vector<bool> visited_;
  std::vector<ChainPoint> chain_;    // the chain being walked
  std::vector<ChainPoint> thinned_;  // its points kept, in order
  ArcPieces pieces_;
  CompileBudget& budget_;
};

}  // namespace

ArcPieces sample_proved_arcs(const ImplicitEquations& equations, const Box3& box, const CurveCells& cells,
                             const ArcSampling& settings, CurveSamples& samples, CompileBudget& budget) {
  return ArcChains(equations, box, cells, settings, samples, budget).run();
}

}  // namespace footpoint
