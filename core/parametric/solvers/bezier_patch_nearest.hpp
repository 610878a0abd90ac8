// The nearest point of one Bézier patch, polynomial or rational, proved from its control net alone: a branch
// and bound over sub-patches (the dyadic quarters, by de Casteljau), each bounded below two ways,
// the larger kept:
//  - the convex hull property: a sub-patch lies in the box of its control points, so the distance
//    from p to that box bounds it ([PieglTiller] L. Piegl, W. Tiller, The NURBS Book, 2nd ed.,
//    Springer 1997, the properties of Bézier surfaces in ch. 3);
//  - a second-order bound of f = ½|S - p|²: by Taylor's theorem f(c + δ) >= f(c) + ∇f(c)·δ +
//    ½ δᵀ H δ for any H enclosing f's Hessian over the sub-patch; f_ss = |S_s|² + (S - p)·S_ss
//    and its kin are enclosed from the boxes of the nets of differences (S_s, S_t, S_ss, S_st,
//    S_tt are Bézier patches of the differences of the net), and on each quadrant of the box
//    about c (δ's signs fixed) the form's least value is found exactly (a corner, an edge's
//    one-dimensional minimum, or the interior stationary point). c is the point of the sub-patch
//    nearest the candidate foot x* in the parameters: x* on the sub-patches that hold it
//    (∇f(x*) ~ 0: the bound is f(x*) to the rounding, which the hull alone reaches only after ~15
//    levels), else a corner or a point of a side (the sub-patches about x*, whose sides pass
//    near it: there f(c) - f(x*) ~ ½ |c - x*|² in f's Hessian, lost from a farther corner).
// A sub-patch over which a component of f's gradient keeps one sign (its enclosure, tightened by
// the centred form ∇f(c) + H δ) towards a side inside the patch holds neither the nearest point
// nor any local minimum: it is dropped, from the search and from the bound (the monotonicity test
// of interval global optimisation, [Hansen] E. Hansen, G. W. Walster, Global Optimization Using
// Interval Analysis, 2nd ed., Dekker 2004, ch. 12).
// The candidate is projected Newton's on the box [0, 1]² from the parameters of the control point
// nearest p, restarted in a sub-patch that may hold a nearer point. A sub-patch is settled when
// it cannot hold a foot within the certificate's gap (projection/certificate.hpp) of the candidate,
// or when it holds the candidate and f has a single local minimum there: f strictly convex (the
// least eigenvalue of every matrix in H positive), or along a direction where x* is on the patch's
// edge, f's derivative of one sign over the whole sub-patch (enclosed in the centred form
// ∇f(x*) + H δ) pushing towards that edge, and f convex along the other. Then x*, which meets
// the first-order conditions, is the sub-patch's only minimum and the foot is unique. The lower
// bound returned is the least of the settled sub-patches' bounds (the dropped ones hold no
// minimum), rigorous for the polynomial of
// the net as stored: every subdivision's rounding is carried as an absolute error of the nets'
// points, the candidate's jet is enclosed with the Bernstein sums' rounding, and every bound is
// rounded outwards. The first kCellLevels levels of quarters and their enclosures, which do not
// depend on p, are computed once per patch.
//
// A rational patch, S = A / W with W = Σ w_kl B_kl > 0, is bounded through one polynomial that
// keeps the dependency between A and W (bounds of S's derivatives by the quotient rule lose it):
// with D = A - p W = Σ w_kl (P_kl - p) B_kl, F = |S - p|² = N / M for N = |D|², M = W², and for a
// level L, F >= L on a sub-patch iff g_L = N - L M >= 0 there. N and M are Bernstein forms of
// degree 2p x 2q, their nets from the sub-patch's nets of D and W by the product formula
// ([FaroukiRajan] R. T. Farouki, V. T. Rajan, Algorithms for polynomials in Bernstein form,
// CAGD 5 (1988) 1-26). Each sub-patch is bounded below by the largest of
//  - its hull (the convex hull property holds with positive weights, [PieglTiller] P4.9);
//  - F >= min_k N_k / M_k (every M_k > 0, so N - F_min M has no negative coefficient): the ratio
//    of Bernstein coefficients, which converges quadratically under subdivision ([CargoShisha]
//    G. T. Cargo, O. Shisha, The Bernstein form of a polynomial, J. Res. NBS 70B (1966) 79-81);
//  - g_L >= γ by Taylor's theorem with L = F(x*), from x* on the sub-patches that hold it
//    (g_L(x*) ~ 0 and ∇g_L(x*) = M ∇F(x*) + (F(x*) - L) ∇M ~ 0: near the foot this removes the
//    cluster effect of the coefficients' O(h²) error), else from the corner nearest x*, with
//    g_L's Hessian enclosed by its nets of second differences and the quadratic form's least
//    value on each quadrant exact as above (it is at least g(x*) - |∇g|² / (2 λ), the Newton-type
//    bound, where g is λ-convex); then F >= L + γ / M with M's range from its net.
// The foot is unique on a sub-patch holding x* when g_L' is strictly convex there for every level
// L' from the sub-patch's lower bound to the tie's (Hess g_L' = Hess g_L - (L' - L) Hess M, both
// enclosed from their nets): a local minimum y of F there with F(y) = L' is one of g_L' =
// M (F - L') too, where g_L'(y) = 0, so by convexity g_L' > 0 elsewhere on the sub-patch, i.e.
// F > F(y): F has one local minimum there within the tie. At the foot Hess g_L = M Hess F, so g is
// as convex as F where it matters. The rounding: D's net is within the nets' errors (err, err_w
// times |p|) plus two roundings of |A| + |p| W, N's and M's nets within 6 (|D| + e) e and the
// product's roundings (its weights are nonnegative and sum to 1), and every bound is rounded
// outwards.
//
// It gives up (proved = false, the caller solves the patch another way) when that cannot be shown
// within the budget of sub-patches: two feet at the same distance, a continuum, a degenerate
// (pole) edge, a saddle of the distance, a rational patch's point closer to it than its
// evaluation's rounding resolves.
#pragma once
#include <array>
#include <limits>
#include <vector>

#include "formula/interval.hpp"
#include "geometry/vec.hpp"
#include "parametric/geometry/parametric_surface.hpp"

namespace footpoint {

namespace bezier_detail {
using Interval = formula::Interval;
using IntervalVec = std::array<Interval, 3>;
// A sub-patch [s0, s1] x [t0, t1] (a cell of the dyadic quarters) and what bounds it independently
// of the point: the box of its net (widened by err, the net's distance to the exact sub-patch's),
// enclosures of S_s, S_t, S_ss, S_tt, S_st over it in its own local parameters (the nets of
// differences), of |S_s|², |S_t|², S_s·S_t, and at each corner the point and the inward first
// derivatives.
struct Cell {
  double s0 = 0.0, s1 = 1.0, t0 = 0.0, t1 = 1.0;
  double err = 0.0;
  double err_w = 0.0;  // a rational patch: its weights' error (its points' is err)
  Vec3 lo{}, hi{};
  IntervalVec su{}, sv{}, suu{}, svv{}, suv{};
  Interval su2{}, sv2{}, susv{};
  double size_s = 0.0, size_t = 0.0;  // the largest |S_s|, |S_t| over it
  struct Corner {
    IntervalVec point{}, es{}, et{};
  };
  std::array<Corner, 4> corners{};  // (cs, ct) at cs * 2 + ct, cs = 1 at s1
  int net = -1;                     // its net's offset in its owner's nets
  int child = -1;                   // the first of its four quarters, -1: none kept
};
}  // namespace bezier_detail

class BezierPatch {
 public:
  static constexpr int kMaxDegree = 7;
  // net[k * (q + 1) + l] is the control point b_kl, k along s; p, q in [1, kMaxDegree]. With
  // weights (w_kl > 0, as many as points) the patch is rational and net holds the homogeneous
  // points w_kl P_kl: S = A / W with A = Σ w_kl P_kl B_kl, W = Σ w_kl B_kl.
  BezierPatch(int p, int q, std::vector<Vec3> net, std::vector<double> weights = {});
  int degree_s() const { return p_; }
  int degree_t() const { return q_; }
  bool rational() const { return !weights_.empty(); }
  const std::vector<Vec3>& net() const { return net_; }            // the (homogeneous) points
  const std::vector<double>& weights() const { return weights_; }  // empty: polynomial
  Vec3 point(std::size_t i) const { return rational() ? (1.0 / weights_[i]) * net_[i] : net_[i]; }
  double magnitude() const { return magnitude_; }  // the largest |coordinate| of the net
  // Whether the edge s = 0 (edge 0), s = 1 (1), t = 0 (2) or t = 1 (3) is one point (a pole): its
  // control points' Euclidean points agree to a few units in the last place.
  bool pole(int edge) const { return poles_[static_cast<std::size_t>(edge)]; }
  double weight_magnitude() const { return weight_magnitude_; }
  // S and its derivatives to second order at (s, t), by the Bernstein basis and its derivatives
  // (a rational patch's by the quotient rule, [PieglTiller] algorithm A4.4).
  SurfaceJet jet(double s, double t) const;
  // The same by Horner's scheme in the power basis (the net converted once): faster, less
  // accurate (the conversion's rounding grows like 3^(p + q)); what Newton's iterations use.
  SurfaceJet power_jet(double s, double t) const;
  // A rational patch's homogeneous jet at (s, t): A, W and their derivatives (Bernstein sums).
  void homogeneous_jet(double s, double t, SurfaceJet& a, std::array<double, 6>& w) const;
  // The quarters of the first kCellLevels levels, kept: the branch and bound's first boxes.
  static constexpr int kCellLevels = 2;
  const std::vector<bezier_detail::Cell>& cells() const { return cells_; }
  const std::vector<Vec3>& cell_nets() const { return cell_nets_; }
  const std::vector<double>& cell_weights() const { return cell_weights_; }  // beside cell_nets
  std::size_t memory_bytes() const {
    return sizeof(*this) + (net_.capacity() + power_.capacity() + cell_nets_.capacity()) * sizeof(Vec3) +
           (weights_.capacity() + power_w_.capacity() + cell_weights_.capacity()) * sizeof(double) +
           cells_.capacity() * sizeof(bezier_detail::Cell);
  }

 private:
  int p_, q_;
  std::vector<Vec3> net_;
  std::vector<double> weights_;
  std::vector<Vec3> power_;                 // the coefficient of s^k t^l at k * (q + 1) + l
  std::vector<double> power_w_;             // the weights' (a rational patch)
  std::vector<bezier_detail::Cell> cells_;  // the root, then each level's quarters
  std::vector<Vec3> cell_nets_;
  std::vector<double> cell_weights_;
  double magnitude_ = 0.0, weight_magnitude_ = 0.0;
  std::array<bool, 4> poles_{};
};

// The Bernstein coefficients (degree 2p x 2q, at k * (2q + 1) + l) of the polynomial
// g_L = |A - p W|² - L W² of a rational patch (A, W as above; a polynomial patch: W = 1), whose
// sign is that of |S - p|² - L: the product of Bernstein forms ([FaroukiRajan] see the source).
std::vector<double> distance_level_net(const BezierPatch& patch, const Vec3& p, double L);

struct PatchNearest {
  bool proved = false;  // false: no claim; the fields below are meaningless
  // The foot is a pole of the patch (BezierPatch::pole): the lower bound is proved, the foot's
  // multiplicity is not (the distance is flat along the pole's edge in the parameters).
  bool pole = false;
  double s = 0.0, t = 0.0;
  SurfaceJet jet;            // at (s, t)
  double distance = 0.0;     // |S(s, t) - p|
  double lower_bound = 0.0;  // no point of the patch is nearer (rigorous)
  int boxes = 0;             // sub-patches bounded
  int iterations = 0;        // Newton's iterations, all starts
  int starts = 0;            // Newton's starts
  double step_norm = 0.0;    // the last Newton step
};

// The patch's nearest point to p, proved as above, within max_boxes sub-patches. With a finite
// cutoff, a sub-patch whose bound is beyond it is settled too: when the patch has no point within
// cutoff, the answer is the candidate found (a point of the patch, not necessarily its nearest)
// and lower_bound is above cutoff.
PatchNearest nearest_on_patch(const BezierPatch& patch, const Vec3& p, int max_boxes = 48,
                              double cutoff = std::numeric_limits<double>::infinity());

}  // namespace footpoint
