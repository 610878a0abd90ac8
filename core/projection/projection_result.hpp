// What every projection returns: the foot point, its parameters, the distance and the solve's
// Summary (the "convergence diagnostics"), plus optional minima and trace. One small struct per
// solve, filled by the solver, serialized by the server, asserted by the tests.
#pragma once
#include <array>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "projection/certificate.hpp"

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

// Where the foot point lies: inside the domain, on an edge or corner of a surface's parameter box
// (a seam of a closed direction is no edge: it is interior), at a pole of a surface (an edge that
// is one point: every parameter along it gives the foot), at an end of a parametric curve (not of a
// closed one), on a face of an implicit curve's or surface's box, on an edge or at a corner of an
// implicit surface's box, at a singular point.
enum class Location {
  interior,
  edge,
  corner,
  endpoint,
  box_face,
  box_edge,
  box_corner,
  singular_point,
  pole,
  kink,
  unknown
};
const char* to_string(Location l);

// How many points of the geometry are nearest: one; k distinct feet at the same distance (within
// the certificate's gap); or a continuum (a curve of them: the foot's Hessian of the distance is
// singular along the geometry, as on the axis of a torus or at the centre of a sphere).
enum class Multiplicity { unique, tied, continuum };
const char* to_string(Multiplicity m);
// Foot points farther apart than this, relative to 1 + |foot|, are distinct (the multiplicity's
// feet and all_minima's entries, on every geometry).
inline constexpr double kDistinctFoot = 1e-8;

struct AnswerMultiplicity {
  bool computed = false;  // auto only
  Multiplicity kind = Multiplicity::unique;
  int count = 1;                            // distinct feet (tied)
  std::vector<std::array<double, 3>> feet;  // tied: the feet, the answer's first

  // Lists `foot` unless a foot listed is within `same` of it.
  void add_distinct(const std::array<double, 3>& foot, double same);
  // The kind the list says: tied with more than one foot, else unique (and no list).
  void settle();
};

struct Summary {
  std::string method;  // the method that ran ("auto", "gsa", ...)
  Status status = Status::non_finite;
  int iterations = 0;      // iterations of the (final) local solve
  double step_norm = 0.0;  // norm of the last parameter / position increment
  // Orthogonality residuals: surfaces |<p-s,s_u>|/(|p-s||s_u|), |<p-s,s_v>|/(|p-s||s_v|);
  // parametric curves one entry; implicit curves |<p-X, n1 x n2>|/(|p-X||n1 x n2|); implicit
  // surfaces |(p-X) x grad f|/(|p-X||grad f|), the sine of the angle between p - X and the normal.
  std::array<double, 2> orthogonality{0.0, 0.0};
  // Implicit curves: |f1|/|grad f1|, |f2|/|grad f2| at the foot point (0 otherwise); implicit
  // surfaces: |f|/|grad f| (one entry).
  std::array<double, 2> equation_residual{0.0, 0.0};
  int starts = 1;  // local solves started (auto: seeds tried)
  Location location = Location::unknown;
  bool on_boundary = false;  // foot point on the domain's edge/corner/endpoint/box face
  Certificate certificate;   // the proof of global optimality (projection/certificate.hpp)
  AnswerMultiplicity multiplicity;
  double residual() const;  // the largest of orthogonality and equation residuals
  bool converged() const { return status == Status::converged; }
};

// One local minimum of the distance (all_minima option), told apart by its foot point.
struct Minimum {
  std::array<double, 3> foot{};
  std::array<double, 2> params{};
  double distance = 0.0;
  Location location = Location::unknown;
  // Surfaces: every parameter pair of the domain known to give this foot point, `params` among
  // them, in increasing u, then v: the copies the search solved (a fold, a seam's two sides) and
  // their translates by the geometry's closure.translations that lie in the domain. At most
  // Options::minima_cap() (copies_truncated when more were found).
  std::vector<std::array<double, 2>> copies{};
  bool copies_truncated = false;
};

struct ProjectionResult {
  int dim = 3;         // 2 for planar curves, else 3
  int num_params = 2;  // 2 surfaces, 1 parametric curves, 0 implicit curves
  std::array<double, 3> foot{};
  std::array<double, 2> params{};
  double distance = std::numeric_limits<double>::quiet_NaN();
  Summary summary;
  std::vector<Minimum> minima;               // with options.all_minima, best first
  bool minima_truncated = false;             // more minima were found than options.max_minima
  std::vector<std::array<double, 3>> trace;  // with options.trace: per-iteration increments
  // The unit normal of the geometry at the foot point (dim coordinates; NaN where none is
  // defined: no answer, a singular point or pole, a space curve) and the distance with the sign
  // of <p - foot, normal> (NaN where the normal is). Set by set_foot_normal.
  std::array<double, 3> normal{std::numeric_limits<double>::quiet_NaN(),
                               std::numeric_limits<double>::quiet_NaN(),
                               std::numeric_limits<double>::quiet_NaN()};
  double signed_distance = std::numeric_limits<double>::quiet_NaN();
  bool has_normal() const { return normal[0] == normal[0]; }
};

// Records the unit normal n at r's foot point (the first r.dim coordinates of n are read) and the
// signed distance of the point p (r.dim coordinates): r.distance with the sign of <p - foot, n>
// (+0 where p is on the geometry). Without a finite answer, or with a non-finite n, both stay NaN.
void set_foot_normal(ProjectionResult& r, const double* p, const std::array<double, 3>& n);

struct Options {
  // Convergence tolerance on the relative parameter step (and on the relative residuals).
  // 0 selects the method's default (parameters converged to ~1e-15 relative).
  double tolerance = 0.0;
  int max_iterations = 0;                        // 0 selects the method's default
  std::optional<std::array<double, 3>> initial;  // a start: (u,v) / (t) / (x,y,z)
  bool all_minima = false;
  // all_minima lists at most this many (0: kDefaultMaxMinima), and says when it truncated.
  int max_minima = 0;
  static constexpr int kDefaultMaxMinima = 64;
  bool trace = false;
  double max_distance = std::numeric_limits<double>::infinity();
  // Compute a certificate (projection/certificate.hpp). Unset: the method's default - `auto`
  // certifies, the papers' local methods do not (asked, they get their answer certified or
  // refuted by the same bounds, without a search for a better one).
  std::optional<bool> certify;
  // The cap on all_minima's list.
  std::size_t minima_cap() const {
    return static_cast<std::size_t>(max_minima > 0 ? max_minima : kDefaultMaxMinima);
  }
};

// No point of the geometry within options.max_distance: status beyond_max_distance, and no foot
// point, parameters or distance (NaN; null in JSON), never an intermediate point; location unknown.
void withhold_answer(ProjectionResult& r);

// Keeps the first options.minima_cap() of r.minima (best first), and says when it cut.
void cap_minima(ProjectionResult& r, const Options& options);

}  // namespace footpoint
