// Shared by the unit tests of the implicit-surface seeding and solvers: equations compiled from
// formulas, their cells in a box, and (closed_forms.hpp) nearest points known independently of
// the code.
#pragma once
#include <string>

#include "closed_forms.hpp"
#include "formula/program.hpp"
#include "geometry/compile_budget.hpp"
#include "implicit/geometry/implicit_surface.hpp"
#include "implicit/seeding/implicit_surface_cells.hpp"

namespace footpoint::test {

// f(x, y, z) = 0.
inline ImplicitSurfaceEquation surface_equation(const std::string& f) {
  return ImplicitSurfaceEquation(formula::Program::compile({{"f", f}}, {"x", "y", "z"}, {}));
}

// What `auto` precomputes for the surface in `box` (no deadline, no bound on bytes).
inline ImplicitSurfaceCells surface_cells(const ImplicitSurfaceEquation& equation, const Box3& box,
                                          const ImplicitSurfaceCellSettings& settings = {}) {
  CompileBudget budget;
  return subdivide_surface(equation, box, budget, settings);
}

}  // namespace footpoint::test
