// The equations of an implicit curve and their exact jets: a spatial curve C = {f1 = 0} ∩ {f2 = 0}
// ([Curve] eq. (5)) or a planar curve f(x, y) = 0, inside a box. Planar curves are embedded in 3-D
// as f1 = f(x, y), f2 = z (so grad f2 = e_z and T = grad f1 x grad f2 = (f_y, -f_x, 0) is the
// planar tangent): discovery, sampling and the global search are then written once for both.
#pragma once
#include <array>
#include <utility>

#include "formula/program.hpp"
#include "geometry/vec.hpp"

namespace footpoint {

using Mat3 = std::array<Vec3, 3>;  // rows; the Hessians are symmetric
inline Vec3 operator*(const Mat3& m, Vec3 v) { return {dot(m[0], v), dot(m[1], v), dot(m[2], v)}; }

// A closed axis-aligned box (planar curves: lo.z = hi.z = 0).
struct Box3 {
  Vec3 lo, hi;
  bool contains(Vec3 x, double slack = 0.0) const {
    for (int k = 0; k < 3; ++k)
      if (x[k] < lo[k] - slack || x[k] > hi[k] + slack) return false;
    return true;
  }
  Vec3 center() const { return 0.5 * (lo + hi); }
  double diagonal() const { return norm(hi - lo); }
};

// f1, f2 and their exact first and second derivatives at one point (jets of the formula tape).
struct ImplicitJet {
  std::array<double, 2> f{};
  std::array<Vec3, 2> grad{};
  std::array<Mat3, 2> hess{};
  // The tangent T = grad f1 x grad f2 ([Curve] eq. (7)).
  Vec3 tangent() const { return cross(grad[0], grad[1]); }
};

class ImplicitEquations {
 public:
  // `program` has the inputs (x, y, z) and outputs f1, f2 (spatial), or inputs (x, y) and the
  // output f (planar).
  ImplicitEquations(formula::Program program, bool planar) : program_(std::move(program)), planar_(planar) {}
  bool planar() const { return planar_; }
  std::array<double, 2> values(Vec3 x) const;
  ImplicitJet jet(Vec3 x) const;
  // False only when the interval enclosure of some equation over the cell excludes 0: then the
  // cell certainly holds no point of the curve (a rigorous exclusion test).
  bool may_vanish(const Box3& cell) const;
  const formula::Program& program() const { return program_; }

 private:
  formula::Program program_;
  bool planar_;
};

}  // namespace footpoint
