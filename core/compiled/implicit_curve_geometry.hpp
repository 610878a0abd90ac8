// The compiled implicit curve: its equations and box (implicit/geometry/implicit_curve.hpp), what `auto`
// precomputes (implicit/seeding/curve_discovery: the proved cells with their enclosures and tree, the
// samples of every piece with their k-d tree), and projection by method name.
// Three forms of the equations:
//  - as written, which the papers' methods iterate on;
//  - the square-free form (formula::Program::square_free: the same points, each repeated factor
//    once), the whole curve, which the meshes and discovery's statistics show;
//  - the factor curves (formula::Program::factor_systems): where the equations are products of
//    factors defined everywhere, the curve is the union of the factors' curves, each regular where
//    the product is singular only because two of them meet (a tacnode of two tangent circles, the
//    node of x y = 0). `auto` and the certificates search and bound each. Otherwise the one factor
//    curve is the whole curve.
#pragma once
#include <cstddef>
#include <memory>
#include <span>
#include <vector>

#include "compiled/compiled_geometry.hpp"
#include "geometry/compile_budget.hpp"
#include "implicit/geometry/implicit_curve.hpp"
#include "implicit/seeding/discovered_curve.hpp"

namespace footpoint {

class ImplicitCurve final : public CompiledGeometry {
 public:
  ImplicitCurve(GeometryDefinition def, ImplicitEquations equations, Box3 box, CompileBudget& budget);

  int point_dim() const override { return equations().planar() ? 2 : 3; }
  int num_params() const override { return 0; }
  const std::vector<MethodInfo>& methods() const override;
  std::size_t memory_bytes() const override;
  bool foot_normal(const ProjectionResult& r, std::array<double, 3>& n) const override;
  bool evaluate_equations(const double* x, EquationEvaluation& out) const override;

  // The square-free equations (the written ones when they have no repeated factor).
  const ImplicitEquations& equations() const { return whole_->equations; }
  const ImplicitEquations& written_equations() const { return written_; }
  const Box3& box() const { return box_; }
  // Discovery of the whole curve.
  const CurveDiscovery& discovery() const { return whole_->discovery; }
  // The factor curves with a point in the box, whose union is the curve (the whole curve alone
  // when its equations do not split).
  std::span<const DiscoveredCurve* const> factors() const { return factors_; }

 private:
  PointDims dims() const;
  // grad f / |grad f| of the square-free planar equation at (x, y); false where grad f = 0.
  bool planar_normal(double x, double y, Vec3& n) const;
  ProjectionResult project_with(std::size_t index, const double* p, const Options& options) const override;

  ImplicitEquations written_;
  Box3 box_;
  std::unique_ptr<const DiscoveredCurve> whole_;
  std::vector<std::unique_ptr<const DiscoveredCurve>> factor_curves_;  // empty when not split
  std::vector<const DiscoveredCurve*> factors_;                        // whole_, or the factor curves
};

}  // namespace footpoint
