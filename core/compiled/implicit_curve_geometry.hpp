// The compiled implicit curve: its equations and box (geometry/implicit_curve.hpp), what `auto`
// precomputes (seeding/curve_discovery: the proved cells with their enclosures and tree, the
// samples of every piece with their k-d tree), and projection by method name.
// Two forms of the equations: as written, which the papers' methods iterate on, and their
// square-free form (formula::Program::square_free: the same points, each repeated factor once),
// which discovery, `auto`, the certificates and the meshes work with.
#pragma once
#include <cstddef>
#include <vector>

#include "compiled/compiled_geometry.hpp"
#include "geometry/implicit_curve.hpp"
#include "seeding/curve_discovery.hpp"
#include "seeding/curve_sample_index.hpp"
#include "seeding/curve_samples.hpp"

namespace footpoint {

class ImplicitCurve final : public CompiledGeometry {
 public:
  ImplicitCurve(GeometryDefinition def, ImplicitEquations equations, Box3 box);

  int point_dim() const override { return equations_.planar() ? 2 : 3; }
  int num_params() const override { return 0; }
  const std::vector<MethodInfo>& methods() const override;
  std::size_t memory_bytes() const override;

  // The square-free equations (the written ones when they have no repeated factor).
  const ImplicitEquations& equations() const { return equations_; }
  const ImplicitEquations& written_equations() const { return written_; }
  const Box3& box() const { return box_; }
  const CurveDiscovery& discovery() const { return discovery_; }
  const CurveSampleIndex& sample_index() const { return index_; }

 private:
  PointDims dims() const;
  ProjectionResult project_with(std::size_t index, const double* p, const Options& options) const override;

  ImplicitEquations written_;
  ImplicitEquations equations_;
  Box3 box_;
  CurveDiscovery discovery_;  // samples of every piece of the curve in the box (for `auto`)
  CurveSampleIndex index_;
};

}  // namespace footpoint
