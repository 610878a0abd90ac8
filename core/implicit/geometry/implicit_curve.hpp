// The equations of an implicit curve and their exact jets: a spatial curve C = {f1 = 0} ∩ {f2 = 0}
// ([Curve] eq. (5)) or a planar curve f(x, y) = 0, inside a box. Planar curves are embedded in 3-D
// as f1 = f(x, y), f2 = z (so grad f2 = e_z and T = grad f1 x grad f2 = (f_y, -f_x, 0) is the
// planar tangent): discovery, sampling and the global search are then written once for both.
#pragma once
#include <array>
#include <utility>

#include "formula/program.hpp"
#include "geometry/box3.hpp"
#include "geometry/interval_vec3.hpp"
#include "geometry/vec.hpp"

namespace footpoint {

using Mat3 = std::array<Vec3, 3>;  // rows; the Hessians are symmetric
inline Vec3 operator*(const Mat3& m, Vec3 v) { return {dot(m[0], v), dot(m[1], v), dot(m[2], v)}; }

// f1, f2 and their exact first and second derivatives at one point (jets of the formula tape).
struct ImplicitJet {
  std::array<double, 2> f{};
  std::array<Vec3, 2> grad{};
  std::array<Mat3, 2> hess{};
  // The tangent T = grad f1 x grad f2 ([Curve] eq. (7)).
  Vec3 tangent() const { return cross(grad[0], grad[1]); }
  // The sine of the angle between grad f1 and grad f2, |T| / (|grad f1| |grad f2|): 0 at a
  // singular point, small where the two surfaces are nearly tangent; NaN where a gradient is 0.
  double normals_sine() const { return norm(tangent()) / (norm(grad[0]) * norm(grad[1])); }
};

// Enclosures over a box of f1, f2, their gradients and Hessians (formula/interval_jet.hpp's
// contract; planar curves' f2 = z exactly): every value, gradient and Hessian at a point of the box
// lies in them where the flags say so.
struct ImplicitIntervalJet {
  std::array<Interval, 2> f{};
  std::array<IVec3, 2> grad{};
  std::array<IMat3, 2> hess{};  // symmetric: row k is column k
  // f1 and f2 are Lipschitz on the box and grad encloses their (Clarke) gradients: the mean value
  // inclusion f(y) - f(x) ∈ grad · (y - x) holds for x, y in the box.
  bool lipschitz = true;
  // Both are twice continuously differentiable on the box and hess encloses their Hessians.
  bool smooth = true;
  // T = ∇f1 × ∇f2 over the box ([Curve] eq. (7)); each component is the exact range over the
  // gradients' enclosures (interval_vec3.hpp), so 0 outside T_k means T_k ≠ 0 at every point.
  IVec3 tangent() const { return ivec::cross(grad[0], grad[1]); }
  // dT[k] = ∂T/∂x_k = (H1 e_k) × ∇f2 + ∇f1 × (H2 e_k) over the box (valid when smooth).
  IMat3 tangent_derivatives() const {
    IMat3 dt;
    for (int k = 0; k < 3; ++k)
      dt[k] = ivec::add(ivec::cross(hess[0][k], grad[1]), ivec::cross(grad[0], hess[1][k]));
    return dt;
  }
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
  // Enclosures of f1 and f2 over the box (Program::intervals; planar: f2 = z exactly); at a point
  // box [x, x], rigorous enclosures of the values at x.
  std::array<Interval, 2> value_enclosure(const Box3& box) const;
  // Enclosures of the jets over the box (a point box [x, x] gives rigorous enclosures at x).
  ImplicitIntervalJet interval_jet(const Box3& box) const;
  // The same without the Hessians (about a third of the work): hess is left holding the whole
  // line; f, grad and the flags are those of interval_jet.
  ImplicitIntervalJet interval_gradient(const Box3& box) const;
  // The enclosures of interval_gradient({x, x}) at one point, from ball jets (Program::ball_jets1,
  // formula/ball.hpp: a few times a point jet's cost, interval jets of a point box 8-38 times).
  ImplicitIntervalJet point_gradient(Vec3 x) const;
  // Enclosures of f1 and f2 at x to the rounding of the values themselves plus O(u^2)
  // (Program::accurate_values); false where the formulas are not polynomials or x is out of range.
  bool accurate_values(Vec3 x, std::array<Interval, 2>& f) const;
  const formula::Program& program() const { return program_; }

 private:
  formula::Program program_;
  bool planar_;
};

}  // namespace footpoint
