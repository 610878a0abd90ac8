#include "parametric/seeding/surface_cells.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>

#include "formula/interval.hpp"
#include "geometry/compile_budget.hpp"

namespace footpoint {

namespace {

struct Rect {
  double u0, u1, v0, v1;
};

// The subdivision as it is built: a binary tree over parameter rectangles. Its leaves are the
// cells; the search hierarchy (SurfaceCellNodes) is built over their boxes at the end.
struct BinaryNode {
  std::int32_t child[2]{-1, -1};
};

struct Evaluated {
  SurfaceJet jet;
  bool finite = false;
  double rho = 0.0;
  double rho2 = 0.0;
  double extent = 0.0;
  double score = 0.0;   // rho / extent: how far the cell is from flat
  bool split_u = true;  // the cell is longer along u on the surface
};

double finite_or_zero(double x) { return std::isfinite(x) ? x : 0.0; }

double chord(const Vec3& a, const Vec3& b) { return finite_or_zero(norm(a - b)); }

Evaluated evaluate(const SurfaceFormulas& f, const Rect& r) {
  Evaluated e;
  const double uc = 0.5 * (r.u0 + r.u1), vc = 0.5 * (r.v0 + r.v1);
  const double hu = 0.5 * (r.u1 - r.u0), hv = 0.5 * (r.v1 - r.v0);
  e.jet = f.jet(uc, vc);
  e.finite = is_finite(e.jet);
  // corners, edge midpoints, the centres of the four quarters, and the quarter points of the
  // centre lines
  constexpr int K = 16;
  const double du[K] = {-hu,       hu,       -hu,       hu,       0,         0,        -hu, hu,
                        -0.5 * hu, 0.5 * hu, -0.5 * hu, 0.5 * hu, -0.5 * hu, 0.5 * hu, 0,   0};
  const double dv[K] = {-hv,       -hv,       hv,       hv,       -hv, hv, 0,         0,
                        -0.5 * hv, -0.5 * hv, 0.5 * hv, 0.5 * hv, 0,   0,  -0.5 * hv, 0.5 * hv};
  Vec3 s[K];
  for (int k = 0; k < K; ++k) s[k] = f.point(uc + du[k], vc + dv[k]);
  // Lengths on the surface along u and v: polylines through the samples (a chord alone is 0 for a
  // closed parameter line, e.g. u over a full period), and |s_u| x width at the centre.
  const double along_u =
      std::max({chord(s[0], s[4]) + chord(s[4], s[1]), chord(s[2], s[5]) + chord(s[5], s[3]),
                chord(s[6], s[12]) + chord(s[12], e.jet.s) + chord(e.jet.s, s[13]) + chord(s[13], s[7]),
                finite_or_zero(norm(e.jet.su) * 2.0 * hu)});
  const double along_v =
      std::max({chord(s[0], s[6]) + chord(s[6], s[2]), chord(s[1], s[7]) + chord(s[7], s[3]),
                chord(s[4], s[14]) + chord(s[14], e.jet.s) + chord(e.jet.s, s[15]) + chord(s[15], s[5]),
                finite_or_zero(norm(e.jet.sv) * 2.0 * hv)});
  e.extent = std::max({along_u, along_v, chord(s[3], s[0]), chord(s[2], s[1])});
  e.split_u = along_u >= along_v;
  if (!e.finite) return e;  // nothing to model: no error estimate, no refinement by flatness
  double dev_lin = 0.0, dev_quad = 0.0, dev_u = 0.0, dev_v = 0.0;
  for (int k = 0; k < K; ++k) {
    if (!is_finite(s[k])) continue;
    const Vec3 lin = e.jet.s + e.jet.su * du[k] + e.jet.sv * dv[k];
    const Vec3 quad = taylor_point(e.jet, du[k], dv[k]);
    const double dl = norm(s[k] - lin);
    dev_lin = std::max(dev_lin, dl);
    dev_quad = std::max(dev_quad, norm(s[k] - quad));
    if (dv[k] == 0.0) dev_u = std::max(dev_u, dl);
    if (du[k] == 0.0) dev_v = std::max(dev_v, dl);
  }
  // Split where the model is worse (along u or along v); where both are as good (a plane, or a
  // twist u*v that no pure direction sees), where the cell is longer. Splitting where it is longer
  // alone would cut a polar wedge (u around a pole) along its radius for ever.
  if (dev_u != dev_v) e.split_u = dev_u > dev_v;
  // Between the samples the tangent-plane error differs from its sampled maximum by at most the
  // third-order remainder, i.e. about the quadratic model's error: take it twice. A few ulps of
  // the coordinates cover the rounding of the model itself.
  const double ulps = 8.0 * std::numeric_limits<double>::epsilon() * (norm(e.jet.s) + e.extent);
  e.rho = dev_lin + 2.0 * dev_quad + ulps;
  e.rho2 = 2.0 * dev_quad + ulps;
  e.score = e.extent > 0.0 ? (e.rho - ulps) / e.extent : 0.0;
  return e;
}

// The rigorous bounds of a cell whose centre jet is `centre` (see SurfaceCellBounds).
SurfaceCellBounds cell_bounds(const SurfaceFormulas& f, const Rect& r, const SurfaceJet& centre) {
  SurfaceCellBounds b;
  b.enclosure = enclose_box<2>(f.program(), {r.u0, r.v0}, {r.u1, r.v1});
  const double uc = 0.5 * (r.u0 + r.u1), vc = 0.5 * (r.v0 + r.v1);
  const PointEnclosure<2> exact = enclose_point<2>(f.program(), {uc, vc});
  b.centre_valid = exact.valid && is_finite(centre);
  b.rho = std::numeric_limits<double>::infinity();
  if (!b.centre_valid) return b;
  // |exact - stored| <= |ball mid - stored| + ball radius, rounded up
  auto apart = [](const Vec3& stored, const Vec3& mid, const Vec3& rad) {
    Vec3 d;
    for (int k = 0; k < 3; ++k) d[k] = (std::abs(stored[k] - mid[k]) + rad[k]) * (1.0 + 0x1p-50);
    return d;
  };
  b.s_rad = apart(centre.s, exact.s, exact.s_rad);
  b.su_rad = apart(centre.su, exact.ds[0], exact.ds_rad[0]);
  b.sv_rad = apart(centre.sv, exact.ds[1], exact.ds_rad[1]);
  if (!b.enclosure.smooth) return b;
  // per coordinate: the centre's rounding, the first partials' rounding times the half-widths, and
  // the remainder ½ (hu^2 |s_uu| + 2 hu hv |s_uv| + hv^2 |s_vv|)
  const double hu = 0.5 * (r.u1 - r.u0), hv = 0.5 * (r.v1 - r.v0);
  const BoxEnclosure<2>& e = b.enclosure;
  double rho2 = 0.0;
  for (int k = 0; k < 3; ++k) {
    auto mag = [&](int pair) { return std::abs(e.d2_mid[pair][k]) + e.d2_rad[pair][k]; };
    const double remainder = 0.5 * (hu * hu * mag(0) + 2.0 * hu * hv * mag(1) + hv * hv * mag(2));
    const double ek = b.s_rad[k] + b.su_rad[k] * hu + b.sv_rad[k] * hv + remainder;
    rho2 += ek * ek;
  }
  b.rho = std::sqrt(rho2) * (1.0 + 0x1p-46);
  if (std::isnan(b.rho)) b.rho = std::numeric_limits<double>::infinity();
  return b;
}

}  // namespace

SurfaceCells::SurfaceCells(const SurfaceFormulas& formulas, const ParamBox& box, CompileBudget& budget,
                           const SurfaceSeedingOptions& options, const SelfCovering& covering)
    : covering_(covering) {
  for (int k = 0; k < 4; ++k) {
    SurfaceCorner& c = corners_[static_cast<std::size_t>(k)];
    c.u = k % 2 == 0 ? box.umin : box.umax;
    c.v = k < 2 ? box.vmin : box.vmax;
    c.jet = formulas.jet(c.u, c.v);
    c.finite = is_finite(c.jet.s);
  }
  std::vector<BinaryNode> nodes;
  std::vector<Rect> rects;
  std::vector<Evaluated> evals;
  std::vector<int> depths;
  // a rectangle that is a translate of another part of the box (parametric/geometry/self_covering.hpp) adds
  // no point of the surface: it is neither evaluated, refined nor a cell
  std::vector<bool> covered;
  auto add_node = [&](const Rect& r, int depth) {
    nodes.emplace_back();
    rects.push_back(r);
    covered.push_back(covering.covered(box, r.u0, r.u1, r.v0, r.v1));
    evals.push_back(covered.back() ? Evaluated{} : evaluate(formulas, r));
    depths.push_back(depth);
    return static_cast<std::int32_t>(nodes.size() - 1);
  };
  auto kept = [&](std::int32_t i) { return !covered[static_cast<std::size_t>(i)]; };
  auto split = [&](std::int32_t i) {
    const Rect r = rects[static_cast<std::size_t>(i)];
    const int depth = depths[static_cast<std::size_t>(i)] + 1;
    Rect a = r, b = r;
    if (evals[static_cast<std::size_t>(i)].split_u) {
      a.u1 = b.u0 = 0.5 * (r.u0 + r.u1);
    } else {
      a.v1 = b.v0 = 0.5 * (r.v0 + r.v1);
    }
    const std::int32_t ia = add_node(a, depth);
    const std::int32_t ib = add_node(b, depth);
    nodes[static_cast<std::size_t>(i)].child[0] = ia;
    nodes[static_cast<std::size_t>(i)].child[1] = ib;
    return std::pair{ia, ib};
  };

  const int max_cells =
      static_cast<int>(std::clamp<std::size_t>(options.max_bytes / bytes_per_cell(), 1, 1 << 24));
  const int min_cells = std::clamp(options.min_cells, 1, max_cells);
  const int target_cells = std::clamp(options.target_cells, min_cells, max_cells);
  // deeper than this (2^-24 of the domain in both directions) a cell is not split
  constexpr int max_depth = 48;
  std::vector<std::int32_t> open{add_node({box.umin, box.umax, box.vmin, box.vmax}, 0)};
  // uniform subdivision, breadth first
  while (static_cast<int>(open.size()) < min_cells && static_cast<int>(open.size()) * 2 <= max_cells) {
    std::vector<std::int32_t> next;
    next.reserve(open.size() * 2);
    for (std::int32_t i : open) {
      budget.check();
      const auto [a, b] = split(i);
      if (kept(a)) next.push_back(a);
      if (kept(b)) next.push_back(b);
    }
    open.swap(next);
  }
  // adaptive refinement, worst cell first: to the target flatness within target_cells, and on
  // to the resolved flatness within the memory cap
  auto worse = [&](std::int32_t a, std::int32_t b) {
    return evals[static_cast<std::size_t>(a)].score < evals[static_cast<std::size_t>(b)].score;
  };
  std::priority_queue<std::int32_t, std::vector<std::int32_t>, decltype(worse)> queue(worse, open);
  int leaves = static_cast<int>(open.size());
  while (!queue.empty()) {
    budget.check();
    const std::int32_t i = queue.top();
    const double score = evals[static_cast<std::size_t>(i)].score;
    const bool refine = (score > options.flatness && leaves < target_cells) ||
                        (score > options.resolved_flatness && leaves < max_cells);
    if (!refine) break;
    queue.pop();
    if (depths[static_cast<std::size_t>(i)] >= max_depth) continue;
    const auto [a, b] = split(i);
    leaves += static_cast<int>(kept(a)) + static_cast<int>(kept(b)) - 1;
    if (kept(a)) queue.push(a);
    if (kept(b)) queue.push(b);
  }
  // the leaves: cells with their rigorous boxes
  cells_.reserve(static_cast<std::size_t>(leaves));
  bounds_.reserve(static_cast<std::size_t>(leaves));
  std::vector<SpaceLeaf> leaves_in_space;
  leaves_in_space.reserve(static_cast<std::size_t>(leaves));
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    if (nodes[i].child[0] >= 0 || covered[i]) continue;
    const Rect& r = rects[i];
    const Evaluated& e = evals[i];
    SurfaceCell cell;
    cell.u0 = r.u0;
    cell.u1 = r.u1;
    cell.v0 = r.v0;
    cell.v1 = r.v1;
    cell.centre = e.jet;
    cell.rho = e.rho;
    cell.rho2 = e.rho2;
    cell.extent = e.extent;
    cell.finite = e.finite;
    cell.resolved = e.score <= options.resolved_flatness;
    cell.fine = e.score <= options.flatness;
    cell.E = dot(e.jet.su, e.jet.su);
    cell.F = dot(e.jet.su, e.jet.sv);
    cell.G = dot(e.jet.sv, e.jet.sv);
    {
      const Vec3 n = cross(e.jet.su, e.jet.sv);
      const double n_len = norm(n), su_len = norm(e.jet.su);
      const double hu = 0.5 * (r.u1 - r.u0), hv = 0.5 * (r.v1 - r.v0);
      cell.framed = e.finite && n_len > 0.0 && su_len > 0.0 && std::isfinite(n_len);
      if (cell.framed) {
        cell.unit_normal = n * (1.0 / n_len);
        cell.e1 = e.jet.su * (1.0 / su_len);
        cell.e2 = cross(cell.unit_normal, cell.e1);
        cell.half1 = su_len * hu + std::abs(dot(e.jet.sv, cell.e1)) * hv;
        cell.half2 = std::abs(dot(e.jet.sv, cell.e2)) * hv;
      }
    }
    const formula::Interval x[2] = {{r.u0, r.u1}, {r.v0, r.v1}};
    formula::Interval out[3];
    formulas.program().intervals(x, out);
    constexpr double inf = std::numeric_limits<double>::infinity();
    SpaceLeaf leaf;
    for (int k = 0; k < 3; ++k) {
      leaf.lo[k] = std::isnan(out[k].lo) ? -inf : out[k].lo;
      leaf.hi[k] = std::isnan(out[k].hi) ? inf : out[k].hi;
    }
    leaf.cell = static_cast<std::int32_t>(cells_.size());
    leaves_in_space.push_back(leaf);
    cells_.push_back(cell);
    budget.check();
    budget.grow(sizeof(SurfaceCell) + sizeof(SurfaceCellBounds));
    bounds_.push_back(cell_bounds(formulas, r, e.jet));
  }
  // sub-boxes on demand (by default up to four pairs per cell, at least 4096 pairs, ~4 MB; about
  // 1 KB a pair, allocated as they are made): the certificates' boxes near folds, kept, are read at
  // the next point instead of enclosed by an interval jet again (bench/surface_bench's batch column)
  refinement_ = std::make_unique<SurfaceRefinement>(
      formulas.program(), cells_.size(),
      std::max(options.refinement_pairs_per_cell * cells_.size(), options.min_refinement_pairs));
  // The search hierarchy is built over the cells' boxes in space, not over the parameter
  // subdivision: a surface folded or turned in space puts cells far apart in parameters side by
  // side, and boxes grouped by where they are overlap less. The whole surface's box is the union.
  lo_ = leaves_in_space[0].lo;
  hi_ = leaves_in_space[0].hi;
  for (const SpaceLeaf& l : leaves_in_space)
    for (int c = 0; c < 3; ++c) {
      lo_[c] = std::min(lo_[c], l.lo[c]);
      hi_[c] = std::max(hi_[c], l.hi[c]);
    }
  if (leaves_in_space.size() == 1) return;  // a single cell: no node
  build_space_tree(leaves_in_space, 0, leaves_in_space.size());
  nodes_.shrink_to_fit();
}

// A node over leaves[begin, end): four groups (fewer when there are fewer leaves), by two rounds
// of median splits of the boxes' centres along their longest spread; a group of one leaf is a
// leaf child, a larger one a node of its own. Nodes come before their children.
std::int32_t SurfaceCells::build_space_tree(std::vector<SpaceLeaf>& leaves, std::size_t begin,
                                            std::size_t end) {
  const auto index = static_cast<std::int32_t>(nodes_.size());
  nodes_.emplace_back();
  auto centre = [](const SpaceLeaf& l, int c) {
    const double m = 0.5 * (l.lo[c] + l.hi[c]);
    return std::isfinite(m) ? m : 0.0;  // an unbounded box (a cell where s is not finite)
  };
  auto split = [&](std::size_t b, std::size_t e) {  // partitions [b, e) at its median; the middle
    double lo[3], hi[3];
    for (int c = 0; c < 3; ++c) lo[c] = std::numeric_limits<double>::infinity(), hi[c] = -lo[c];
    for (std::size_t i = b; i < e; ++i)
      for (int c = 0; c < 3; ++c) {
        lo[c] = std::min(lo[c], centre(leaves[i], c));
        hi[c] = std::max(hi[c], centre(leaves[i], c));
      }
    int axis = 0;
    for (int c = 1; c < 3; ++c)
      if (hi[c] - lo[c] > hi[axis] - lo[axis]) axis = c;
    const std::size_t m = b + (e - b) / 2;
    std::nth_element(
        leaves.begin() + static_cast<std::ptrdiff_t>(b), leaves.begin() + static_cast<std::ptrdiff_t>(m),
        leaves.begin() + static_cast<std::ptrdiff_t>(e),
        [&](const SpaceLeaf& x, const SpaceLeaf& y) { return centre(x, axis) < centre(y, axis); });
    return m;
  };
  constexpr int W = SurfaceCellNode::kWidth;
  std::size_t bounds[W + 1];
  int groups = 0;
  if (end - begin <= static_cast<std::size_t>(W)) {
    groups = static_cast<int>(end - begin);
    for (int g = 0; g <= groups; ++g) bounds[g] = begin + static_cast<std::size_t>(g);
  } else {
    const std::size_t mid = split(begin, end);
    bounds[0] = begin;
    bounds[1] = split(begin, mid);
    bounds[2] = mid;
    bounds[3] = split(mid, end);
    bounds[4] = end;
    groups = W;
  }
  SurfaceCellNode node;
  constexpr double inf = std::numeric_limits<double>::infinity();
  for (int c = 0; c < 3; ++c)
    for (int k = 0; k < W; ++k) {
      node.lo[c][k] = inf;
      node.hi[c][k] = -inf;
    }
  for (int k = 0; k < W; ++k) node.child[k] = -1;
  node.children = groups;
  for (int k = 0; k < groups; ++k)
    for (std::size_t i = bounds[k]; i < bounds[k + 1]; ++i)
      for (int c = 0; c < 3; ++c) {
        node.lo[c][k] = std::min(node.lo[c][k], leaves[i].lo[c]);
        node.hi[c][k] = std::max(node.hi[c][k], leaves[i].hi[c]);
      }
  nodes_[static_cast<std::size_t>(index)] = node;
  for (int k = 0; k < groups; ++k) {
    const std::int32_t child = bounds[k + 1] - bounds[k] == 1
                                   ? ~leaves[bounds[k]].cell
                                   : build_space_tree(leaves, bounds[k], bounds[k + 1]);
    nodes_[static_cast<std::size_t>(index)].child[k] = child;
  }
  return index;
}

double SurfaceCells::root_distance2(const Vec3& p) const {
  double d2 = 0.0;
  for (int c = 0; c < 3; ++c) {
    const double d = std::max({lo_[c] - p[c], 0.0, p[c] - hi_[c]});
    d2 += d * d;
  }
  return d2;
}

std::size_t SurfaceCells::memory_bytes() const {
  return sizeof(*this) + nodes_.capacity() * sizeof(SurfaceCellNode) +
         cells_.capacity() * sizeof(SurfaceCell) + bounds_bytes() +
         covering_.translations.capacity() * sizeof(covering_.translations[0]);
}

}  // namespace footpoint
