#include "implicit/seeding/implicit_surface_cells.hpp"

#include <cstring>

#include <algorithm>
#include <cmath>
#include <string>

#include "geometry/compile_budget.hpp"
#include "geometry/dense_solve.hpp"
#include "geometry/geometry_error.hpp"

namespace footpoint {

namespace {

using formula::interval::add;
using formula::interval::intersect;
using formula::interval::mul;
using formula::interval::sub;

// An enclosure of f over the box: the natural one intersected with the mean value form.
Interval enclosure(const ImplicitSurfaceEquation& equation, const Box3& box) {
  const ImplicitSurfaceIntervalJet j = equation.interval_gradient(box);
  if (!j.lipschitz) return j.f;
  const Vec3 c = box.center();
  Interval mean = equation.value_enclosure({c, c});
  for (int k = 0; k < 3; ++k) mean = add(mean, mul(j.grad[k], sub({box.lo[k], box.hi[k]}, {c[k], c[k]})));
  const Interval both = intersect(j.f, mean);
  return formula::interval::is_empty(both) ? j.f : both;
}

// Newton on grad f = 0 (the Hessian as Jacobian) from x: a singular point when it converges to a
// point where f vanishes too.
bool newton_singular(const ImplicitSurfaceEquation& equation, const Box3& cell, Vec3& x) {
  for (int n = 0; n < 30; ++n) {
    const ImplicitSurfaceJet j = equation.jet(x);
    Matrix<3> h;
    Vector<3> g{j.grad.x, j.grad.y, j.grad.z};
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) h[r][c] = j.hess[r][c];
    if (!dense_solve<3>(h, g)) return false;
    const Vec3 dx{-g[0], -g[1], -g[2]};
    x += dx;
    if (!is_finite(x) || !cell.contains(x, cell.max_edge())) return false;
    if (norm(dx) <= 1e-15 * std::max(1.0, norm(x))) break;
  }
  const ImplicitSurfaceJet j = equation.jet(x);
  double scale = 0.0;
  for (const Vec3& row : j.hess)
    scale = std::max({scale, std::fabs(row.x), std::fabs(row.y), std::fabs(row.z)});
  const double size = std::max(1.0, norm(x));
  // f(x) = 0 within its own rounding (the point enclosure holds 0), or within what Newton's last
  // rounding-level step, ~1e-14 |x|, leaves of a quadratic form: H |dx|^2.
  const Interval at = equation.value_enclosure({x, x});
  return (!at.excludes_zero() || std::fabs(j.f) <= 1e-28 * scale * size * size) &&
         norm(j.grad) <= 1e-10 * (scale * size + 1e-300);
}

// The zeros of f along the segment a + t (b - a), t in [0, 1]: interval subdivision of the
// segment, bisection then Newton on each sign change, and the subintervals that shrink to
// 2^-40 of the edge without a sign change but with |f| at the rounding level (a tangency).
void edge_zeros(const ImplicitSurfaceEquation& equation, Vec3 a, Vec3 b, std::vector<Vec3>& out,
                std::size_t& examined, std::size_t max_cells, CompileBudget& budget) {
  struct Piece {
    double t0, t1;
  };
  auto at = [&](double t) { return a + t * (b - a); };
  auto segment_box = [&](double t0, double t1) { return Box3{min(at(t0), at(t1)), max(at(t0), at(t1))}; };
  std::vector<Piece> stack{{0.0, 1.0}};
  while (!stack.empty()) {
    budget.check();
    if (++examined > max_cells)
      throw GeometryError("geometry_too_complex", "domain", -1,
                          "the surface meets the box's edges too often to resolve within " +
                              std::to_string(max_cells) + " cells; shrink the box");
    const Piece piece = stack.back();
    stack.pop_back();
    const Box3 box = segment_box(piece.t0, piece.t1);
    const ImplicitSurfaceIntervalJet j = equation.interval_gradient(box);
    if (j.f.excludes_zero()) continue;
    const Interval along = ivec::dot(j.grad, ivec::of_point(b - a));
    const double f0 = equation.value(at(piece.t0)), f1 = equation.value(at(piece.t1));
    if (j.lipschitz && along.excludes_zero()) {
      // f is monotone here: at most one zero, where the ends' signs differ (or an end is one).
      if (f0 == 0.0) out.push_back(at(piece.t0));
      if (f1 == 0.0) out.push_back(at(piece.t1));
      if (f0 * f1 >= 0.0) continue;
      double lo = piece.t0, hi = piece.t1, flo = f0;
      for (int n = 0; n < 200 && hi - lo > 0.0; ++n) {
        const double mid = 0.5 * (lo + hi);
        if (mid <= lo || mid >= hi) break;
        const double fm = equation.value(at(mid));
        if (fm == 0.0) {
          lo = hi = mid;
          break;
        }
        if ((fm < 0.0) == (flo < 0.0)) {
          lo = mid;
          flo = fm;
        } else {
          hi = mid;
        }
      }
      out.push_back(at(0.5 * (lo + hi)));
      continue;
    }
    if (piece.t1 - piece.t0 <= 0x1p-40) {
      const double t = 0.5 * (piece.t0 + piece.t1);
      const ImplicitSurfaceJet jm = equation.jet(at(t));
      if (std::fabs(jm.f) <= 1e-12 * std::max(1.0, norm(jm.grad) * norm(b - a))) out.push_back(at(t));
      continue;
    }
    const double mid = 0.5 * (piece.t0 + piece.t1);
    stack.push_back({mid, piece.t1});
    stack.push_back({piece.t0, mid});
  }
}

void add_distinct(std::vector<Vec3>& points, Vec3 x, double same) {
  for (const Vec3& y : points)
    if (norm(x - y) <= same) return;
  points.push_back(x);
}

}  // namespace

Box3 octant_of(const Box3& box, int octant) {
  const Vec3 c = box.center();
  Box3 b;
  for (int k = 0; k < 3; ++k) {
    const bool upper = (octant >> k) & 1;
    b.lo[k] = upper ? c[k] : box.lo[k];
    b.hi[k] = upper ? box.hi[k] : c[k];
  }
  return b;
}

bool land_on_surface(const ImplicitSurfaceEquation& equation, Vec3& x, int iterations) {
  for (int n = 0; n < iterations; ++n) {
    const ImplicitSurfaceJet j = equation.jet(x);
    const double g2 = norm2(j.grad);
    if (!(g2 > 0.0) || !std::isfinite(j.f)) return false;
    const Vec3 dx = (j.f / g2) * j.grad;
    x -= dx;
    if (!is_finite(x)) return false;
    if (norm(dx) <= 1e-14 * (1.0 + norm(x))) return true;
  }
  return false;
}

void LeafEnclosureCache::reset(std::size_t leaves) {
  size_ = leaves;
  state_ = std::make_unique<std::atomic<std::uint8_t>[]>(leaves);
  for (std::size_t i = 0; i < leaves; ++i) state_[i].store(0, std::memory_order_relaxed);
  // Uninitialized: an entry is written (and its pages touched) when its leaf is first used.
  storage_.reset(new unsigned char[leaves * sizeof(LeafEnclosures)]);
}

LeafEnclosures LeafEnclosureCache::get(const ImplicitSurfaceEquation& equation, std::int32_t leaf,
                                       const Box3& box) const {
  std::atomic<std::uint8_t>& state = state_[static_cast<std::size_t>(leaf)];
  unsigned char* kept = storage_.get() + static_cast<std::size_t>(leaf) * sizeof(LeafEnclosures);
  if (state.load(std::memory_order_acquire) == 2) {
    LeafEnclosures e;
    std::memcpy(&e, kept, sizeof e);
    return e;
  }
  const Vec3 c = box.center();
  const ImplicitSurfaceIntervalJet at = equation.interval_gradient({c, c});
  const LeafEnclosures e{equation.interval_jet(box), equation.value_enclosure({c, c}), at.f, at.grad};
  std::uint8_t unclaimed = 0;
  if (state.compare_exchange_strong(unclaimed, 1, std::memory_order_acq_rel)) {
    std::memcpy(kept, &e, sizeof e);
    state.store(2, std::memory_order_release);
  }
  return e;
}

std::size_t LeafEnclosureCache::memory_bytes() const {
  return size_ * (sizeof(std::atomic<std::uint8_t>) + sizeof(LeafEnclosures));
}

std::size_t ImplicitSurfaceCells::memory_bytes() const {
  return sizeof(*this) + cells.capacity() * sizeof(ImplicitSurfaceCell) + samples.capacity() * sizeof(Vec3) +
         leaf_enclosures.memory_bytes() + edge_points.capacity() * sizeof(BoxEdgePoint) +
         singular_points.capacity() * sizeof(Vec3) + (sample_index ? sample_index->memory_bytes() : 0);
}

ImplicitSurfaceCells subdivide_surface(const ImplicitSurfaceEquation& equation, const Box3& box,
                                       CompileBudget& budget, const ImplicitSurfaceCellSettings& settings) {
  ImplicitSurfaceCells out;
  out.box = box;
  auto count = [&]() {
    budget.check();
    if (++out.examined > settings.max_cells)
      throw GeometryError("geometry_too_complex", "domain", -1,
                          "the surface is too intricate to resolve in this box within the limit of " +
                              std::to_string(settings.max_cells) + " cells; shrink the box");
  };
  count();
  if (enclosure(equation, box).excludes_zero()) return out;
  out.cells.push_back({box});
  out.leaf_diagonal = box.diagonal() * std::ldexp(1.0, -settings.levels);
  // Breadth first, level by level: the children of a cell are consecutive.
  std::size_t level_begin = 0;
  std::vector<std::int32_t> singular_candidates;
  for (int level = 0; level < settings.levels; ++level) {
    const std::size_t level_end = out.cells.size();
    for (std::size_t i = level_begin; i < level_end; ++i) {
      const Box3 parent = out.cells[i].box;
      const auto first = static_cast<std::int32_t>(out.cells.size());
      for (int octant = 0; octant < 8; ++octant) {
        count();
        const Box3 child = octant_of(parent, octant);
        if (enclosure(equation, child).excludes_zero()) continue;
        budget.grow(sizeof(ImplicitSurfaceCell));
        out.cells.push_back({child});
      }
      out.cells[i].first_child = first;
      out.cells[i].children = static_cast<std::int32_t>(out.cells.size()) - first;
    }
    level_begin = level_end;
  }
  const double same = 1e-9 * std::max(1.0, box.diagonal());
  for (ImplicitSurfaceCell& cell : out.cells) {
    if (cell.first_child >= 0) continue;  // split (a cell whose octants all excluded S holds none)
    cell.leaf = static_cast<std::int32_t>(out.leaves);
    ++out.leaves;
    budget.check();
    Vec3 x = cell.box.center();
    if (land_on_surface(equation, x) && cell.box.contains(x, 0.5 * cell.box.max_edge()) && box.contains(x)) {
      cell.sample = static_cast<std::int32_t>(out.samples.size());
      budget.grow(sizeof(Vec3));
      out.samples.push_back(x);
    }
    const ImplicitSurfaceIntervalJet j = equation.interval_gradient(cell.box);
    if (!j.grad[0].excludes_zero() && !j.grad[1].excludes_zero() && !j.grad[2].excludes_zero()) {
      Vec3 s = cell.box.center();
      if (newton_singular(equation, cell.box, s) && box.contains(s))
        add_distinct(out.singular_points, s, same);
    }
  }
  // The twelve edges: along axis k, the other two coordinates at their bounds.
  std::vector<Vec3> on_edges;
  for (int k = 0; k < 3; ++k)
    for (int corner = 0; corner < 4; ++corner) {
      Vec3 a = box.lo, b;
      const int i = (k + 1) % 3, l = (k + 2) % 3;
      a[i] = (corner & 1) ? box.hi[i] : box.lo[i];
      a[l] = (corner & 2) ? box.hi[l] : box.lo[l];
      b = a;
      a[k] = box.lo[k];
      b[k] = box.hi[k];
      std::vector<Vec3> zeros;
      edge_zeros(equation, a, b, zeros, out.examined, settings.max_cells, budget);
      for (const Vec3& z : zeros) add_distinct(on_edges, z, same);
    }
  for (const Vec3& x : on_edges) {
    int at_bounds = 0;
    for (int k = 0; k < 3; ++k) at_bounds += (x[k] == box.lo[k] || x[k] == box.hi[k]) ? 1 : 0;
    out.edge_points.push_back({x, at_bounds == 3});
  }
  budget.grow(out.leaves * (sizeof(std::atomic<std::uint8_t>) + sizeof(LeafEnclosures)));
  out.leaf_enclosures.reset(out.leaves);
  out.sample_index = std::make_shared<const PointIndex>(out.samples);
  return out;
}

}  // namespace footpoint
