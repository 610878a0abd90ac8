// `auto`, the default surface method: the global nearest point of s over the closed parameter
// domain, edges and corners included.
//
// Branch and bound over the precomputed cells (seeding/surface_cells.hpp): the cell tree is walked
// nearest box first, and a cell is skipped when
//   1. its box is farther than the best distance known (a solved foot point, or any cell centre:
//      every s(t) bounds the minimum from above) or than options.max_distance;
//   2. its tangent-plane model, grown by the model error ρ, is that far (the distance to the
//      rectangle in the tangent plane that holds the cell's tangent parallelogram, less ρ);
//   3. the minimum of its Newton model (the second-order Taylor expansion of ½|s - p|^2 at the
//      centre) over the cell grown by a margin lies on the grown cell's border inside the domain:
//      the distance decreases into a neighbour, which answers for it (two cells claiming each
//      other are solved from between their two predictions). The claim must beat the model's
//      error, else the cell is solved - next to the domain's boundary always, inside it when the
//      cell may hold a point nearer than the best known (the model's least value over the cell
//      less its error): near a fold, or for a point nearer the surface than the model's error,
//      claims can lead past the nearest minimum to a worse one or into a neighbour never visited;
//   4. a minimum already found, no farther than the cell model's foot point (a farther one may be
//      another, where the model's error is not small next to the distance), lies within a cell's
//      width of the cell model's minimiser (a coarse cell: in the cell; a coarse cell inside the
//      domain whose claim failed rule 3's error test: in the cell grown by the margin, where its
//      claim pointed), on the same face of the domain (interior, the same edge, the same corner) -
//      not for the candidates of a coarse cell next to the boundary whose claim failed that test.
//      (Distinct minima are told apart by parameters here, not by 3-D foot points: a surface
//      folding over itself has distinct minima with feet closer than any model can tell apart.
//      Periodic and degenerate parametrisations, which reach one foot from many (u, v), cost a
//      local solve per copy - cut short by the cutoff below; the copies are merged by foot
//      point in the result.)
// Any surface point evaluated (cell centres, the domain's corners) that is nearer than the
// answer at the end starts one more solve: a safety net for a basin lost to a model's error.
// The first cell that survives rules 1-3 is solved at once (a tight bound for the rest of the
// walk); the later ones are candidates, solved after the walk nearest model foot first, each
// solve lowering the bound for the rest (rules 1, 2 and 4 applied again), by a local solve
// (solvers/surface/projected_newton.hpp) from the model's minimiser: 2-5 Newton steps. The later
// solves stop after 1-3 steps when Newton's model proves their basin to be that of a minimiser
// already found, or - given the best distance so far - to hold nothing nearer (another copy of
// the same foot point on a periodic or folded parametrisation, or a worse local minimum).
#pragma once
#include "geometry/parametric_surface.hpp"
#include "geometry/projection_result.hpp"
#include "geometry/surface_closure.hpp"
#include "seeding/surface_cells.hpp"

namespace footpoint::surface {

// options.initial is a warm start: solved from first, its distance bounds the search from the
// start (a neighbour's foot speeds up a coherent sequence of points); the search is global as
// always. options.all_minima returns every distinct local minimum found (interior, edge, corner,
// pole), best first, at most options.max_minima. options.trace: the steps of the local solve that
// gave the answer. With no point within options.max_distance: beyond_max_distance, no foot point,
// and a certificate that none is nearer. `closure` (geometry/surface_closure.hpp): seams are no
// edges, poles are their own location. diagnostics.multiplicity: unique, tied or continuum.
ProjectionResult project_auto(const SurfaceCells& cells, const SurfaceFormulas& formulas, const ParamBox& box,
                              const SurfaceClosure& closure, const Vec3& p, const Options& options);

}  // namespace footpoint::surface
