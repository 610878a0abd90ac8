// `auto` for parametric curves: the global nearest point over the closed interval [tmin, tmax].
// The nearest sample s0 (parametric/seeding/curve_parametric_samples) bounds d* <= |p - s0| = d0; every point
// of the curve lies within arc length h/2 of a sample, so the nearest point has a sample within
// d0 + h/2. The candidates are the samples within that radius that are discrete local minima of
// the distance, nearest first; each is refined by bracketed Newton between its neighbours
// (parametric_newton), an end sample by the first-order condition at tmin / tmax, while its
// distance minus h/2 can still beat the best found.
#pragma once
#include "parametric/geometry/curve_closure.hpp"
#include "parametric/geometry/parametric_curve.hpp"
#include "parametric/seeding/parametric_curve_cells.hpp"
#include "projection/projection_result.hpp"
#include "seeding/curve_sample_index.hpp"

namespace footpoint::curve {

// `index` is the k-d tree of the curve's dense samples (parametric/seeding/curve_parametric_samples), `cells`
// what the certificate bounds (parametric/seeding/parametric_curve_cells.hpp). The answer carries its
// certificate (parametric/solvers/parametric_curve_certificate.hpp) unless options.certify is false; a nearer
// minimum the certificate finds is the answer. On a curve that closes smoothly
// (parametric/geometry/curve_closure.hpp) tmin and tmax are one interior point, no endpoint. Farther than
// options.max_distance: no answer.
ProjectionResult parametric_curve_auto(const CurveFormulas& formulas, const ParamInterval& domain,
                                       const CurveSampleIndex& index, const ParametricCurveCells& cells,
                                       const CurveClosure& closure, Vec3 p, const Options& options);

}  // namespace footpoint::curve
