// The Summary of a foot point X of p on an implicit curve: the equation residuals |f_i| / |grad f_i|,
// the orthogonality residual of eq. (7) made relative, |<p - X, T>| / (|p - X| |T|) with
// T = grad f1 x grad f2, and where X lies (interior, box_face, singular_point).
#pragma once
#include <string>

#include "implicit/geometry/implicit_curve.hpp"
#include "projection/projection_result.hpp"
#include "solvers/iteration_control.hpp"

namespace footpoint::curve {

// |grad f1 x grad f2| / (|grad f1| |grad f2|) below this marks a singular point of the curve (the
// sine of the angle between the two normals; Newton-refined singular points reach ~1e-15).
inline constexpr double kSingularSine = 1e-7;

// Fills equation_residual, orthogonality, location and on_boundary of `summary` for the foot x.
// At a box face crossing the orthogonality entry is the first-order optimality residual of the
// distance restricted to the box (0 when the curve leaves the box moving away from p); at a
// singular point it is 0 (T vanishes there). When p is (almost) on the curve the orthogonality is
// measured against max(|p - X|, 1e-3 max(1, |X|)), since the direction p - X is then undefined.
void fill_implicit_residuals(const ImplicitEquations& equations, const Box3& box, Vec3 p, Vec3 x,
                             Summary& summary);
// The same from the jets j at x, already evaluated (planar: a planar curve's, which has no z faces).
void fill_implicit_residuals(const ImplicitJet& j, bool planar, const Box3& box, Vec3 p, Vec3 x,
                             Summary& summary);

// True when the residuals in `summary` meet the control's tolerance at the point x (the equation
// residuals relative to max(1, |x|)); `with_orthogonality` false for Algorithm 1, which only aims
// at landing on the curve.
bool implicit_residuals_met(const Summary& summary, Vec3 x, const IterationControl& control,
                            bool with_orthogonality = true);

// The same test without a Summary, inside the paper's iterations: the equation residuals at x, and
// (with_orthogonality) the orthogonality residual of eq. (7) for p, as at an interior point.
bool foot_residuals_met(const ImplicitEquations& equations, Vec3 p, Vec3 x, const IterationControl& control,
                        bool with_orthogonality);

// A result for the foot x of p: dim, num_params 0, foot, distance and the residuals.
ProjectionResult implicit_result(const ImplicitEquations& equations, const Box3& box, Vec3 p, Vec3 x,
                                 const char* method);
// The same with the residuals already computed (fill_implicit_residuals for p and x).
ProjectionResult implicit_result(bool planar, Vec3 p, Vec3 x, const char* method, const Summary& residuals);

}  // namespace footpoint::curve
