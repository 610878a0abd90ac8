// The certificate of an answer on a parametric curve (projection/certificate.hpp): a rigorous lower
// bound L on the distance from p to c over the closed interval [tmin, tmax], by branch and bound
// over the precomputed cells (parametric/seeding/parametric_curve_cells.hpp), as for surfaces
// (parametric/solvers/surface_certificate.hpp) in one parameter. A cell is closed when a lower bound
// of the distance over it reaches the target d - gap/2:
//   1. the boxes of c over the hierarchy's nodes, nearest first (a subtree beyond is closed);
//   2. the tangent-line model: the distance from p to the segment c_c + c'_c δ, |δ| <= h, less the
//      model's proved error ρ;
//   3. the second-order bound of f = ½|c - p|^2 from the cell's centre, f'' = |c'|^2 + (c - p)·c''
//      enclosed over the cell;
//   4. the same from each known minimiser near the cell (the answer: its own cell closes when f is
//      convex there);
//   5. what stays open is solved from (a nearer minimum replaces the answer, or refutes a given
//      one) and bisected (an interval jet and a ball jet per half) within a budget.
// Where c' vanishes (cusps, t^k parametrisations) nothing differs: the bounds never divide by the
// speed, and the interval image decides.
#pragma once
#include <functional>
#include <vector>

#include "parametric/geometry/parametric_curve.hpp"
#include "parametric/seeding/parametric_curve_cells.hpp"
#include "projection/certificate.hpp"

namespace footpoint::curve {

struct CurveCertifyOptions {
  int max_boxes = 64;   // sub-intervals bounded at run time per point (an interval jet and a ball jet each)
  int max_solves = 16;  // local solves started from intervals that stay open
};

// A local minimum of the distance: parameter and distance.
struct CurveMinimum {
  double t = 0.0;
  double distance = 0.0;
};
// A local solve from t (a descent to a local minimum inside the domain).
using CurveLocalSolve = std::function<CurveMinimum(double t)>;

struct CurveCertification {
  Certificate certificate;
  bool improved = false;  // a nearer minimum than the answer was found (with may_improve)
  CurveMinimum better;
};

CurveCertification certify_parametric_curve(const ParametricCurveCells& cells, const CurveFormulas& formulas,
                                            Vec3 p, CurveMinimum answer, const std::vector<double>& known,
                                            const CurveLocalSolve& solve, bool may_improve,
                                            const CurveCertifyOptions& options = {});

// The certificate of an answer at t inside the domain, given as it is (a local method's, with
// options.certify): certified, refuted (nearer_point) or neither within the budget.
Certificate certify_curve_answer(const ParametricCurveCells& cells, const CurveFormulas& formulas,
                                 const ParamInterval& domain, Vec3 p, double t);

// A safeguarded Newton descent of f(t) = ½|c(t) - p|^2 on [tmin, tmax] from t0 (backtracking on f,
// a gradient step where f'' <= 0), to a local minimum: the certificate's solve.
CurveMinimum descend_on_interval(const CurveFormulas& formulas, const ParamInterval& domain, Vec3 p,
                                 double t0);

}  // namespace footpoint::curve
