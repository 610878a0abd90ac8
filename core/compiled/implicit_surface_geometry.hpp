// The compiled implicit surface f(x, y, z) = 0 clipped to a box: its equation (the square-free
// form, formula::Program::square_free: (x^2 + y^2 + z^2 - 1)^2 is the sphere, regular), its factor
// surfaces (formula::Program::factor_systems: where f is a product of factors defined everywhere,
// the surface is the union of theirs, implicit/solvers/implicit_surface_union.hpp; otherwise the
// one piece is the square-free surface), what `auto` precomputes for each
// (implicit/seeding/implicit_surface_cells: the octree of cells that may hold the surface, a
// sample in each leaf, the points on the box's edges, the singular points), and projection by
// method name.
#pragma once
#include <cstddef>
#include <memory>
#include <vector>

#include "compiled/compiled_geometry.hpp"
#include "geometry/compile_budget.hpp"
#include "implicit/geometry/implicit_surface.hpp"
#include "implicit/seeding/implicit_surface_cells.hpp"
#include "implicit/solvers/implicit_surface_union.hpp"

namespace footpoint {

class ImplicitSurface final : public CompiledGeometry {
 public:
  ImplicitSurface(GeometryDefinition def, formula::Program program, Box3 box, CompileBudget& budget);

  int point_dim() const override { return 3; }
  int num_params() const override { return 0; }
  const std::vector<MethodInfo>& methods() const override;
  std::size_t memory_bytes() const override;
  bool evaluate_equations(const double* x, EquationEvaluation& out) const override;
  // grad f / |grad f| of the square-free equation at the foot (none at a singular point).
  bool foot_normal(const ProjectionResult& r, std::array<double, 3>& n) const override;

  // The square-free equation (the written one when it has no repeated factor).
  const ImplicitSurfaceEquation& equation() const { return equation_; }
  const ImplicitSurfaceEquation& written_equation() const { return written_; }
  const Box3& box() const { return box_; }
  // The factor surfaces with cells in the box (the square-free surface alone when f does not split).
  const std::vector<surface_implicit::SurfacePiece>& pieces() const { return pieces_; }
  // The first piece's cells (the whole surface's when f does not split).
  const ImplicitSurfaceCells& cells() const { return pieces_.front().cells; }

 private:
  // grad f / |grad f| of the square-free equation at x; false where grad f = 0.
  bool unit_normal(Vec3 x, Vec3& n) const;
  ProjectionResult project_with(std::size_t index, const double* p, const Options& options) const override;

  ImplicitSurfaceEquation written_;
  ImplicitSurfaceEquation equation_;
  Box3 box_;
  std::vector<surface_implicit::SurfacePiece> pieces_;
};

}  // namespace footpoint
