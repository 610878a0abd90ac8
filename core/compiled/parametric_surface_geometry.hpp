// The compiled parametric surface: s(u, v) = (x, y, z) over [umin, umax] x [vmin, vmax], its seams
// and poles, the seeding data of `auto`, and projection by method name (auto, gsa, first_order,
// hybrid, newton).
#pragma once
#include <cstddef>
#include <vector>

#include "compiled/compiled_geometry.hpp"
#include "geometry/compile_budget.hpp"
#include "parametric/geometry/parametric_surface.hpp"
#include "parametric/geometry/surface_closure.hpp"
#include "parametric/seeding/surface_cells.hpp"

namespace footpoint {

class ParametricSurface final : public CompiledGeometry {
 public:
  // `program` computes x, y, z (in that order) from (u, v); finds the seams and poles (with the
  // directions def.periodic declares: GeometryError when they are not) and builds the seeding
  // cells within `budget`.
  ParametricSurface(GeometryDefinition def, formula::Program program, const ParamBox& box,
                    CompileBudget& budget, const SurfaceSeedingOptions& seeding = {});

  int point_dim() const override { return 3; }
  int num_params() const override { return 2; }
  const std::vector<MethodInfo>& methods() const override;
  std::size_t memory_bytes() const override;
  bool evaluate(const double* t, Evaluation& out) const override;
  bool foot_normal(const ProjectionResult& r, std::array<double, 3>& n) const override;

  const SurfaceFormulas& formulas() const { return formulas_; }
  const ParamBox& domain() const { return box_; }
  // Where the domain meets itself: seams (closed directions) and poles, found at compile time.
  const SurfaceClosure& closure() const { return closure_; }
  const SurfaceCells& cells() const { return cells_; }
  // Translations under which the formulas repeat within the box (parametric/geometry/self_covering.hpp).
  const SelfCovering& self_covering() const { return self_covering_; }

 private:
  ProjectionResult project_with(std::size_t index, const double* p, const Options& options) const override;

  SurfaceFormulas formulas_;
  ParamBox box_;
  SurfaceClosure closure_;
  SelfCovering self_covering_;
  SurfaceCells cells_;
};

}  // namespace footpoint
