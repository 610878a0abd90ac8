// The compiled parametric curve: its formulas and parameter interval
// (parametric/geometry/parametric_curve.hpp), whether it closes, the dense samples `auto` precomputes with
// their k-d tree, and projection by method name.
#pragma once
#include <cstddef>
#include <vector>

#include "compiled/compiled_geometry.hpp"
#include "geometry/compile_budget.hpp"
#include "parametric/geometry/curve_closure.hpp"
#include "parametric/geometry/parametric_curve.hpp"
#include "parametric/seeding/curve_parametric_samples.hpp"
#include "parametric/seeding/parametric_curve_cells.hpp"
#include "seeding/curve_sample_index.hpp"
#include "seeding/curve_samples.hpp"

namespace footpoint {

class ParametricCurve final : public CompiledGeometry {
 public:
  ParametricCurve(GeometryDefinition def, CurveFormulas formulas, ParamInterval domain,
                  CompileBudget& budget);

  int point_dim() const override { return formulas_.dim(); }
  int num_params() const override { return 1; }
  const std::vector<MethodInfo>& methods() const override;
  std::size_t memory_bytes() const override;
  bool evaluate(const double* t, Evaluation& out) const override;
  bool foot_normal(const ProjectionResult& r, std::array<double, 3>& n) const override;

  const CurveFormulas& formulas() const { return formulas_; }
  const ParamInterval& domain() const { return domain_; }
  // Whether c(tmin) = c(tmax), found at compile time (or declared: def.periodic = {"t"}).
  const CurveClosure& closure() const { return closure_; }
  // Dense samples along the curve (params holds t) with their k-d tree, for `auto` and for the
  // default start of the local methods.
  const CurveSamples& samples() const { return samples_; }
  const CurveSampleIndex& sample_index() const { return index_; }
  // What the certificates bound: cells of a few sample gaps with their enclosures.
  const ParametricCurveCells& cells() const { return cells_; }

 private:
  ProjectionResult project_with(std::size_t index, const double* p, const Options& options) const override;
  // The sampling of samples_, with the bytes each sample commits the curve to.
  static ParametricSampling sampling();

  CurveFormulas formulas_;
  ParamInterval domain_;
  CurveClosure closure_;
  CurveSamples samples_;
  CurveSampleIndex index_;
  ParametricCurveCells cells_;
};

}  // namespace footpoint
