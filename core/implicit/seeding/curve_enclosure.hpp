// A rigorous enclosure of an implicit curve: the box is bisected level by level and every cell in
// which the interval range of f1 or of f2 excludes 0 is dropped (formula::Program::intervals over
// the cell). The remaining cells, all of one size, hold every point of the curve in the box; some
// may hold none (interval ranges overestimate).
//
// The grid is laid over a box a few percent larger than the curve's, its planes at offsets no
// formula's nice numbers share (so that a circle through (1, 0) or a tangent at y = 1 does not sit
// on a cell's edge or face at every level); its cells are clipped to the curve's box.
#pragma once
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "geometry/compile_budget.hpp"
#include "implicit/geometry/implicit_curve.hpp"

namespace footpoint {

using CellIndex = std::array<std::int32_t, 3>;

// A uniform grid over the box: 2^bits[k] cells along axis k, each clipped to `clip`.
struct CellGrid {
  static constexpr double kInfinity = std::numeric_limits<double>::infinity();
  Box3 box;
  std::array<int, 3> bits{};
  Box3 clip{{-kInfinity, -kInfinity, -kInfinity}, {kInfinity, kInfinity, kInfinity}};
  Box3 cell(const CellIndex& c) const;  // clipped
  // The clipped cell has positive extent along every axis the grid has: a cell, not a face of one.
  bool solid(const CellIndex& c) const;
  CellIndex index_of(Vec3 x) const;  // clamped to the grid
  Vec3 edge() const;
  double max_edge() const;
  static std::uint64_t key(const CellIndex& c) {
    return static_cast<std::uint64_t>(c[0]) | (static_cast<std::uint64_t>(c[1]) << 21) |
           (static_cast<std::uint64_t>(c[2]) << 42);
  }
  // 2^kMaxBits cells per axis at most: a cell index and the one after it are int32.
  static constexpr int kMaxBits = 30;
  bool finest() const { return std::max({bits[0], bits[1], bits[2]}) >= kMaxBits; }
  // The grid one bisection finer along the axes that are at least half as long as the longest
  // (so cells stay roughly cubical); planar boxes (zero z extent) are never split along z.
  CellGrid refined() const;
  // Which axes refined() splits.
  std::array<bool, 3> split_axes() const;
};

struct EnclosureSettings {
  // Stop bisecting once the cells are this many times smaller than the bounding box of the cells
  // that remain (the curve's size, as far as intervals can tell): fine enough that a cell holds a
  // simple piece of a curve, coarse enough to be cheap.
  double cells_across = 48.0;
  int max_levels = 21;             // 2^21 cells per axis fit the 21-bit fields of CellGrid::key
  std::size_t max_cells = 400000;  // budget: stop refining (coarser enclosure) beyond this
};

struct CurveEnclosure {
  CellGrid grid;
  std::vector<CellIndex> cells;
  int levels = 0;
  std::size_t tests = 0;   // interval evaluations
  bool truncated = false;  // stopped by the cell budget, not by the size criterion
};

// The enclosure's grid over `box`: the extended, offset box above, clipped to `box`.
CellGrid enclosure_grid(const Box3& box);

CurveEnclosure enclose_curve(const ImplicitEquations& equations, const Box3& box, CompileBudget& budget,
                             const EnclosureSettings& settings = {});

// The cells of `grid` one level finer inside `parent`'s cell that may hold curve points.
void refine_cell(const ImplicitEquations& equations, const CellGrid& grid, const CellIndex& parent,
                 std::vector<CellIndex>& children, std::size_t& tests, CompileBudget& budget);

}  // namespace footpoint
