#include "parametric/geometry/nurbs_patches.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "formula/expression_builder.hpp"

namespace footpoint::nurbs {

namespace {

using Homogeneous = std::array<double, 4>;
using formula::ExpressionBuilder;
using Node = ExpressionBuilder::Node;

// The blossom of the degree-p B-spline with control points d[0..p] (P_{i-p..i}) on span i of the
// knots U at the arguments x[0..p-1]: de Boor's triangle with level r at x[r - 1].
Homogeneous blossom(std::vector<Homogeneous> d, int i, int p, const std::vector<double>& U,
                    const std::vector<double>& x) {
  for (int r = 1; r <= p; ++r)
    for (int j = p; j >= r; --j) {
      const double lo = U[static_cast<std::size_t>(i - p + j)];
      const double hi = U[static_cast<std::size_t>(i + j + 1 - r)];
      const double alpha = (x[static_cast<std::size_t>(r - 1)] - lo) / (hi - lo);
      auto& dj = d[static_cast<std::size_t>(j)];
      const auto& dl = d[static_cast<std::size_t>(j - 1)];
      for (int c = 0; c < 4; ++c) dj[c] = (1.0 - alpha) * dl[c] + alpha * dj[c];
    }
  return d[static_cast<std::size_t>(p)];
}

// The Bézier points b_0..b_p of span i = [U_i, U_{i+1}] of the curve with control points d[0..p].
std::vector<Homogeneous> bezier_points(const std::vector<Homogeneous>& d, int i, int p,
                                       const std::vector<double>& U) {
  const double a = U[static_cast<std::size_t>(i)], b = U[static_cast<std::size_t>(i + 1)];
  std::vector<Homogeneous> out;
  for (int k = 0; k <= p; ++k) {
    std::vector<double> x(static_cast<std::size_t>(p), a);
    std::fill(x.end() - k, x.end(), b);
    out.push_back(blossom(d, i, p, U, x));
  }
  return out;
}

// The non-empty spans i (U_i < U_{i+1}) of a knot vector for n control points of degree p.
std::vector<int> spans(int n, int p, const std::vector<double>& U) {
  std::vector<int> out;
  for (int i = p; i < n; ++i)
    if (U[static_cast<std::size_t>(i)] < U[static_cast<std::size_t>(i + 1)]) out.push_back(i);
  return out;
}

double binomial(int n, int k) {
  double b = 1.0;
  for (int i = 1; i <= k; ++i) b = b * (n - k + i) / i;
  return b;
}

// The power-basis coefficients a_0..a_p of Σ_k b_k B_k^p(s): a_j = binom(p, j) Σ_{k<=j} binom(j, k)
// (-1)^(j-k) b_k, homogeneous coordinates alike.
std::vector<Homogeneous> power_coefficients(const std::vector<Homogeneous>& b, int p) {
  std::vector<Homogeneous> a(static_cast<std::size_t>(p + 1), Homogeneous{});
  for (int j = 0; j <= p; ++j)
    for (int k = 0; k <= j; ++k) {
      const double f = binomial(p, j) * binomial(j, k) * ((j - k) % 2 ? -1.0 : 1.0);
      for (int c = 0; c < 4; ++c) a[static_cast<std::size_t>(j)][c] += f * b[static_cast<std::size_t>(k)][c];
    }
  return a;
}

// x, y[, z] of Σ_m a_m monomial_m, divided by Σ_m a_m[3] monomial_m when rational.
std::vector<Node> rational_sum(ExpressionBuilder& e, const std::vector<Homogeneous>& a,
                               const std::vector<Node>& monomials, int dimension, bool rational) {
  auto sum = [&](int c) {
    Node out = e.constant(0.0);
    for (std::size_t m = 0; m < a.size(); ++m) out = e.add(out, e.mul(e.constant(a[m][c]), monomials[m]));
    return out;
  };
  std::vector<Node> out;
  const Node w = rational ? sum(3) : e.constant(1.0);
  for (int c = 0; c < dimension; ++c) out.push_back(rational ? e.div(sum(c), w) : sum(c));
  return out;
}

// The box of the Euclidean control points b / w, widened to hold the exact piece (see the header).
Box3 hull_of(const std::vector<Homogeneous>& b) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  Box3 box{{kInf, kInf, kInf}, {-kInf, -kInf, -kInf}};
  double magnitude = 0.0;
  for (const auto& h : b) {
    const Vec3 x{h[0] / h[3], h[1] / h[3], h[2] / h[3]};
    box.lo = min(box.lo, x);
    box.hi = max(box.hi, x);
    magnitude = std::max({magnitude, std::abs(x.x), std::abs(x.y), std::abs(x.z)});
  }
  const double widen = 0x1p-40 * magnitude + std::numeric_limits<double>::min();
  box.lo = box.lo - Vec3{widen, widen, widen};
  box.hi = box.hi + Vec3{widen, widen, widen};
  return box;
}

}  // namespace

std::vector<CurvePiece> bezier_pieces(const Curve& curve, std::size_t max_nodes) {
  const int p = curve.degree, n = static_cast<int>(curve.weighted.size());
  std::vector<CurvePiece> out;
  for (const int i : spans(n, p, curve.knots)) {
    const std::vector<Homogeneous> d(curve.weighted.begin() + (i - p), curve.weighted.begin() + i + 1);
    const std::vector<Homogeneous> b = bezier_points(d, i, p, curve.knots);
    const double a = curve.knots[static_cast<std::size_t>(i)],
                 c = curve.knots[static_cast<std::size_t>(i + 1)];
    ExpressionBuilder e(1, max_nodes);
    std::vector<Node> monomials;
    for (int k = 0; k <= p; ++k) monomials.push_back(e.power(e.input(0), k));
    const std::vector<Node> xyz =
        rational_sum(e, power_coefficients(b, p), monomials, curve.dimension, curve.rational);
    out.push_back({{a, c}, e.program(xyz), hull_of(b), b});
  }
  return out;
}

std::vector<SurfacePiece> bezier_pieces(const Surface& surface, std::size_t max_nodes) {
  const auto [p, q] = surface.degree;
  const auto& U = surface.knots_u;
  const auto& V = surface.knots_v;
  std::vector<SurfacePiece> out;
  for (const int i : spans(surface.count_u, p, U))
    for (const int j : spans(surface.count_v, q, V)) {
      // rows[r][l]: the Bézier point l in v of control row i - p + r
      std::vector<std::vector<Homogeneous>> rows;
      for (int r = i - p; r <= i; ++r) {
        const auto first = surface.weighted.begin() + static_cast<std::ptrdiff_t>(r) * surface.count_v;
        const std::vector<Homogeneous> d(first + (j - q), first + j + 1);
        rows.push_back(bezier_points(d, j, q, V));
      }
      std::vector<Homogeneous> net;  // net[k * (q + 1) + l] = b_kl
      net.resize(static_cast<std::size_t>((p + 1) * (q + 1)));
      for (int l = 0; l <= q; ++l) {
        std::vector<Homogeneous> column;
        for (const auto& row : rows) column.push_back(row[static_cast<std::size_t>(l)]);
        const std::vector<Homogeneous> b = bezier_points(column, i, p, U);
        for (int k = 0; k <= p; ++k)
          net[static_cast<std::size_t>(k * (q + 1) + l)] = b[static_cast<std::size_t>(k)];
      }
      const ParamBox span{U[static_cast<std::size_t>(i)], U[static_cast<std::size_t>(i + 1)],
                          V[static_cast<std::size_t>(j)], V[static_cast<std::size_t>(j + 1)]};
      // The power basis in s of every column, then in t of every row: a[k * (q + 1) + l] of s^k t^l.
      std::vector<Homogeneous> a(net.size());
      for (int l = 0; l <= q; ++l) {
        std::vector<Homogeneous> column;
        for (int k = 0; k <= p; ++k) column.push_back(net[static_cast<std::size_t>(k * (q + 1) + l)]);
        const std::vector<Homogeneous> c = power_coefficients(column, p);
        for (int k = 0; k <= p; ++k)
          a[static_cast<std::size_t>(k * (q + 1) + l)] = c[static_cast<std::size_t>(k)];
      }
      for (int k = 0; k <= p; ++k) {
        const std::vector<Homogeneous> row(a.begin() + k * (q + 1), a.begin() + (k + 1) * (q + 1));
        const std::vector<Homogeneous> c = power_coefficients(row, q);
        std::copy(c.begin(), c.end(), a.begin() + k * (q + 1));
      }
      ExpressionBuilder e(2, max_nodes);
      std::vector<Node> monomials;
      for (int k = 0; k <= p; ++k)
        for (int l = 0; l <= q; ++l)
          monomials.push_back(e.mul(e.power(e.input(0), k), e.power(e.input(1), l)));
      const std::vector<Node> xyz = rational_sum(e, a, monomials, 3, surface.rational);
      out.push_back({span, e.program(xyz), hull_of(net), net});
    }
  return out;
}

}  // namespace footpoint::nurbs
