#include "implicit/seeding/curve_enclosure.hpp"

#include <algorithm>
#include <cmath>

#include "geometry/compile_budget.hpp"

namespace footpoint {

Box3 CellGrid::cell(const CellIndex& c) const {
  Box3 b;
  for (int k = 0; k < 3; ++k) {
    const double n = std::ldexp(1.0, bits[k]);
    const double w = box.hi[k] - box.lo[k];
    b.lo[k] = std::max(clip.lo[k], box.lo[k] + w * (c[k] / n));
    b.hi[k] = std::min(clip.hi[k], (c[k] + 1.0 == n) ? box.hi[k] : box.lo[k] + w * ((c[k] + 1.0) / n));
  }
  return b;
}

bool CellGrid::solid(const CellIndex& c) const {
  const Box3 b = cell(c);
  for (int k = 0; k < 3; ++k)
    if (box.hi[k] > box.lo[k] && !(b.lo[k] < b.hi[k])) return false;
  return true;
}

CellGrid enclosure_grid(const Box3& box) {
  // Fractions of the box's width added below and above it along x, y, z.
  constexpr double kBelow[3] = {0.0131, 0.0173, 0.0097};
  constexpr double kAbove[3] = {0.0089, 0.0151, 0.0117};
  CellGrid g;
  g.box = box;
  g.clip = box;
  for (int k = 0; k < 3; ++k) {
    const double w = box.hi[k] - box.lo[k];
    g.box.lo[k] = box.lo[k] - kBelow[k] * w;
    g.box.hi[k] = box.hi[k] + kAbove[k] * w;
  }
  return g;
}

CellIndex CellGrid::index_of(Vec3 x) const {
  CellIndex c{};
  for (int k = 0; k < 3; ++k) {
    const double n = std::ldexp(1.0, bits[k]);
    const double w = box.hi[k] - box.lo[k];
    const double s = w > 0.0 ? std::floor((x[k] - box.lo[k]) / w * n) : 0.0;
    c[k] = static_cast<std::int32_t>(std::clamp(s, 0.0, n - 1.0));
  }
  return c;
}

Vec3 CellGrid::edge() const {
  Vec3 e;
  for (int k = 0; k < 3; ++k) e[k] = std::ldexp(box.hi[k] - box.lo[k], -bits[k]);
  return e;
}

double CellGrid::max_edge() const {
  const Vec3 e = edge();
  return std::max({e.x, e.y, e.z});
}

std::array<bool, 3> CellGrid::split_axes() const {
  const Vec3 e = edge();
  const double m = max_edge();
  return {e.x > 0.0 && e.x >= 0.5 * m, e.y > 0.0 && e.y >= 0.5 * m, e.z > 0.0 && e.z >= 0.5 * m};
}

CellGrid CellGrid::refined() const {
  CellGrid g = *this;
  const auto split = split_axes();
  for (int k = 0; k < 3; ++k)
    if (split[k]) ++g.bits[k];
  return g;
}

void refine_cell(const ImplicitEquations& equations, const CellGrid& grid, const CellIndex& parent,
                 std::vector<CellIndex>& children, std::size_t& tests, CompileBudget& budget) {
  const auto split = grid.split_axes();
  const CellGrid fine = grid.refined();
  for (int m = 0; m < 8; ++m) {
    CellIndex c = parent;
    bool valid = true;
    for (int k = 0; k < 3; ++k) {
      const int bit = (m >> k) & 1;
      if (split[k])
        c[k] = 2 * parent[k] + bit;
      else if (bit)
        valid = false;
    }
    if (!valid || !fine.solid(c)) continue;
    ++tests;
    budget.check();
    if (equations.may_vanish(fine.cell(c))) children.push_back(c);
  }
}

CurveEnclosure enclose_curve(const ImplicitEquations& equations, const Box3& box, CompileBudget& budget,
                             const EnclosureSettings& settings) {
  CurveEnclosure e;
  e.grid = enclosure_grid(box);
  ++e.tests;
  if (equations.may_vanish(box)) e.cells.push_back({0, 0, 0});
  std::vector<CellIndex> next;
  while (!e.cells.empty()) {
    // The size criterion: the cells against the bounding box of what remains.
    Box3 bound{e.grid.cell(e.cells.front()).lo, e.grid.cell(e.cells.front()).hi};
    for (const auto& c : e.cells) {
      const Box3 b = e.grid.cell(c);
      for (int k = 0; k < 3; ++k) {
        bound.lo[k] = std::min(bound.lo[k], b.lo[k]);
        bound.hi[k] = std::max(bound.hi[k], b.hi[k]);
      }
    }
    if (e.grid.max_edge() <= bound.diagonal() / settings.cells_across || e.levels >= settings.max_levels)
      break;
    if (e.cells.size() * 8 > settings.max_cells) {
      e.truncated = true;
      break;
    }
    next.clear();
    for (const auto& c : e.cells) refine_cell(equations, e.grid, c, next, e.tests, budget);
    e.grid = e.grid.refined();
    e.cells.swap(next);
    ++e.levels;
  }
  return e;
}

}  // namespace footpoint
