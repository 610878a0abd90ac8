#include "implicit/solvers/implicit_surface_auto.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "implicit/solvers/implicit_surface_certificate.hpp"
#include "implicit/solvers/implicit_surface_lagrange.hpp"
#include "implicit/solvers/implicit_surface_methods.hpp"
#include "solvers/answer_multiplicity.hpp"
#include "solvers/iteration_control.hpp"

namespace footpoint::surface_implicit {

namespace {

// Newton's budget per start, and the rounds of certificate and new starts.
constexpr int kLocalIterations = 50;
constexpr int kAutoFirstOrderIterations = 200;
constexpr int kRounds = 6;
constexpr std::size_t kStartsPerRound = 4;
// Solves from samples that may lie by another foot at the answer's distance (a tie).
constexpr std::size_t kTieStarts = 8;

struct Candidate {
  Vec3 x;
  double distance = curve::kInfinity;
  Location location = Location::unknown;
  int iterations = 0;
  double step = 0.0;
};

class Search {
 public:
  Search(const ImplicitSurfaceEquation& equation, const ImplicitSurfaceCells& cells, Vec3 p,
         const curve::IterationControl& control)
      : equation_(equation), cells_(cells), p_(p), control_(control) {}

  void consider(Vec3 x, Location location, int iterations = 0, double step = 0.0) {
    const double d = norm(p_ - x);
    reached_.push_back({x, d});
    if (d < best_.distance) best_ = {x, d, location, iterations, step};
  }

  // With all_minima: keeps the solves' ends that are local minima of the distance on S ∩ B.
  void collect_minima(std::vector<Candidate>* minima) { minima_ = minima; }

  // A local minimum of |p - x|^2 / 2 on S within the box at the stationary point x with multiplier
  // l (and, on the face x_axis = bound, its multiplier m along e_axis): the Lagrangian's Hessian
  // I + l H is positive semidefinite on the directions x can move in ([NW06] Theorem 12.5), and on
  // a face p - x points out of the box (m >= 0 at an upper bound, <= 0 at a lower one).
  void keep_if_minimum(Vec3 x, double l, int axis = -1, double bound = 0.0) {
    if (!minima_) return;
    const ImplicitSurfaceJet j = equation_.jet(x);
    const Mat3 a = lagrangian_hessian(j, l);
    const double scale = 1e-10 * (1.0 + std::fabs(l) * norm(j.hess[0]) + std::fabs(l) * norm(j.hess[1]) +
                                  std::fabs(l) * norm(j.hess[2]));
    const double g = norm(j.grad);
    if (!(g > 0.0)) return;
    const Vec3 n = j.grad / g;
    if (axis >= 0) {
      Vec3 e{0.0, 0.0, 0.0};
      e[axis] = 1.0;
      const double m = dot(p_ - x - l * j.grad, e);
      if (bound == cells_.box.hi[axis] ? m < -scale : m > scale) return;
      const Vec3 t = cross(n, e);
      if (!(norm(t) > 0.0) || dot(t, a * t) < -scale * norm2(t)) return;
    } else {
      // the form on the tangent plane must be >= 0
      const TangentForm t = tangent_form(a, n);
      const double a11 = t.a11, a12 = t.a12, a22 = t.a22;
      if (a11 < -scale || a22 < -scale || a11 * a22 - a12 * a12 < -scale * (std::fabs(a11) + std::fabs(a22)))
        return;
    }
    minima_->push_back({x, norm(p_ - x), box_location(cells_.box, x)});
  }

  // Newton on the Lagrange system from the surface point s, then on the faces it leaves the box
  // through or lies near (within a leaf's diagonal).
  void solve_from(Vec3 s) {
    ++starts_;
    const Box3& box = cells_.box;
    const double h = cells_.leaf_diagonal;
    const SurfaceMinimum m = lagrange_newton_interior(equation_, p_, s, 2.0 * h, control_);
    if (m.converged && box.contains(m.x)) {
      consider(m.x, box_location(box, m.x), m.iterations, m.step);
      keep_if_minimum(m.x, m.multiplier);
    }
    if (!m.converged) {
      // Newton's system is singular along a continuum of feet (p on a surface of revolution's
      // axis): Hartmann's iteration, whose step needs no solve, settles on one of them.
      curve::IterationControl slow = control_;
      slow.max_iterations = kAutoFirstOrderIterations;
      const HartmannEnd e = hartmann_iteration(equation_, p_, s, slow);
      if (e.status == Status::converged && box.contains(e.x))
        consider(e.x, box_location(box, e.x), e.iterations, e.step);
    }
    for (int k = 0; k < 3; ++k)
      for (const double bound : {box.lo[k], box.hi[k]}) {
        const bool beyond = m.converged && (bound == box.lo[k] ? m.x[k] < bound : m.x[k] > bound);
        if (!beyond && std::fabs(s[k] - bound) > h) continue;
        ++starts_;
        const SurfaceMinimum f = lagrange_newton_face(equation_, p_, s, k, bound, 2.0 * h, control_);
        if (f.converged && box.contains(f.x)) {
          consider(f.x, box_location(box, f.x), f.iterations, f.step);
          keep_if_minimum(f.x, f.multiplier, k, bound);
        }
      }
  }

  // The sample nearest to p (the k-d tree over the samples).
  int nearest_sample() const {
    if (!cells_.sample_index) return -1;
    double d2 = 0.0;
    return cells_.sample_index->nearest(p_, d2);
  }

  // Whether no other sample within `radius` of sample i is nearer to p (a discrete local minimum of
  // the distance over the samples: a start of its own for all_minima).
  bool discrete_minimum(int i, double radius) const {
    return discrete_minimum(cells_.samples[static_cast<std::size_t>(i)], radius);
  }
  bool discrete_minimum(Vec3 s, double radius) const {
    return !cells_.sample_index || !cells_.sample_index->nearer_within(s, radius, p_, norm2(p_ - s));
  }

  // Other feet within the tie's gap of the answer's distance (solvers/answer_multiplicity.hpp):
  // the certificate's tie_starts (the samples of the leaves outside its convex box K that may hold
  // such a foot, more than two leaf diagonals from the answer: every leaf that holds one) that are
  // discrete local minima of the distance among the tie_samples (those, and K's leaves that meet
  // the ball of that radius) start solves, nearest first, at most kTieStarts. Among those alone: a
  // chain of ever nearer samples, each within two leaf diagonals of the last, from a tied foot's
  // sample then stays among them and ends at a start, or by the answer; a sample of another leaf
  // (a sample may lie up to half a leaf's edge outside its leaf) could otherwise be the nearer one
  // that hides the tie and starts nothing.
  void solve_ties(const SurfaceCertificate& c) {
    if (c.tie_starts.empty() || !cells_.sample_index) return;
    const double h = cells_.leaf_diagonal;
    std::vector<Vec3> starts;
    for (const std::int32_t i : c.tie_starts) {
      const Vec3 s = cells_.samples[static_cast<std::size_t>(i)];
      if (!cells_.sample_index->nearer_within(s, 2.0 * h, p_, norm2(p_ - s), c.tie_samples))
        starts.push_back(s);
    }
    std::sort(starts.begin(), starts.end(), [&](Vec3 a, Vec3 b) { return norm2(p_ - a) < norm2(p_ - b); });
    for (std::size_t i = 0; i < std::min(starts.size(), kTieStarts); ++i) solve_from(starts[i]);
  }

  // A nearer minimum or a continuum the certificate's bound did not settle (it failed with no
  // sample nearer than the answer): its rivals that lie away from the answer and are discrete
  // local minima of the distance over the samples start solves, nearest first, at most
  // kTieStarts. `near_minima`: a nearer minimum the samples do not show (two minima of nearly
  // equal distance within two leaf diagonals): every rival more than a leaf diagonal from the
  // answer.
  void solve_from_rivals(std::vector<Vec3> rivals, bool near_minima = false) {
    if (!std::isfinite(best_.distance)) return;
    const double h = cells_.leaf_diagonal;
    const Vec3 answer = best_.x;
    std::sort(rivals.begin(), rivals.end(), [&](Vec3 a, Vec3 b) { return norm2(p_ - a) < norm2(p_ - b); });
    std::size_t started = 0;
    for (const Vec3& s : rivals) {
      if (started >= kTieStarts) break;
      if (near_minima ? norm(s - answer) <= h : norm(s - answer) <= 2.0 * h || !discrete_minimum(s, 2.0 * h))
        continue;
      solve_from(s);
      ++started;
    }
  }

  const Candidate& best() const { return best_; }
  int starts() const { return starts_; }
  // Every point of S considered: the solves' ends, the box's edge points, the singular points.
  const std::vector<ReachedFoot>& reached() const { return reached_; }

 private:
  const ImplicitSurfaceEquation& equation_;
  const ImplicitSurfaceCells& cells_;
  Vec3 p_;
  const curve::IterationControl& control_;
  Candidate best_;
  int starts_ = 0;
  std::vector<ReachedFoot> reached_;
  std::vector<Candidate>* minima_ = nullptr;
};

}  // namespace

ProjectionResult implicit_surface_auto(const ImplicitSurfaceEquation& equation,
                                       const ImplicitSurfaceCells& cells, Vec3 p, const Options& options) {
  std::vector<std::array<double, 3>> trace;
  const curve::IterationControl control = curve::make_control(options, kLocalIterations, &trace);
  Search search(equation, cells, p, control);
  for (const BoxEdgePoint& e : cells.edge_points)
    search.consider(e.x, e.corner ? Location::box_corner : Location::box_edge);
  for (const Vec3& s : cells.singular_points) search.consider(s, Location::singular_point);
  std::vector<Candidate> minima;
  if (options.all_minima) {
    // Every discrete local minimum of the distance over the samples starts a solve of its own.
    search.collect_minima(&minima);
    for (std::size_t i = 0; i < cells.samples.size(); ++i)
      if (search.discrete_minimum(static_cast<int>(i), 2.0 * cells.leaf_diagonal))
        search.solve_from(cells.samples[i]);
  }
  const int nearest = search.nearest_sample();
  if (nearest >= 0) search.solve_from(cells.samples[static_cast<std::size_t>(nearest)]);
  // No local solve converged (a kink of abs, min or max, where Newton's and Hartmann's steps are
  // undefined): the nearest sample, a point of the surface but no stationary point of the
  // distance, is the answer, reported as degenerate with its certificate.
  const bool stationary = std::isfinite(search.best().distance);
  if (!stationary && nearest >= 0) {
    const Vec3 s = cells.samples[static_cast<std::size_t>(nearest)];
    search.consider(s, box_location(cells.box, s));
  }

  ProjectionResult r;
  Certificate certificate;
  const bool certify = options.certify.value_or(true);
  if (std::isfinite(search.best().distance) && certify) {
    // The first round on a tenth of the box budget: an answer that needs more is often not the
    // nearest (a nearer minimum close to it, which the rivals' solves then find), and one that is
    // gets the full budget in the next round.
    int budget = kCertificateBoxes / 10;
    for (int round = 0; round < kRounds; ++round) {
      SurfaceCertificate c =
          certify_surface_answer(equation, cells, p, search.best().x, search.best().distance, budget);
      certificate = c.certificate;
      if (certificate.certified) {
        search.solve_ties(c);  // a tie's other feet
        break;
      }
      const double before = search.best().distance;
      if (c.nearer.empty()) {
        // nothing sampled is nearer, yet the bound stayed below: the answer may be off a flat
        // minimum (a continuum), whose other points are among the rivals, or a nearer minimum
        // lies close to the answer, where its own samples are not nearer than the answer
        search.solve_from_rivals(c.rivals);
        if (!(search.best().distance < before)) search.solve_from_rivals(std::move(c.rivals), true);
      } else {
        std::sort(c.nearer.begin(), c.nearer.end(),
                  [&](Vec3 a, Vec3 b) { return norm2(p - a) < norm2(p - b); });
        for (std::size_t i = 0; i < std::min(c.nearer.size(), kStartsPerRound); ++i)
          search.solve_from(c.nearer[i]);
      }
      if (!(search.best().distance < before) && budget == kCertificateBoxes) break;
      budget = kCertificateBoxes;
    }
  }
  const Candidate& best = search.best();
  if (!std::isfinite(best.distance)) {
    r.dim = 3;
    r.num_params = 0;
    r.summary.method = "auto";
    r.summary.status = Status::degenerate;
    r.summary.starts = search.starts();
    return r;
  }
  r = implicit_surface_result(equation, cells.box, p, best.x, "auto");
  if (best.location == Location::singular_point) {
    r.summary.location = Location::singular_point;
    r.summary.orthogonality[0] = 0.0;  // no normal at a singular point
  }
  r.summary.status =
      curve::within_max_distance(stationary ? Status::converged : Status::degenerate, best.distance, control);
  r.summary.iterations = best.iterations;
  r.summary.step_norm = best.step;
  r.summary.starts = search.starts();
  r.summary.certificate = certificate;
  if (!certify) r.summary.certificate.computed = false;
  // flat to second order (solvers/answer_multiplicity.hpp): with p - X = l grad f (the Lagrange
  // condition), the Hessian of ½|x - p|^2 on S at X is the Lagrangian's I + l H(X) on the tangent
  // plane ([NW06] Theorem 12.5), whose least eigenvalue vanishes when p is a centre of curvature
  // of S at X: the centre of a sphere, a point on a surface of revolution's axis facing its
  // circle of feet. The points reached: the solves' ends, the box's edge points, the singular points.
  const auto flat = [&] {
    const Vec3 answer{r.foot[0], r.foot[1], r.foot[2]};
    const ImplicitSurfaceJet j = equation.jet(answer);
    const double g2 = norm2(j.grad);
    if (!(g2 > 0.0)) return false;
    const double l = dot(p - answer, j.grad) / g2;
    return std::fabs(tangent_form(lagrangian_hessian(j, l), j.grad / std::sqrt(g2)).least_eigenvalue()) <=
           kFlatMinimum;
  };
  r.summary.multiplicity =
      answer_multiplicity(r, p, flat, search.reached(), [](const ReachedFoot& f) { return f.foot; });
  r.trace = std::move(trace);
  if (options.all_minima) {
    // The answer first, then the other local minima found, nearest first, each foot once; a
    // continuum of nearest points once, by the answer (as parametric surfaces and curves list it).
    const bool continuum = r.summary.multiplicity.kind == Multiplicity::continuum;
    const double gap = TiedFeet::gap_of(r.distance, p, Vec3{r.foot[0], r.foot[1], r.foot[2]});
    if (continuum)
      std::erase_if(minima, [&](const Candidate& m) { return std::fabs(m.distance - r.distance) <= gap; });
    minima.insert(minima.begin(), best);
    std::stable_sort(minima.begin() + 1, minima.end(),
                     [](const Candidate& a, const Candidate& b) { return a.distance < b.distance; });
    for (const Candidate& m : minima) {
      bool seen = false;
      for (const Minimum& k : r.minima)
        seen = seen || norm(m.x - Vec3{k.foot[0], k.foot[1], k.foot[2]}) <= kDistinctFoot * (1.0 + norm(m.x));
      if (seen || m.distance > control.max_distance) continue;
      Minimum out;
      out.foot = {m.x.x, m.x.y, m.x.z};
      out.distance = m.distance;
      out.location = m.location == Location::singular_point ? m.location : box_location(cells.box, m.x);
      r.minima.push_back(out);
    }
    cap_minima(r, options);
  }
  if (r.summary.status == Status::beyond_max_distance) withhold_answer(r);
  return r;
}

}  // namespace footpoint::surface_implicit
