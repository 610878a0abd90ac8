#include "solvers/piecewise_nearest.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace footpoint {

double distance_lower_bound(const Box3& box, const Vec3& p) {
  double sum = 0.0;
  for (int k = 0; k < 3; ++k) {
    // max(lo - p, p - hi, 0), a NaN term left out (as std::fmax does), without a call.
    double gap = 0.0;
    if (box.lo[k] - p[k] > gap) gap = box.lo[k] - p[k];
    if (p[k] - box.hi[k] > gap) gap = p[k] - box.hi[k];
    sum += gap * gap;
  }
  // Each gap, square and sum is rounded to nearest: at most 6 roundings of relative 2^-53 each.
  return std::sqrt(sum) * (1.0 - 0x1p-49);
}

PieceTree::PieceTree(std::vector<Box3> hulls) : hulls_(std::move(hulls)) {
  order_.resize(hulls_.size());
  std::iota(order_.begin(), order_.end(), 0);
  if (!hulls_.empty()) build(0, static_cast<std::int32_t>(hulls_.size()));
}

std::int32_t PieceTree::build(std::int32_t first, std::int32_t count) {
  constexpr std::int32_t kLeaf = 4;  // pieces a leaf holds
  Node node{
      hulls_[static_cast<std::size_t>(order_[static_cast<std::size_t>(first)])], first, count, {-1, -1}};
  for (std::int32_t i = first + 1; i < first + count; ++i)
    node.box =
        footpoint::hull(node.box, hulls_[static_cast<std::size_t>(order_[static_cast<std::size_t>(i)])]);
  const auto index = static_cast<std::int32_t>(nodes_.size());
  nodes_.push_back(node);
  if (count <= kLeaf) return index;
  const Vec3 extent = node.box.hi - node.box.lo;
  const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : extent.y >= extent.z ? 1 : 2;
  const auto begin = order_.begin() + first, middle = begin + count / 2, end = begin + count;
  std::nth_element(begin, middle, end, [&](std::int32_t a, std::int32_t b) {
    return hulls_[static_cast<std::size_t>(a)].center()[axis] <
           hulls_[static_cast<std::size_t>(b)].center()[axis];
  });
  const std::int32_t left = build(first, count / 2);
  const std::int32_t right = build(first + count / 2, count - count / 2);
  nodes_[static_cast<std::size_t>(index)].child[0] = left;
  nodes_[static_cast<std::size_t>(index)].child[1] = right;
  return index;
}

std::size_t PieceTree::memory_bytes() const {
  return sizeof(*this) + hulls_.capacity() * sizeof(Box3) + order_.capacity() * sizeof(std::int32_t) +
         nodes_.capacity() * sizeof(Node);
}

namespace {

double tie_gap(const ProjectionResult& r, const Vec3& p) {
  const Vec3 foot{r.foot[0], r.foot[1], r.foot[2]};
  return std::fmax(Certificate::kRelativeGap * r.distance, Certificate::absolute_gap_at(p, foot));
}

double foot_scale(const std::array<double, 3>& f) {
  return 1.0 + std::sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
}

}  // namespace

PiecewiseNearest nearest_over_pieces(
    const PieceTree& pieces, const Vec3& p, const Options& options,
    const std::function<ProjectionResult(std::size_t, const Options&, double)>& solve) {
  // Best first over the tree: entries are nodes (id >= 0) and pieces (id = -1 - piece), keyed by
  // the lower bound of their box; a node popped pushes its children (a leaf its pieces).
  struct Entry {
    double lower;
    std::int32_t id;
  };
  const auto farther = [](const Entry& a, const Entry& b) {
    return a.lower > b.lower || (a.lower == b.lower && a.id < b.id);
  };
  // The walk's storage is kept by each thread from one point to the next (no allocation a point).
  thread_local std::vector<Entry> heap;
  heap.clear();
  if (pieces.size() > 0) heap.push_back({distance_lower_bound(pieces.nodes()[0].box, p), 0});

  struct Solved {
    std::size_t piece;
    double lower;
    ProjectionResult r;
  };
  thread_local std::vector<Solved> solved;
  solved.clear();
  const Solved* best = nullptr;
  double unsolved_bound = std::numeric_limits<double>::infinity();  // the nearest box left out
  while (!heap.empty()) {
    std::pop_heap(heap.begin(), heap.end(), farther);
    const Entry e = heap.back();
    heap.pop_back();
    const bool beyond_best = best && !options.all_minima && e.lower > best->r.distance + tie_gap(best->r, p);
    if (beyond_best || e.lower > options.max_distance) {
      unsolved_bound = e.lower;
      break;
    }
    if (e.id >= 0) {
      const PieceTree::Node& node = pieces.nodes()[static_cast<std::size_t>(e.id)];
      if (node.child[0] >= 0) {
        for (const std::int32_t c : node.child) {
          heap.push_back({distance_lower_bound(pieces.nodes()[static_cast<std::size_t>(c)].box, p), c});
          std::push_heap(heap.begin(), heap.end(), farther);
        }
      } else {
        for (std::int32_t i = node.first; i < node.first + node.count; ++i) {
          const std::int32_t piece = pieces.order()[static_cast<std::size_t>(i)];
          heap.push_back({distance_lower_bound(pieces.hull(static_cast<std::size_t>(piece)), p), -1 - piece});
          std::push_heap(heap.begin(), heap.end(), farther);
        }
      }
      continue;
    }
    const auto k = static_cast<std::size_t>(-1 - e.id);
    const double cutoff =
        best ? best->r.distance + tie_gap(best->r, p) : std::numeric_limits<double>::infinity();
    solved.push_back({k, e.lower, solve(k, options, cutoff)});
    if (solved.back().r.summary.status == Status::deadline_exceeded) break;
    best = nullptr;
    for (const Solved& s : solved)
      if (std::isfinite(s.r.distance) && (!best || s.r.distance < best->r.distance)) best = &s;
  }

  PiecewiseNearest out;
  out.pieces_solved = static_cast<int>(solved.size());
  if (!best) {
    // No piece within reach: the first solved piece's answer says why (deadline, beyond
    // max_distance), or every box is beyond max_distance.
    if (!solved.empty()) {
      out.result = solved.front().r;
      out.piece = solved.front().piece;
      for (const Solved& s : solved)
        if (s.r.summary.status == Status::deadline_exceeded) out.result = s.r;
    } else {
      out.result.summary.status = Status::beyond_max_distance;
      out.result.summary.method = "auto";
      withhold_answer(out.result);
    }
    return out;
  }

  out.result = best->r;
  out.piece = best->piece;
  Summary& summary = out.result.summary;
  const double d = best->r.distance;
  const Vec3 foot{best->r.foot[0], best->r.foot[1], best->r.foot[2]};

  // The certificate: no point nearer than the least of the pieces' bounds.
  summary.starts = 0;
  summary.certificate.boxes = 0;
  double lower_bound = unsolved_bound;
  const Solved* weakest = nullptr;  // the solved piece with the smallest lower bound
  for (const Solved& s : solved) {
    summary.starts += s.r.summary.starts;
    summary.certificate.boxes += s.r.summary.certificate.boxes;
    const Certificate& c = s.r.summary.certificate;
    const double bound = c.computed ? c.lower_bound : s.lower;
    if (bound < lower_bound) {
      lower_bound = bound;
      weakest = &s;
    }
  }
  Certificate& certificate = summary.certificate;
  if (certificate.computed) {
    certificate.lower_bound = std::fmin(lower_bound, d);
    certificate.absolute_gap = Certificate::absolute_gap_at(p, foot);
    certificate.certified = Certificate::meets_gap(d, certificate.lower_bound, certificate.absolute_gap);
    if (certificate.certified)
      certificate.reason = CertificateReason::gap_met;
    else if (weakest && weakest->r.summary.certificate.computed)
      certificate.reason = weakest->r.summary.certificate.reason;
    else
      certificate.reason = CertificateReason::budget_exhausted;
  }

  // Ties: the feet of every solved piece within the gap of d, each once.
  if (summary.multiplicity.computed) {
    AnswerMultiplicity m;
    m.computed = true;
    m.feet.clear();
    const double gap = tie_gap(best->r, p);
    bool continuum = false;
    m.add_distinct(best->r.foot, kDistinctFoot * foot_scale(best->r.foot));  // the answer's first
    for (const Solved& s : solved) {
      if (!std::isfinite(s.r.distance) || s.r.distance > d + gap) continue;
      if (s.r.summary.multiplicity.kind == Multiplicity::continuum) continuum = true;
      std::vector<std::array<double, 3>> feet = s.r.summary.multiplicity.feet;
      if (feet.empty()) feet.push_back(s.r.foot);
      for (const auto& f : feet) m.add_distinct(f, kDistinctFoot * foot_scale(f));
    }
    m.settle();
    if (continuum) {
      m.kind = Multiplicity::continuum;
      m.feet.clear();
      m.count = 1;
    }
    summary.multiplicity = std::move(m);
  }

  // all_minima: the pieces' minima merged, a foot once.
  if (options.all_minima) {
    std::vector<Minimum> merged;
    for (const Solved& s : solved)
      for (const Minimum& m : s.r.minima) {
        const bool seen = std::any_of(merged.begin(), merged.end(), [&](const Minimum& o) {
          const double dx = o.foot[0] - m.foot[0], dy = o.foot[1] - m.foot[1], dz = o.foot[2] - m.foot[2];
          return std::sqrt(dx * dx + dy * dy + dz * dz) <= kDistinctFoot * foot_scale(m.foot);
        });
        if (!seen) merged.push_back(m);
      }
    std::stable_sort(merged.begin(), merged.end(),
                     [](const Minimum& a, const Minimum& b) { return a.distance < b.distance; });
    out.result.minima = std::move(merged);
    out.result.minima_truncated = false;
    cap_minima(out.result, options);
  }
  return out;
}

}  // namespace footpoint
