#include "implicit/solvers/implicit_surface_certificate.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "implicit/solvers/implicit_surface_lagrange.hpp"

namespace footpoint::surface_implicit {

namespace {

using formula::interval::add;
using formula::interval::mag;
using formula::interval::mul;
using formula::interval::sub;
namespace iv = formula::interval;

constexpr double kRound = 0x1p-50;  // a few units of rounding, relative

// The multiplier l of the foot x*: least squares of p - x* = l grad f over the coordinates not at
// a bound of the box (the face multipliers take the others). At a corner every l is a multiplier
// of the Lagrangian; the middle of those that give r = x* - p + l grad f the signs of the box's
// multipliers (r_k >= 0 at a lower bound, <= 0 at an upper one, so that r . (x - x*) >= 0 in the
// box), or 0 when none does.
double foot_multiplier(const ImplicitSurfaceJet& j, const Box3& box, Vec3 p, Vec3 x) {
  double num = 0.0, den = 0.0, lo = -std::numeric_limits<double>::infinity(), hi = -lo;
  for (int k = 0; k < 3; ++k) {
    const bool at_lo = x[k] == box.lo[k], at_hi = x[k] == box.hi[k];
    if (!at_lo && !at_hi) {
      num += j.grad[k] * (p[k] - x[k]);
      den += j.grad[k] * j.grad[k];
      continue;
    }
    // (x - p)_k + l g_k >= 0 (lower bound) or <= 0 (upper bound): a half-line of l.
    const double g = at_lo ? j.grad[k] : -j.grad[k], c = at_lo ? x[k] - p[k] : p[k] - x[k];
    if (g > 0.0)
      lo = std::max(lo, -c / g);
    else if (g < 0.0)
      hi = std::min(hi, -c / g);
    else if (c < 0.0)
      hi = lo - 1.0;  // no l helps
  }
  if (den > 0.0) return num / den;
  if (!(lo <= hi)) return 0.0;
  if (std::isfinite(lo) && std::isfinite(hi)) return 0.5 * (lo + hi);
  if (std::isfinite(lo)) return lo + 1.0 + std::fabs(lo);
  if (std::isfinite(hi)) return hi - 1.0 - std::fabs(hi);
  return 0.0;
}

// min over d in [a, b] (a <= 0 <= b) and s in [r.lo, r.hi] of s d + m / 2 d^2: at an end, or
// where the derivative vanishes when m > 0.
double separable_minimum(Interval r, double m, double a, double b) {
  double best = 0.0;  // d = 0
  for (const double s : {r.lo, r.hi}) {
    const double d = m > 0.0 ? std::clamp(-s / m, a, b) : a;
    for (const double t : {a, b, d}) best = std::min(best, s * t + 0.5 * m * t * t);
  }
  return best - kRound * (std::fabs(best) + std::max(std::fabs(a), std::fabs(b)) * mag(r));
}

// The eigenvectors of the symmetric 3 x 3 matrix a (columns of q), by cyclic Jacobi rotations
// (G. H. Golub, C. F. Van Loan, Matrix Computations, 4th ed., Sec. 8.5.2).
Mat3 eigenvectors(Mat3 a) {
  Mat3 q{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
  for (int sweep = 0; sweep < 12; ++sweep) {
    double off = 0.0;
    for (int i = 0; i < 3; ++i)
      for (int j = i + 1; j < 3; ++j) off += a[i][j] * a[i][j];
    if (!(off > 0.0)) break;
    for (int i = 0; i < 3; ++i)
      for (int j = i + 1; j < 3; ++j) {
        if (a[i][j] == 0.0) continue;
        const double theta = (a[j][j] - a[i][i]) / (2.0 * a[i][j]);
        const double t = std::copysign(1.0, theta) / (std::fabs(theta) + std::sqrt(theta * theta + 1.0));
        const double c = 1.0 / std::sqrt(t * t + 1.0), s = t * c;
        for (int k = 0; k < 3; ++k) {  // a <- a G (columns i, j)
          const double ki = a[k][i], kj = a[k][j];
          a[k][i] = c * ki - s * kj;
          a[k][j] = s * ki + c * kj;
        }
        for (int k = 0; k < 3; ++k) {  // a <- G^T a (rows i, j)
          const double ik = a[i][k], jk = a[j][k];
          a[i][k] = c * ik - s * jk;
          a[j][k] = s * ik + c * jk;
        }
        for (int k = 0; k < 3; ++k) {  // q <- q G
          const double ki = q[k][i], kj = q[k][j];
          q[k][i] = c * ki - s * kj;
          q[k][j] = s * ki + c * kj;
        }
      }
  }
  return q;
}

// A lower bound m of the eigenvalues of every symmetric matrix in the interval matrix a: with q
// the midpoint's eigenvectors, Gershgorin's discs of the enclosure of q^T a q bound those of
// q^T A q from below by m'; q^T A q and A have the same eigenvalues up to the departure of q
// from orthogonality, which m' / (1 + e), e >= ||q^T q - I||_2 (bounded by the sum of the
// entries' magnitudes), covers: d^T A d = h^T (q^T A q) h >= m' |h|^2 >= m' |d|^2 / (1 + e) for
// d = q h. -inf when the bound is not positive.
double eigenvalue_lower_bound(const IMat3& a) {
  Mat3 mid;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) mid[i][j] = iv::mid(a[i][j]);
  const Mat3 q = eigenvectors(mid);
  // n = q^T a q, enclosed.
  IMat3 aq;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      Interval sum = iv::point(0.0);
      for (int k = 0; k < 3; ++k) sum = add(sum, mul(q[k][j], a[i][k]));
      aq[i][j] = sum;
    }
  double m = std::numeric_limits<double>::infinity(), e = 0.0;
  for (int i = 0; i < 3; ++i) {
    Interval row[3];
    for (int j = 0; j < 3; ++j) {
      Interval sum = iv::point(0.0);
      for (int k = 0; k < 3; ++k) sum = add(sum, mul(q[k][i], aq[k][j]));
      row[j] = sum;
      double qq = 0.0;
      for (int k = 0; k < 3; ++k) qq += q[k][i] * q[k][j];
      e += std::fabs(qq - (i == j ? 1.0 : 0.0)) + 8.0 * kRound;
    }
    double off = 0.0;
    for (int j = 0; j < 3; ++j)
      if (j != i) off += mag(row[j]);
    m = std::min(m, row[i].lo - off * (1.0 + kRound));
  }
  if (!(m > 0.0) || !(e < 0.5)) return -std::numeric_limits<double>::infinity();
  return m / (1.0 + e) * (1.0 - kRound);
}

// A lower bound of |p - x|^2 / 2 over the points x of S in k (a box around x* within the box),
// or -inf where the Lagrangian is not shown convex there. The augmented Lagrangian
// L(x) = |p - x|^2 / 2 + l f(x) + c/2 f(x)^2 (c >= 0; [NW06] Sec. 17.3) is |p - x|^2 / 2 on S as
// well; its Hessian I + l H + c (grad f grad f^T + f H) adds c |grad f|^2 along the normal, where
// I + l H alone is indefinite when p lies inside a tube of the surface near its core (a torus),
// while its form on the tangent plane is the distance's.
// The better of the bounds with the weights c in `weights` (negative: not tried).
double convex_bound(const ImplicitSurfaceEquation& equation, const Box3& k, Vec3 p, Vec3 x, double l,
                    std::array<double, 2> weights) {
  const ImplicitSurfaceIntervalJet over = equation.interval_jet(k);
  if (!over.smooth) return -std::numeric_limits<double>::infinity();
  const ImplicitSurfaceIntervalJet at = equation.interval_gradient({x, x});
  if (!at.lipschitz) return -std::numeric_limits<double>::infinity();
  double best = -std::numeric_limits<double>::infinity();
  for (const double c : weights) {
    if (c < 0.0) continue;
    IMat3 lagrangian;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        lagrangian[i][j] = add(iv::point(i == j ? 1.0 : 0.0), mul(l, over.hess[i][j]));
        if (c > 0.0) {
          const Interval gg = i == j ? iv::sqr(over.grad[i]) : mul(over.grad[i], over.grad[j]);
          lagrangian[i][j] = add(lagrangian[i][j], mul(c, add(gg, mul(over.f, over.hess[i][j]))));
        }
      }
    const double m = eigenvalue_lower_bound(lagrangian);
    if (!(m > 0.0)) continue;
    // L(x*) = |p - x*|^2 / 2 + l f(x*) + c/2 f(x*)^2, r = x* - p + (l + c f(x*)) grad f(x*), enclosed.
    const Interval multiplier = add(iv::point(l), mul(c, at.f));
    Interval value = add(mul(l, at.f), mul(0.5 * c, iv::sqr(at.f)));
    for (int i = 0; i < 3; ++i) {
      const Interval gap = sub(iv::point(x[i]), iv::point(p[i]));
      value = add(value, mul(0.5, iv::sqr(gap)));
    }
    double bound = value.lo;
    for (int i = 0; i < 3; ++i) {
      const Interval r = add(sub(iv::point(x[i]), iv::point(p[i])), mul(multiplier, at.grad[i]));
      bound += separable_minimum(r, m, k.lo[i] - x[i], k.hi[i] - x[i]);
    }
    best = std::max(best, bound - kRound * std::fabs(bound));
  }
  return best;
}

// The weights c of the augmented Lagrangian worth trying about the foot: 0 (the plain Lagrangian)
// unless I + l H is indefinite there, where no box about it can be shown convex; and, where the
// least eigenvalue of I + l H is below half the tangent form's, the least of |grad f|^-2 times 1/4,
// 1, 4, 16, 64 that lifts it there (the tangent form's, approached as c grows, bounds it above).
// -1 for a weight not to try.
std::array<double, 2> augmentations(const ImplicitSurfaceJet& j, double l) {
  const double g2 = norm2(j.grad);
  if (!(g2 > 0.0)) return {0.0, -1.0};
  const Mat3 a = lagrangian_hessian(j, l);
  const double tangent = tangent_form(a, j.grad / std::sqrt(g2)).least_eigenvalue();
  // Whether the least eigenvalue of a + c grad f grad f^T exceeds `floor`: Sylvester's criterion,
  // the leading principal minors of a + c grad f grad f^T - floor I positive.
  auto above = [&](double c, double floor) {
    Mat3 b = a;
    for (int r = 0; r < 3; ++r)
      for (int q = 0; q < 3; ++q) b[r][q] += c * j.grad[r] * j.grad[q] - (r == q ? floor : 0.0);
    const double m2 = b[0][0] * b[1][1] - b[0][1] * b[1][0];
    const double m3 = b[0][0] * (b[1][1] * b[2][2] - b[1][2] * b[2][1]) -
                      b[0][1] * (b[1][0] * b[2][2] - b[1][2] * b[2][0]) +
                      b[0][2] * (b[1][0] * b[2][1] - b[1][1] * b[2][0]);
    return b[0][0] > 0.0 && m2 > 0.0 && m3 > 0.0;
  };
  std::array<double, 2> out{above(0.0, 0.0) ? 0.0 : -1.0, -1.0};
  if (!(tangent > 0.0) || above(0.0, 0.5 * tangent)) return out;
  for (double scale = 0.25; scale <= 64.0; scale *= 4.0)
    if (above(scale / g2, 0.5 * tangent)) {
      out[1] = scale / g2;
      break;
    }
  return out;
}

// The samples of the leaves under the cells `roots` whose box comes within `reach` of p (squared,
// rounded outwards) and that `keep(cell)` keeps; a cell `skip(cell)` names is not descended.
template <class Skip, class Keep>
void samples_within(const ImplicitSurfaceCells& cells, std::vector<std::int32_t> roots, Vec3 p, double reach,
                    Skip&& skip, Keep&& keep, std::vector<std::int32_t>& out) {
  const double reach2 = square_upper_bound(reach);
  while (!roots.empty()) {
    const ImplicitSurfaceCell& cell = cells.cells[static_cast<std::size_t>(roots.back())];
    roots.pop_back();
    if (distance2_lower_bound(p, cell.box) > reach2 || skip(cell)) continue;
    if (cell.first_child >= 0) {
      for (std::int32_t i = 0; i < cell.children; ++i) roots.push_back(cell.first_child + i);
    } else if (cell.sample >= 0 && keep(cell)) {
      out.push_back(cell.sample);
    }
  }
}

double lower_sqrt(double twice_half_square) {
  return twice_half_square > 0.0 ? std::sqrt(twice_half_square) * (1.0 - kRound) : 0.0;
}

}  // namespace

SurfaceCertificate certify_surface_answer(const ImplicitSurfaceEquation& equation,
                                          const ImplicitSurfaceCells& cells, Vec3 p, Vec3 foot,
                                          double distance, int budget) {
  SurfaceCertificate out;
  Certificate& c = out.certificate;
  c.computed = true;
  c.absolute_gap = Certificate::absolute_gap_at(p, foot);
  const double gap = std::fmax(Certificate::kRelativeGap * distance, c.absolute_gap);
  const double threshold = distance - 0.5 * gap;
  double lower = distance;
  const Box3& box = cells.box;
  if (cells.empty()) {
    c.lower_bound = distance;
    c.certified = true;
    c.reason = CertificateReason::gap_met;
    return out;
  }

  // K: the largest box around the foot (the whole box's extent, halved up to 14 times) on which
  // the Lagrangian is shown convex with a bound within half the gap.
  const ImplicitSurfaceJet j = equation.jet(foot);
  const double l = foot_multiplier(j, box, p, foot);
  const std::array<double, 2> weights = augmentations(j, l);
  const double augment = std::max(weights[1], 0.0);
  Box3 k{foot, foot};
  bool have_k = false;
  for (double w = box.max_edge(); w >= box.max_edge() * 0x1p-14; w *= 0.5) {
    const Box3 trial = intersection(box, {foot - Vec3{w, w, w}, foot + Vec3{w, w, w}});
    const double half_square = convex_bound(equation, trial, p, foot, l, weights);
    const double bound = lower_sqrt(2.0 * half_square);
    if (half_square > -std::numeric_limits<double>::infinity() && bound >= threshold) {
      k = trial;
      have_k = true;
      lower = std::min(lower, bound);
      break;
    }
  }

  // Branch and bound over the tree, then over pieces of the leaves.
  struct Piece {
    Box3 box;
    int depth;          // 0: a whole leaf
    std::int32_t leaf;  // the leaf it lies in: its index in the cells' enclosure cache
    Box3 leaf_box;
    std::int32_t sample;  // the leaf's sample (-1: none)
  };
  std::vector<std::int32_t> stack{0};
  std::vector<Piece> pieces;
  // The tie's reach (SurfaceCertificate::tie_starts): the cells settled by their distance alone
  // that come within it, to be descended for their leaves' samples once certified.
  const double reach = distance + gap;
  std::vector<std::int32_t> shell;
  // The samples of the leaves bounded piece by piece one of whose pieces outside K may hold a point
  // within reach: its bound (by distance or by the Lagrangian) at most reach, or not settled. A
  // leaf without a sample (Newton from its centre left the box or the leaf: a foot on a face of
  // the box) gives the sample nearest to its centre.
  std::vector<std::int32_t> within_reach;
  std::int32_t last_leaf = -1;  // a leaf's pieces are consecutive
  auto may_tie = [&](const Piece& piece, double bound) {
    if (piece.leaf == last_leaf || !(bound <= reach) || (have_k && k.contains(piece.box))) return;
    last_leaf = piece.leaf;
    double d2 = 0.0;
    const std::int32_t sample = piece.sample >= 0 || !cells.sample_index
                                    ? piece.sample
                                    : cells.sample_index->nearest(piece.leaf_box.center(), d2);
    if (sample >= 0) within_reach.push_back(sample);
  };
  // Settled by its distance: nothing in b is nearer than the threshold; or b lies in K.
  auto near_settled = [&](const Box3& b, double& bound) {
    bound = distance_lower_bound(p, b);
    if (bound >= threshold) {
      lower = std::min(lower, bound);
      return true;
    }
    return have_k && k.contains(b);
  };
  // Settled by the Lagrangian: g(x) = |p - x|^2 / 2 + l f(x) is |p - x|^2 / 2 on S, and its
  // enclosure over b (the natural one and the mean value form about b's centre, intersected) is
  // at least the threshold's half square; or f's enclosure excludes 0 (b holds no point of S).
  // Second order, where the first does not settle b: Taylor's theorem about the centre c with the
  // Hessian I + l H(b) enclosed over b, g(c + d) >= g(c) + grad g(c) . d + d^T Q d / 2, bounded below
  // by the separable diagonal part less the off-diagonal entries at b's half-widths.
  // With the augmented Lagrangian's weight (convex_bound) as well, g + c/2 f^2, whose Hessian adds
  // c (grad f grad f^T + f H): the better of the two bounds.
  // The enclosures over b are those over the leaf b lies in (`leaf`; wider than b's own, but
  // holding over b), unless the formula is not smooth over the whole leaf; those at b's centre are
  // the leaf's when b is the whole leaf (`whole`).
  auto second_order_bound = [&](const Box3& b, const LeafEnclosures& leaf, bool whole) {
    const ImplicitSurfaceIntervalJet over = leaf.over.smooth ? leaf.over : equation.interval_jet(b);
    if (!over.smooth) return 0.0;
    const Vec3 centre = b.center();
    ImplicitSurfaceIntervalJet at;
    if (whole) {
      at.f = leaf.centre_f;
      at.grad = leaf.centre_grad;
    } else {
      at = equation.interval_gradient({centre, centre});
    }
    // The bound with multiplier `lm` and weight `weight`.
    auto bound_with = [&](double lm, double weight) {
      Interval value = add(mul(lm, at.f), mul(0.5 * weight, iv::sqr(at.f)));
      const Interval multiplier = add(iv::point(lm), mul(weight, at.f));
      double cross_terms = 0.0, linear = 0.0;
      for (int i = 0; i < 3; ++i) {
        const Interval to_p = sub(iv::point(centre[i]), iv::point(p[i]));
        value = add(value, mul(0.5, iv::sqr(to_p)));
        const Interval slope = add(to_p, mul(multiplier, at.grad[i]));
        Interval diagonal = add(iv::point(1.0), mul(lm, over.hess[i][i]));
        if (weight > 0.0)
          diagonal = add(diagonal, mul(weight, add(iv::sqr(over.grad[i]), mul(over.f, over.hess[i][i]))));
        const double half = 0.5 * (b.hi[i] - b.lo[i]) * (1.0 + kRound);
        linear += separable_minimum(slope, diagonal.lo, b.lo[i] - centre[i], b.hi[i] - centre[i]);
        for (int c = 0; c < 3; ++c) {
          if (c == i) continue;
          Interval entry = mul(lm, over.hess[i][c]);
          if (weight > 0.0)
            entry =
                add(entry, mul(weight, add(mul(over.grad[i], over.grad[c]), mul(over.f, over.hess[i][c]))));
          cross_terms += 0.5 * mag(entry) * half * (0.5 * (b.hi[c] - b.lo[c]));
        }
      }
      const double half_square = value.lo + linear - cross_terms * (1.0 + kRound);
      return half_square - kRound * std::fabs(half_square);
    };
    double best = bound_with(l, 0.0);
    if (augment > 0.0) best = std::max(best, bound_with(l, augment));
    // Every multiplier gives a bound (the Lagrangian is |p - x|^2 / 2 on S for any): where the
    // foot's fails, the least-squares one of p - c = l grad f(c) at b's centre c.
    const Vec3 g{iv::mid(at.grad[0]), iv::mid(at.grad[1]), iv::mid(at.grad[2])};
    if (lower_sqrt(2.0 * best) < threshold && norm2(g) > 0.0) {
      const double own = dot(p - centre, g) / norm2(g);
      if (std::isfinite(own)) best = std::max(best, bound_with(own, 0.0));
    }
    return best;
  };
  auto lagrangian_settled = [&](const Box3& b, const LeafEnclosures& leaf, bool whole, double& bound) {
    const Vec3 centre = b.center();
    ImplicitSurfaceIntervalJet jb;
    Interval fc;
    if (whole) {
      jb = leaf.over;
      fc = leaf.centre_value;
    } else if (leaf.over.lipschitz) {
      // A part of a leaf: the leaf's gradient enclosure holds over it, and f over it is enclosed
      // by the mean value form about its centre, f(c) + grad f(leaf) . (b - c) (R. E. Moore,
      // R. B. Kearfott, M. J. Cloud, Introduction to Interval Analysis, SIAM 2009, Sec. 6.4).
      fc = equation.value_enclosure({centre, centre});
      jb.grad = leaf.over.grad;
      jb.f = fc;
      for (int i = 0; i < 3; ++i)
        jb.f = add(jb.f, mul(jb.grad[i], sub(Interval{b.lo[i], b.hi[i]}, iv::point(centre[i]))));
    } else {
      jb = equation.interval_gradient(b);
      fc = equation.value_enclosure({centre, centre});
    }
    if (jb.f.excludes_zero()) {
      bound = std::numeric_limits<double>::infinity();  // no point of S in b
      return true;
    }
    if (!jb.lipschitz) return false;
    Interval mean = mul(l, fc), natural = mul(l, jb.f);
    for (int i = 0; i < 3; ++i) {
      const Interval side{b.lo[i], b.hi[i]};
      const Interval to_p = sub(side, iv::point(p[i]));
      natural = add(natural, mul(0.5, iv::sqr(to_p)));
      const Interval gap_c = sub(iv::point(centre[i]), iv::point(p[i]));
      mean = add(mean, mul(0.5, iv::sqr(gap_c)));
      const Interval slope = add(to_p, mul(l, jb.grad[i]));
      mean = add(mean, mul(slope, sub(side, iv::point(centre[i]))));
    }
    double half_square = std::max(natural.lo, mean.lo) * (1.0 - kRound);
    if (lower_sqrt(2.0 * half_square) < threshold)
      half_square = std::max(half_square, second_order_bound(b, leaf, whole));
    const double b2 = lower_sqrt(2.0 * half_square);
    if (b2 < threshold) return false;
    bound = b2;
    lower = std::min(lower, bound);
    return true;
  };
  while (!stack.empty()) {
    const std::int32_t index = stack.back();
    const ImplicitSurfaceCell& cell = cells.cells[static_cast<std::size_t>(index)];
    stack.pop_back();
    double bound = 0.0;
    if (near_settled(cell.box, bound)) {
      if (bound >= threshold && bound <= reach && !(have_k && k.contains(cell.box))) shell.push_back(index);
      continue;
    }
    if (cell.first_child >= 0) {
      for (std::int32_t i = 0; i < cell.children; ++i) stack.push_back(cell.first_child + i);
      continue;
    }
    if (cell.sample >= 0) {
      const Vec3 s = cells.samples[static_cast<std::size_t>(cell.sample)];
      if (norm(p - s) < distance - gap) out.nearer.push_back(s);
      if (!(have_k && k.contains(cell.box)) && norm(p - s) <= distance + cells.leaf_diagonal)
        out.rivals.push_back(s);
    }
    pieces.push_back({cell.box, 0, cell.leaf, cell.box, cell.sample});
  }
  // Pieces of the leaves, depth first, up to 16 levels below the leaves and the box budget.
  while (!pieces.empty()) {
    const Piece piece = pieces.back();
    pieces.pop_back();
    double bound = 0.0;
    if (near_settled(piece.box, bound)) {
      may_tie(piece, bound);
      continue;
    }
    if (c.boxes >= budget || piece.depth >= 16) {
      lower = std::min(lower, bound);
      may_tie(piece, bound);
      continue;
    }
    ++c.boxes;
    const LeafEnclosures leaf = cells.leaf_enclosures.get(equation, piece.leaf, piece.leaf_box);
    if (lagrangian_settled(piece.box, leaf, piece.depth == 0, bound)) {
      may_tie(piece, bound);
      continue;
    }
    // Halved along the edges at least half its longest (a flat leaf of a flat box is not made
    // flatter), whole along the others: the parts cover b.
    const Box3& b = piece.box;
    const double longest = b.max_edge();
    int axes = 0;
    for (int k = 0; k < 3; ++k)
      if (b.hi[k] - b.lo[k] >= 0.5 * longest) axes |= 1 << k;
    for (int octant = 0; octant < 8; ++octant) {
      if ((octant & ~axes) != 0) continue;
      const Box3 half = octant_of(b, octant);
      Box3 part = b;
      for (int k = 0; k < 3; ++k)
        if ((axes >> k) & 1) {
          part.lo[k] = half.lo[k];
          part.hi[k] = half.hi[k];
        }
      pieces.push_back({part, piece.depth + 1, piece.leaf, piece.leaf_box, piece.sample});
    }
  }
  c.lower_bound = std::min(lower, distance);
  c.certified = Certificate::meets_gap(distance, c.lower_bound, c.absolute_gap);
  if (c.certified) {
    // The leaves that may hold a point within reach outside K: those bounded piece by piece that
    // may, and those under the shell (settled by distance, at most reach) not in K.
    const auto in_k = [&](const ImplicitSurfaceCell& cell) { return have_k && k.contains(cell.box); };
    std::vector<std::int32_t> may = std::move(within_reach);
    samples_within(
        cells, std::move(shell), p, reach, in_k, [](const ImplicitSurfaceCell&) { return true; }, may);
    std::sort(may.begin(), may.end());
    may.erase(std::unique(may.begin(), may.end()), may.end());
    const double apart = 2.0 * cells.leaf_diagonal;
    for (const std::int32_t i : may)
      if (norm(cells.samples[static_cast<std::size_t>(i)] - foot) > apart) out.tie_starts.push_back(i);
    if (!out.tie_starts.empty()) {
      // those and the samples of the leaves in K that meet the ball
      out.tie_samples = std::move(may);
      samples_within(
          cells, {0}, p, reach, [](const ImplicitSurfaceCell&) { return false; }, in_k, out.tie_samples);
      std::sort(out.tie_samples.begin(), out.tie_samples.end());
      out.tie_samples.erase(std::unique(out.tie_samples.begin(), out.tie_samples.end()),
                            out.tie_samples.end());
    }
  }
  c.reason = c.certified           ? CertificateReason::gap_met
             : !out.nearer.empty() ? CertificateReason::nearer_point
                                   : CertificateReason::budget_exhausted;
  return out;
}

}  // namespace footpoint::surface_implicit
