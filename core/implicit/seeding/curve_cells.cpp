#include "implicit/seeding/curve_cells.hpp"

#include <cstdio>
#include <limits>
#include <string>

#include "geometry/compile_budget.hpp"
#include "geometry/geometry_error.hpp"

namespace footpoint {

namespace {

// What the subdivision reached, for the message of a refusal.
std::string reached(const CurveCells& out, const CurveEnclosure& enclosure) {
  char what[240];
  std::snprintf(
      what, sizeof what,
      "%zu cells examined, %zu proved, %zu left unproved, %d bisections below the first cells of edge %.3g",
      out.examined, out.cells.size(), out.unproved.size(), out.deepest, enclosure.grid.max_edge());
  return what;
}

}  // namespace

CurveCells subdivide_curve(const ImplicitEquations& equations, const CurveEnclosure& enclosure,
                           CompileBudget& budget, const SubdivisionSettings& settings) {
  CurveCells out;
  try {
    subdivide(equations, enclosure, settings, out, budget);
  } catch (const GeometryError& e) {
    if (e.code != "compile_timeout") throw;
    throw GeometryError(e.code, e.field, e.position,
                        std::string(e.what()) + " (reached: " + reached(out, enclosure) + ")");
  }
  return out;
}

void subdivide(const ImplicitEquations& equations, const CurveEnclosure& enclosure,
               const SubdivisionSettings& settings, CurveCells& out, CompileBudget& budget) {
  std::vector<CellGrid> grids{enclosure.grid};
  struct Item {
    int level;
    CellIndex index;
  };
  std::vector<Item> stack;
  for (const CellIndex& c : enclosure.cells) stack.push_back({0, c});
  std::vector<CellIndex> children;
  std::size_t tests = 0;
  FaceCrossingCache faces(equations);
  while (!stack.empty()) {
    budget.check();
    const Item item = stack.back();
    stack.pop_back();
    if (++out.examined > settings.max_cells)
      throw GeometryError("geometry_too_complex", "domain", -1,
                          "the curve is too intricate to resolve in this box within the limit of " +
                              std::to_string(settings.max_cells) +
                              " cells (reached: " + reached(out, enclosure) + "); shrink the box");
    const CellGrid grid = grids[static_cast<std::size_t>(item.level)];  // a copy: grids grows
    const Box3 box = grid.cell(item.index);
    CellProof proof = prove_cell(
        equations, box,
        item.level < settings.max_tightening ? settings.tightness : std::numeric_limits<double>::infinity(),
        &faces);
    out.evaluations += proof.evaluations;
    if (proof.verdict == CellVerdict::empty) continue;
    if (proof.verdict == CellVerdict::arcs) {
      ProvedCell cell;
      cell.box = box;
      cell.axis = proof.axis;
      cell.first_crossing = static_cast<std::int32_t>(out.crossings.size());
      cell.crossing_count = static_cast<std::int32_t>(proof.crossings.size());
      cell.bounds = proof.bounds;
      cell.around = enlarged_bounds(equations, box, enclosure.grid.clip);
      ++out.evaluations;
      out.crossings.insert(out.crossings.end(), proof.crossings.begin(), proof.crossings.end());
      out.capsules.insert(out.capsules.end(), proof.capsules.begin(), proof.capsules.end());
      out.capsule_begin.push_back(static_cast<std::int32_t>(out.capsules.size()));
      budget.grow(sizeof(cell) + sizeof(std::int32_t));
      out.cells.push_back(cell);
      continue;
    }
    // unproved after max_extra_levels, or at the finest grid the indices hold (an isolated point
    // of the curve, x^2 + y^2 = 0, keeps one cell unproved at every level): kept as an unproved box
    if (item.level >= settings.max_extra_levels || grid.finest()) {
      out.unproved.push_back({box, proof.reason});
      continue;
    }
    if (static_cast<std::size_t>(item.level + 1) == grids.size()) grids.push_back(grid.refined());
    children.clear();
    refine_cell(equations, grid, item.index, children, tests, budget);
    out.evaluations += tests;
    tests = 0;
    for (const CellIndex& child : children) stack.push_back({item.level + 1, child});
    if (item.level + 1 > out.deepest) out.deepest = item.level + 1;
  }
}

}  // namespace footpoint
