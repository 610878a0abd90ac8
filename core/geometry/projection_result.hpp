// What every projection returns: the foot point, its parameters, the distance and the solve's
// Summary (the "convergence diagnostics"), plus optional minima and trace. One small struct per
// solve, filled by the solver, serialized by the server, asserted by the tests.
#pragma once
#include <array>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "geometry/certificate.hpp"

namespace footpoint {

enum class Status {
  converged,            // residuals meet the tolerance
  max_iterations,       // iteration budget spent before convergence
  diverged,             // iterates grew without bound / left every sensible region
  non_finite,           // a formula or a step produced NaN or infinity
  degenerate,           // singular Jacobian / tangent plane (e.g. s_u x s_v = 0) stopped the method
  outside_domain,       // a paper method converged, but to parameters outside the domain
  not_orthogonal,       // the method settled on the geometry at a point that is not orthogonal: not a
                        // foot point ([Curve] Algorithm 1 only lands on the curve)
  beyond_max_distance,  // every point of the geometry is farther than options.max_distance
  deadline_exceeded,    // the request's deadline passed before this point was solved
};
const char* to_string(Status s);

enum class Location { interior, edge, corner, endpoint, box_face, singular_point, unknown };
const char* to_string(Location l);

struct Summary {
  std::string method;  // the method that ran ("auto", "gsa", ...)
  Status status = Status::non_finite;
  int iterations = 0;      // iterations of the (final) local solve
  double step_norm = 0.0;  // norm of the last parameter / position increment
  // Orthogonality residuals: surfaces |<p-s,s_u>|/(|p-s||s_u|), |<p-s,s_v>|/(|p-s||s_v|);
  // parametric curves one entry; implicit curves |<p-X, n1 x n2>|/(|p-X||n1 x n2|).
  std::array<double, 2> orthogonality{0.0, 0.0};
  // Implicit curves: |f1|/|grad f1|, |f2|/|grad f2| at the foot point (0 otherwise).
  std::array<double, 2> equation_residual{0.0, 0.0};
  int starts = 1;  // local solves started (auto: seeds tried)
  Location location = Location::unknown;
  bool on_boundary = false;  // foot point on the domain's edge/corner/endpoint/box face
  Certificate certificate;   // the proof of global optimality (geometry/certificate.hpp)
  double residual() const;   // the largest of orthogonality and equation residuals
  bool converged() const { return status == Status::converged; }
};

// One local minimum of the distance (all_minima option), told apart by its foot point.
struct Minimum {
  std::array<double, 3> foot{};
  std::array<double, 2> params{};
  double distance = 0.0;
  Location location = Location::unknown;
};

struct ProjectionResult {
  int dim = 3;         // 2 for planar curves, else 3
  int num_params = 2;  // 2 surfaces, 1 parametric curves, 0 implicit curves
  std::array<double, 3> foot{};
  std::array<double, 2> params{};
  double distance = std::numeric_limits<double>::quiet_NaN();
  Summary summary;
  std::vector<Minimum> minima;               // with options.all_minima, best first
  std::vector<std::array<double, 3>> trace;  // with options.trace: per-iteration increments
};

struct Options {
  // Convergence tolerance on the relative parameter step (and on the relative residuals).
  // 0 selects the method's default (parameters converged to ~1e-15 relative).
  double tolerance = 0.0;
  int max_iterations = 0;                        // 0 selects the method's default
  std::optional<std::array<double, 3>> initial;  // a start: (u,v) / (t) / (x,y,z)
  bool all_minima = false;
  bool trace = false;
  double max_distance = std::numeric_limits<double>::infinity();
  // Compute a certificate (geometry/certificate.hpp). Unset: the method's default - `auto`
  // certifies, the papers' local methods do not (asked, they get their answer certified or
  // refuted by the same bounds, without a search for a better one).
  std::optional<bool> certify;
};

}  // namespace footpoint
