// Krawczyk's test for the zeros of a smooth map G: R^N -> R^N in a box X ([Krawczyk], [Moore77];
// [Neumaier] Section 5.1): with m a point of X, J an interval matrix holding G'(ξ) for every ξ in
// X (each row the gradient enclosure of one component over X), and Y any real matrix (here the
// inverse of J's midpoint),
//   K(X) = m - Y G(m) + (I - Y J)(X - m).
// By the mean value theorem row by row, every zero x of G in X satisfies
// x = m - Y G(m) + (I - Y J~)(x - m) for a J~ in J, so
//   - every zero of G in X lies in K(X): K(X) ∩ X = ∅ proves there is none;
//   - K(X) ⊆ X proves that X holds a zero (Brouwer's fixed-point theorem applied to
//     x -> x - Y G(x), which maps X into K(X)); with ‖I - Y J‖ < 1, which makes Y and every matrix
//     of J nonsingular, it is the only one ([Moore77]; [Neumaier] Section 5.1). K(X) ⊂ int X
//     implies that contraction by itself ([Neumaier] Section 5.1); the weaker K(X) ⊆ X matters
//     where X is a few ulps wide along a coordinate that G fixes exactly;
//   - with c >= ‖I - Y J‖∞, c < 1, every zero x of G in X has ‖x - m‖∞ <= ‖Y G(m)‖∞ / (1 - c):
//     the tight enclosure of a zero next to a good approximation m, from one evaluation over a
//     large X (which proves its uniqueness there) and one at m.
// Every product and sum is rounded outwards (midpoint-radius, geometry/midpoint_radius.hpp), so
// K(X), c and the radius enclose their exact values.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "formula/interval.hpp"
#include "geometry/dense_solve.hpp"
#include "geometry/midpoint_radius.hpp"

namespace footpoint {

template <int N>
using IntervalVector = std::array<formula::Interval, N>;
template <int N>
using IntervalMatrix = std::array<std::array<formula::Interval, N>, N>;  // rows

enum class KrawczykVerdict {
  unique_zero,  // K(X) ⊂ int X, or K(X) ⊆ X with ‖I - Y J‖ < 1: exactly one zero in X
  no_zero,      // K(X) ∩ X = ∅: none
  undecided,    // neither (X too large for the contraction, or a zero near its boundary)
};

template <int N>
struct KrawczykResult {
  KrawczykVerdict verdict = KrawczykVerdict::undecided;
  IntervalVector<N> image{};  // K(X)
  // An upper bound of ‖I - Y J‖∞ (infinity when Y could not be formed).
  double contraction = std::numeric_limits<double>::infinity();
  // When contraction < 1: every zero of G in X is within this ∞-distance of m.
  double radius = std::numeric_limits<double>::infinity();
};

// An approximate inverse of a small matrix: by the adjugate for N <= 3, else column by column.
template <int N>
bool approximate_inverse(const Matrix<N>& c, Matrix<N>& y) {
  if constexpr (N == 1) {
    y[0][0] = 1.0 / c[0][0];
    return std::isfinite(y[0][0]);
  } else if constexpr (N == 2) {
    const double det = c[0][0] * c[1][1] - c[0][1] * c[1][0];
    y = {{{c[1][1] / det, -c[0][1] / det}, {-c[1][0] / det, c[0][0] / det}}};
  } else if constexpr (N == 3) {
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        const int i1 = (i + 1) % 3, i2 = (i + 2) % 3, j1 = (j + 1) % 3, j2 = (j + 2) % 3;
        y[j][i] = c[i1][j1] * c[i2][j2] - c[i1][j2] * c[i2][j1];  // cofactor (i, j), transposed
      }
    const double inverse_det = 1.0 / (c[0][0] * y[0][0] + c[0][1] * y[1][0] + c[0][2] * y[2][0]);
    for (auto& row : y)
      for (double& v : row) v *= inverse_det;
  } else {
    for (int j = 0; j < N; ++j) {
      Vector<N> e{};
      e[j] = 1.0;
      if (!dense_solve<N>(c, e)) return false;
      for (int i = 0; i < N; ++i) y[i][j] = e[i];
    }
    return true;
  }
  for (const auto& row : y)
    for (double v : row)
      if (!std::isfinite(v)) return false;
  return true;
}

// x: the box X; m: a point of X; gm: an enclosure of G(m); jac: enclosures over X of the rows of G'.
template <int N>
KrawczykResult<N> krawczyk(const IntervalVector<N>& x, const Vector<N>& m, const IntervalVector<N>& gm,
                           const IntervalMatrix<N>& jac) {
  using namespace formula;
  using namespace formula::interval;
  KrawczykResult<N> r;
  // Y = mid(J)^-1 (an approximate inverse: only its use below is rigorous).
  Matrix<N> c{};
  for (int i = 0; i < N; ++i)
    for (int j = 0; j < N; ++j) c[i][j] = mid(jac[i][j]);
  Matrix<N> y{};
  if (!approximate_inverse<N>(c, y)) return r;
  // Y G(m), I - Y J and K(X) in midpoint-radius form, each a centre and one radius with the
  // rounding allowance of geometry/midpoint_radius.hpp.
  static_assert(N >= 1 && N <= 6, "the rounding allowances count at most 15 terms");
  constexpr double kU = midrad::kU;
  const auto radius = midrad::radius;
  using midrad::Ball;
  std::array<Ball, N> g{}, dx{};
  std::array<std::array<Ball, N>, N> jb{};
  for (int l = 0; l < N; ++l) {
    g[l] = midrad::of(gm[l]);
    dx[l] = midrad::of(sub(x[l], point(m[l])));
    for (int j = 0; j < N; ++j) jb[l][j] = midrad::of(jac[l][j]);
  }
  // Y G(m).
  std::array<Ball, N> yg{};
  for (int i = 0; i < N; ++i) {
    double c = 0.0, s = 0.0, rr = 0.0;
    bool terms = false;
    for (int l = 0; l < N; ++l) {
      c += y[i][l] * g[l].c;
      s += std::abs(y[i][l] * g[l].c);
      rr += std::abs(y[i][l]) * g[l].r;
      terms = terms || (y[i][l] != 0.0 && g[l].nonzero());
    }
    yg[i] = {c, radius(rr, s, terms)};
  }
  // I - Y J.
  std::array<std::array<Ball, N>, N> mb{};
  for (int i = 0; i < N; ++i)
    for (int j = 0; j < N; ++j) {
      double c = i == j ? 1.0 : 0.0, s = std::abs(c), rr = 0.0;
      bool terms = false;
      for (int l = 0; l < N; ++l) {
        c -= y[i][l] * jb[l][j].c;
        s += std::abs(y[i][l] * jb[l][j].c);
        rr += std::abs(y[i][l]) * jb[l][j].r;
        terms = terms || (y[i][l] != 0.0 && jb[l][j].nonzero());
      }
      mb[i][j] = {c, radius(rr, s, terms)};
    }
  double contraction = 0.0, step = 0.0;
  bool interior = true, inside = true, disjoint = false, finite = true;
  for (int i = 0; i < N; ++i) {
    // K_i = m_i + r_i, r_i = Σ_j (I - Y J)_ij (X_j - m_j) - (Y G(m))_i: r_i as above, then
    // c = fl(m_i + r_i), whose rounding u |c| joins the radius (two roundings more, covered by
    // the factor), and [c - rad, c + rad] with each end one rounding: one step outwards. Where
    // every term of r_i is an exact 0, c = m_i exactly and K_i is that point.
    double rest = -yg[i].c, s = std::abs(yg[i].c), rr = yg[i].r, row = 0.0;
    bool terms = yg[i].nonzero();
    for (int j = 0; j < N; ++j) {
      rest += mb[i][j].c * dx[j].c;
      s += std::abs(mb[i][j].c * dx[j].c);
      rr += std::abs(mb[i][j].c) * dx[j].r + mb[i][j].r * (std::abs(dx[j].c) + dx[j].r);
      row += std::abs(mb[i][j].c) + mb[i][j].r;
      terms = terms || (mb[i][j].nonzero() && dx[j].nonzero());
    }
    row = radius(row, 0.0, true);  // 2N - 1 roundings of a sum of non-negative terms
    const double c = m[i] + rest;
    const double rad = (radius(rr, s, terms) + kU * std::abs(c)) * (1.0 + 4.0 * kU);
    const Interval k = terms ? Interval{next_down(c - rad), next_up(c + rad)} : point(m[i]);
    finite = finite && std::isfinite(k.lo) && std::isfinite(k.hi) && std::isfinite(row);
    if (!(row <= contraction)) contraction = row;
    const double step_i = radius(std::abs(yg[i].c) + yg[i].r, 0.0, true);
    if (!(step_i <= step)) step = step_i;  // NaN propagates: no radius
    r.image[i] = k;
    if (k.hi < x[i].lo || k.lo > x[i].hi) disjoint = true;
    if (!(k.lo > x[i].lo && k.hi < x[i].hi)) interior = false;
    if (!(k.lo >= x[i].lo && k.hi <= x[i].hi)) inside = false;
  }
  // Infinite or NaN parts (an unbounded enclosure, an overflow) decide nothing.
  if (!finite || !std::isfinite(step)) {
    r.image = x;
    return r;
  }
  r.contraction = contraction;
  if (contraction < 1.0) r.radius = next_up(step / next_down(1.0 - contraction));
  r.verdict = disjoint                                    ? KrawczykVerdict::no_zero
              : interior || (inside && contraction < 1.0) ? KrawczykVerdict::unique_zero
                                                          : KrawczykVerdict::undecided;
  return r;
}

}  // namespace footpoint
