// The search of surface `auto` (parametric/solvers/surface_auto.hpp): one SurfaceSearch per point. The
// walk of the cell tree, the cell rules and the candidates' solves are surface_search.cpp; the
// answer made of what the walk found (the certificate, the multiplicity, all_minima) is
// surface_search_answer.cpp. Internal to solvers/surface.
#pragma once
#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

#include "parametric/geometry/box_quadratic.hpp"
#include "parametric/geometry/parametric_surface.hpp"
#include "parametric/geometry/params.hpp"
#include "parametric/geometry/surface_closure.hpp"
#include "parametric/seeding/surface_cells.hpp"
#include "parametric/solvers/projected_newton.hpp"
#include "parametric/solvers/surface_convergence.hpp"
#include "projection/projection_result.hpp"

namespace footpoint::surface {

// The Newton model's minimiser is sought over the cell grown by this fraction of its width on
// each side, so that a minimum near a cell's border is claimed by the cells on both sides.
inline constexpr double kMargin = 0.25;
// A minimiser predicted by an early-stopped solve this near (relative to 1 + |foot|) to a foot
// found is a copy of it (the multiplicity's test).
inline constexpr double kCopyOfFoot = 1e-6;
// Solutions remembered for the known-minimum rule when not all minima are wanted.
inline constexpr int kRemembered = 16;
inline constexpr int kStack = 128;
// Claims (the claim rule) remembered to find two cells that claim each other.
inline constexpr int kClaims = 128;
// The known-minimum rule: a minimum found within this many cell widths of where a fine cell's model puts its
// minimum is that minimum (a fine cell's model has one minimum; a second, better one that near
// would show in it). Measured from the model's minimiser, not from the cell: a minimum one cell
// away from one the model sees inside its own cell is another one.
inline constexpr double kSameBasin = 1.0;
// Cells waiting for a local solve (more are solved in batches of this size).
inline constexpr int kCandidates = 64;

// Which face of the domain a parameter point is on: per parameter -1 (lower bound), +1 (upper),
// 0 (inside). The known-minimum rule only merges a candidate with a minimum on the same face.
// (No default member initializers: the search's candidate buffer is left unconstructed until
// used; Face{} is the interior.)
struct Face {
  int u, v;
  bool operator==(const Face&) const = default;
};

// The face of the domain that a box minimum is on: on the side `side` of the rectangle
// [lo, hi] where that side is the domain's bound.
inline Face face_of(const ParamBox& box, const std::array<int, 2>& side, const Params<2>& lo,
                    const Params<2>& hi) {
  return {side[0] < 0 && lo[0] == box.umin ? -1 : (side[0] > 0 && hi[0] == box.umax ? 1 : 0),
          side[1] < 0 && lo[1] == box.vmin ? -1 : (side[1] > 0 && hi[1] == box.vmax ? 1 : 0)};
}

inline Face face_of(const ParamBox& box, double u, double v) {
  return {u <= box.umin ? -1 : (u >= box.umax ? 1 : 0), v <= box.vmin ? -1 : (v >= box.vmax ? 1 : 0)};
}

struct Found {
  LocalSolution sol;
  double u_start = 0.0, v_start = 0.0;
};

class SurfaceSearch {
  struct Candidate;

 public:
  SurfaceSearch(const SurfaceCells& cells, const SurfaceFormulas& formulas, const ParamBox& box,
                const SurfaceClosure& closure, const Vec3& p, const Options& options)
      : cells_(cells),
        formulas_(formulas),
        box_(box),
        closure_(closure),
        p_(p),
        options_(options),
        criteria_(convergence_criteria(options, box, kLocalMaxIterations)),
        bound_(options.max_distance) {
    if (options.all_minima) all_.reserve(8);
  }

  void run();

  ProjectionResult result();

 private:
  // The local solve (parametric/solvers/projected_newton.hpp) on the surface rather than on its
  // parameter box: a solve that stops on a bound of a closed direction because the distance still
  // decreases across it (the gradient <s - p, s_u> of ½|s - p|^2 points out of the box, by more
  // than rounding) goes on from the opposite bound, the same points of the surface
  // (parametric/geometry/surface_closure.hpp); at most kSeamCrossings times.
  LocalSolution solve_across_seams(double u, double v, std::vector<std::array<double, 3>>* trace = nullptr,
                                   const EarlyStop* early = nullptr,
                                   const SurfaceJet* start_jet = nullptr) const;
  static constexpr int kSeamCrossings = 4;
  static constexpr double kSeamSlope = 1e-10;

  // The result at a local solve's minimiser.
  ProjectionResult answer(const LocalSolution& s) const;

  // No point of the surface within options.max_distance (or none finite): no foot point,
  // parameters or distance (null in JSON), never an intermediate point.
  ProjectionResult no_answer() const;

  // The certificate of the answer (parametric/solvers/surface_certificate.hpp), from every minimiser
  // the search found; where it finds a nearer minimum (the search's estimates lost its basin), that
  // one is the answer. Without an answer within options.max_distance, the certificate proves that
  // none is nearer than it (a lower bound of at least max_distance, to the gap) - or finds one.
  void certify(ProjectionResult& r, bool within);

  // How many feet are nearest (projection/projection_result.hpp): a continuum where the Hessian of
  // f = ½|s - p|^2 at the answer, over the parameters free there, is singular to rounding (a
  // direction along which the distance stays); else the distinct feet among the minima solved to
  // the end at the answer's distance within the certificate's gap.
  AnswerMultiplicity multiplicity(const ProjectionResult& r) const;

  // A leaf of the walk: cell `index`, whose box is `box_lb` away, through the tangent-plane and
  // claim rules; what survives becomes candidates.
  void visit(std::int32_t index, double box_lb);

  // Candidates at the model's best point on each of the cell's sides on the domain's boundary
  // whose model value is at most `threshold`, other than on `except` (a candidate already).
  void add_boundary_candidates(const SurfaceCell& c, const BoxQuadratic& q, double lb, double threshold,
                               Face except);

  // A cell that may hold a better minimum, to be solved from its centre + (du, dv); `model` is
  // its Newton model (its Hessian at the centre starts the early stop's Lipschitz estimate).
  // The known-minimum rule may merge it with a minimum found nearby if the cell is resolved and `mergeable`;
  // `basin`, when given, is where (else around the model's minimiser, or the coarse cell itself).
  void add_candidate(const SurfaceCell& c, const BoxQuadratic& model, double du, double dv, double lb,
                     Face face, bool mergeable = true,
                     std::optional<std::array<double, 4>> basin = std::nullopt);

  // Nearest model foot first; each solve lowers the bound, which drops the candidates whose
  // lower bound it passes (the box and tangent-plane rules again). The known-minimum rule: a
  // candidate next to a minimum already found, no farther than the cell model's foot, on the same
  // face of the domain (interior, the same edge, the same corner), is that minimum - within
  // kSameBasin cells of a fine cell's model minimiser, inside a coarse cell, in the grown cell
  // where a coarse cell's failed claim pointed; never for the boundary candidates of a coarse
  // cell. Distinct minima are told apart by parameters here, not by 3-D foot points: a surface
  // folding over itself has distinct minima with feet closer than any model can tell apart.
  // Periodic and degenerate parametrisations, which reach one foot from many (u, v), cost a local
  // solve per copy, cut short by the early stop (parametric/solvers/basin_early_stop.hpp); the
  // copies are merged by foot point in the result. The others are solved, and stop early once
  // their basin is shown to be a known minimiser's.
  void solve_candidates();

  // A local solve from (u0, v0); `from` (a candidate) gives the early stop its reference point.
  void solve(double u0, double v0, const Candidate* from = nullptr);

  // A minimum the certificate found: among the minima for the multiplicity and all_minima.
  void record_solution(const LocalSolution& s);

  // A minimiser (u, v) at `distance` (an abandoned solve's: a lower bound), for the known-minimum
  // rule and the certificate.
  void remember(double u, double v, double distance);

  // Smaller distance wins; a converged solution wins a tie with an unconverged one.
  static bool better(const LocalSolution& a, const LocalSolution& b);

  // Greedy walk to the leaf whose boxes are nearest (no solve): the first cell visited, and the
  // answer beyond max_distance. With `path`, records the nodes passed and their children's
  // squared box distances, which the walk reuses.
  struct PathStep {
    std::int32_t node;
    double d2[SurfaceCellNode::kWidth];
  };
  std::int32_t descend(PathStep* path = nullptr, int* path_length = nullptr) const;

  // Every distinct minimum found within max_distance, best first, at most options.max_minima
  // (*truncated when more were found); a continuum at the answer's distance is its one
  // representative, the answer.
  std::vector<Minimum> minima(const ProjectionResult& r, bool* truncated) const;
  // The parameter copies of one foot point from the parameters solved for it (Minimum::copies):
  // their images across the closure's seams, then their translates (SelfCovering::copies).
  std::vector<Params<2>> parameter_copies(std::vector<Params<2>> seeds, bool* truncated) const;

  const SurfaceCells& cells_;
  const SurfaceFormulas& formulas_;
  const ParamBox& box_;
  const SurfaceClosure& closure_;
  const Vec3 p_;
  const Options& options_;
  const ConvergenceCriteria criteria_;
  double bound_;
  double nearest_ = std::numeric_limits<double>::infinity();
  std::int32_t nearest_cell_ = -1;
  int solves_ = 0;
  Found best_;
  bool has_best_ = false;
  // A cell whose model puts the minimum in a neighbour: its grown rectangle and that point.
  struct Claim {
    double u0, u1, v0, v1;
    double u, v;
    bool grown_contains(double x, double y) const { return x >= u0 && x <= u1 && y >= v0 && y <= v1; }
  };
  Claim claims_[kClaims];
  struct Candidate {
    double d_model;               // distance to the model's foot point
    double lb;                    // lower bound (box and tangent-plane rules)
    double u, v;                  // start of the local solve
    std::array<double, 4> basin;  // the known-minimum rule's region: u0, u1, v0, v1
    Face face;                    // the face the model's minimiser is on
    bool mergeable;               // the known-minimum rule applies
    Params<2> reference_t;        // the cell's centre and the Newton model's Hessian there
    std::array<double, 3> reference_H;
  };
  Candidate candidates_[kCandidates];
  int candidates_count_ = 0;
  int claims_count_ = 0;
  Params<2> feet_[kRemembered];        // minimisers found (all_minima: all_ has all of them)
  double feet_distance_[kRemembered];  // and their distances (abandoned: lower bounds)
  int feet_count_ = 0;
  std::vector<Found> all_;
  // every minimiser found (u, v, distance; abandoned solves: the predicted minimiser and a lower
  // bound), for the certificate
  static constexpr int kMinimisers = 64;
  struct Minimiser {
    double u, v, distance;
    Vec3 foot;      // when complete
    bool complete;  // solved to the end (not abandoned early)
  };
  Minimiser minimisers_[kMinimisers];
  int minimisers_count_ = 0;
};

}  // namespace footpoint::surface
