// c(t) = (x(t), y(t)[, z(t)]), t in [tmin, tmax], and its exact derivatives from the formula tape,
// in the plane or in space. Planar curves are embedded in 3-D with z = 0.
#pragma once
#include <utility>

#include "formula/program.hpp"
#include "geometry/vec.hpp"

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

}  // namespace footpoint
