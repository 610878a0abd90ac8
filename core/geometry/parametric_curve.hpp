// Parametric curves c(t) = (x(t), y(t)[, z(t)]), t in [tmin, tmax], in the plane or in space.
// Planar curves are embedded in 3-D with z = 0.
#pragma once
#include <string_view>
#include <vector>

#include "formula/program.hpp"
#include "geometry/geometry.hpp"
#include "geometry/vec.hpp"
#include "seeding/curve_sample_index.hpp"
#include "seeding/curve_samples.hpp"

namespace footpoint {

// c(t) and its exact first and second derivatives.
struct CurveJet {
  Vec3 c, d1, d2;
};

class CurveFormulas {
 public:
  // `program` has the input t and the outputs x, y[, z].
  explicit CurveFormulas(formula::Program program)
      : program_(std::move(program)), dim_(program_.num_outputs()) {}
  int dim() const { return dim_; }
  Vec3 point(double t) const {
    double out[3] = {0.0, 0.0, 0.0};
    program_.values(&t, out);
    return {out[0], out[1], out[2]};
  }
  CurveJet jet(double t) const {
    formula::Jet2<1> j[3];
    program_.jets2<1>(&t, j);
    CurveJet r;
    r.c = {j[0].v, j[1].v, dim_ == 3 ? j[2].v : 0.0};
    r.d1 = {j[0].g[0], j[1].g[0], dim_ == 3 ? j[2].g[0] : 0.0};
    r.d2 = {j[0].h[0][0], j[1].h[0][0], dim_ == 3 ? j[2].h[0][0] : 0.0};
    return r;
  }
  const formula::Program& program() const { return program_; }

 private:
  formula::Program program_;
  int dim_;
};

struct ParamInterval {
  double tmin, tmax;
  bool contains(double t) const { return t >= tmin && t <= tmax; }
};

class ParametricCurve final : public CompiledGeometry {
 public:
  ParametricCurve(GeometryDefinition def, CurveFormulas formulas, ParamInterval domain);

  int point_dim() const override { return formulas_.dim(); }
  int num_params() const override { return 1; }
  const std::vector<MethodInfo>& methods() const override;
  ProjectionResult project(const double* p, std::string_view method, const Options& options) const override;
  std::size_t memory_bytes() const override;

  const CurveFormulas& formulas() const { return formulas_; }
  const ParamInterval& domain() const { return domain_; }
  // Dense samples along the curve (params holds t) with their k-d tree, for `auto` and for the
  // default start of the local methods.
  const CurveSamples& samples() const { return samples_; }
  const CurveSampleIndex& sample_index() const { return index_; }

 private:
  CurveFormulas formulas_;
  ParamInterval domain_;
  CurveSamples samples_;
  CurveSampleIndex index_;
};

}  // namespace footpoint
