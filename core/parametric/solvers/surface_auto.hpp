// `auto`, the default surface method: the global nearest point of s over the closed parameter
// domain, edges and corners included.
//
// Branch and bound over the precomputed cells (parametric/seeding/surface_cells.hpp): the cell tree is walked
// nearest box first, and a cell is skipped when its box is farther than the best distance known
// (the box rule), when its tangent-plane model is (the tangent-plane rule), when its Newton model
// puts the minimum in a neighbour that answers for it (the claim rule), or when a minimum already
// found answers for it (the known-minimum rule); each rule is stated with the code that applies it
// (surface_auto.cpp). Any surface point evaluated (cell centres, the domain's corners) that is
// nearer than the answer at the end starts one more solve: a safety net for a basin lost to a
// model's error. The first cell that survives is solved at once (a tight bound for the rest of the
// walk); the later ones are candidates, solved after the walk nearest model foot first, each solve
// lowering the bound for the rest, by a local solve (parametric/solvers/projected_newton.hpp) from
// the model's minimiser: 2-5 Newton steps, stopped after 1-3 when Newton's model proves the basin
// to be that of a minimiser already found, or - given the best distance so far - to hold nothing
// nearer (parametric/solvers/basin_early_stop.hpp). The answer then gets its certificate
// (parametric/solvers/surface_certificate.hpp), which proves no point nearer or finds one.
#pragma once
#include "parametric/geometry/parametric_surface.hpp"
#include "parametric/geometry/surface_closure.hpp"
#include "parametric/seeding/surface_cells.hpp"
#include "projection/projection_result.hpp"

namespace footpoint::surface {

// options.initial is a warm start: solved from first, its distance bounds the search from the
// start (a neighbour's foot speeds up a coherent sequence of points); the search is global as
// always. options.all_minima returns every distinct local minimum found (interior, edge, corner,
// pole), best first, at most options.max_minima. options.trace: the steps of the local solve that
// gave the answer. With no point within options.max_distance: beyond_max_distance, no foot point,
// and a certificate that none is nearer. `closure` (parametric/geometry/surface_closure.hpp): seams are no
// edges, poles are their own location. diagnostics.multiplicity: unique, tied or continuum.
ProjectionResult project_auto(const SurfaceCells& cells, const SurfaceFormulas& formulas, const ParamBox& box,
                              const SurfaceClosure& closure, const Vec3& p, const Options& options);

}  // namespace footpoint::surface
