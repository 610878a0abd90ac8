// The equation of an implicit surface S = {f(x, y, z) = 0} inside a closed box, and its exact jets
// (value, gradient, Hessian of the formula tape) and rigorous enclosures over boxes (interval
// jets, formula/interval_jet.hpp): what the surface's local methods iterate on and what its
// subdivision, search and certificate bound.
#pragma once
#include <utility>

#include "formula/program.hpp"
#include "geometry/box3.hpp"
#include "geometry/interval_vec3.hpp"
#include "implicit/geometry/implicit_curve.hpp"

namespace footpoint {

// f and its exact first and second derivatives at one point.
struct ImplicitSurfaceJet {
  double f = 0.0;
  Vec3 grad;
  Mat3 hess{};  // rows; symmetric
};

// Enclosures of f and its gradient over a box (the flags of formula/interval_jet.hpp: where
// `lipschitz` is false the gradient enclosure holds the whole line).
struct ImplicitSurfaceIntervalJet {
  Interval f;
  IVec3 grad{};
  IMat3 hess{};  // only from interval_jet(); the whole line where smooth is false
  bool lipschitz = true;
  bool smooth = true;
};

class ImplicitSurfaceEquation {
 public:
  // `program` has the inputs (x, y, z) and one output f.
  explicit ImplicitSurfaceEquation(formula::Program program) : program_(std::move(program)) {}
  double value(Vec3 x) const;
  ImplicitSurfaceJet jet(Vec3 x) const;
  // An enclosure of f over the box (at a point box [x, x], of f(x) with its rounding).
  Interval value_enclosure(const Box3& box) const;
  // False only when f's enclosure over the box excludes 0: the box holds no point of S.
  bool may_vanish(const Box3& box) const { return !value_enclosure(box).excludes_zero(); }
  // Enclosures of f and grad f over the box (Program::interval_jets1).
  ImplicitSurfaceIntervalJet interval_gradient(const Box3& box) const;
  // Enclosures of f, grad f and the Hessian over the box (Program::interval_jets2).
  ImplicitSurfaceIntervalJet interval_jet(const Box3& box) const;
  const formula::Program& program() const { return program_; }

 private:
  formula::Program program_;
};

}  // namespace footpoint
