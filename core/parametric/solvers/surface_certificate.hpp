// The certificate of an answer on a parametric surface (projection/certificate.hpp): a rigorous
// lower bound L on the distance from p to s over the whole closed domain, by branch and bound
// over the compiled cells (parametric/seeding/surface_cells.hpp) and, where they are too coarse, sub-boxes
// bounded at run time. Given the answer's distance d, a box is closed when a lower bound of the
// distance over it reaches the target d - gap/2 (gap = max(1e-9 d, absolute gap)); every bound
// is rigorous (parametric/geometry/distance_bound.hpp):
//   1. the interval box of s over the cell (the search hierarchy's boxes, outward rounded),
//      walked nearest first: a subtree whose box is beyond the target is closed whole;
//   2. the tangent-plane model at the cell's centre: the distance from p to the rectangle holding
//      the tangent parallelogram, less the proved model error ρ (SurfaceCellBounds::rho);
//   3. the second-order bound from the cell's centre (its jet with its rounding radii), with λ a
//      lower bound of the smallest eigenvalue of ∇²f = JᵀJ + Σ (s_k - p_k)∇²s_k over the cell;
//   4. from each known minimiser z near the box (the answer, its copies on a periodic or folded
//      parametrisation, other local minima): the foot region bound (parametric/geometry/
//      foot_region_bound.hpp) over the hull of the box and z, with the second partials of a box
//      that holds that hull (the box, the box it was bisected from, or its union with z's cell):
//      f(z) less the rounding wherever the surface about z bends little against its metric at the
//      scale of the hull, with no bound of ∇²f over the box; then the second-order bound of 3
//      from z, where f is convex on the box;
//   5. the monotonicity test (distance_bound.hpp: gradient_signs): a box over which f rises or
//      falls along a parameter, towards a face inside the domain, holds no minimiser and closes;
//   6. what remains open is solved from (auto: a local minimum nearer than the answer replaces
//      it, and the certificate continues with the new distance), then bisected: each half gets an
//      interval jet of its own (a runtime sub-box) and the bounds 1, 3, 4, 5 again, within a budget
//      of sub-boxes per point. Sampled estimates order nothing here that decides.
// L is the least bound of the boxes, not above the target where everything closed (and never
// above d). certified = d - L <= the gap; otherwise the reason: budget_exhausted, non_finite (a
// box where the formulas are undefined or not smooth stayed open), or nearer_point (certifying
// a given answer without search, a point of the surface nearer than it by more than the gap was
// found: the answer is no global minimum).
#pragma once
#include <array>
#include <functional>
#include <vector>

#include "parametric/geometry/parametric_surface.hpp"
#include "parametric/geometry/params.hpp"
#include "parametric/seeding/surface_cells.hpp"
#include "parametric/solvers/projected_newton.hpp"
#include "projection/certificate.hpp"

namespace footpoint::surface {

struct SurfaceCertifyOptions {
  // Sub-boxes bounded per point beyond the compiled cells (one interval jet and one ball jet each
  // where the refinement has not kept them yet; once kept, their enclosures are read, not
  // computed again). The count decides, not the cache: an answer's certificate is the same whichever
  // points came before it. 1600: on bench/surface_bench's sets (section 1: the Open CASCADE
  // comparison's S1-S3, [GSA] Ex. 1 over [-25,25]^2, torus, sphere; box and near points) >= 99.3 %
  // certified, against 5-99 % with 48 and 65-100 % with 400. Most points need far fewer; the rest
  // lie near folds (s_u x s_v = 0), where the distance's basins are narrow along the fold and only
  // small boxes prove convexity, or see many copies of their foot (a self-covering domain), each
  // needing its own proof.
  int max_boxes = 1600;
  // Local solves started per point from boxes that stay open.
  int max_solves = 32;
  // The answer is a distance to certify against (no point of the surface within max_distance),
  // not a point: its distance is not measured from its parameters (CertificateLedger::measure_from).
  bool threshold = false;
};

struct SurfaceCertification {
  Certificate certificate;
  // A local minimum nearer than the answer, found while certifying with a solver (auto).
  bool improved = false;
  LocalSolution better;
};

// A local solve from (u, v) (auto: projected Newton to convergence).
using SurfaceLocalSolve = std::function<LocalSolution(double u, double v)>;

// Certifies `answer` (its parameters, jet and distance) for the point p. `known` are other
// minimisers (parameters) already found. `solve` is started where a box stays open (it finds the
// copies of a tied answer and the minima a box may hide); a minimum nearer than the answer
// replaces it when `may_improve` (auto: returned in `better`), and refutes it otherwise.
SurfaceCertification certify_surface(const SurfaceCells& cells, const SurfaceFormulas& formulas,
                                     const ParamBox& box, const Vec3& p, const LocalSolution& answer,
                                     const std::vector<Params<2>>& known, const SurfaceLocalSolve& solve,
                                     bool may_improve, const SurfaceCertifyOptions& options = {});

// The certificate of an answer at (u, v) inside the domain, given as it is (a paper's method with
// options.certify): certified, or refuted with reason nearer_point, or neither within the budget.
Certificate certify_answer(const SurfaceCells& cells, const SurfaceFormulas& formulas, const ParamBox& box,
                           const Vec3& p, double u, double v, const SurfaceCertifyOptions& options = {});

}  // namespace footpoint::surface
