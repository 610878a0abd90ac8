// Non-uniform rational B-spline curves and surfaces: their definition checked, and their points
// with exact derivatives to second order, span by span ([PieglTiller] L. Piegl, W. Tiller, The
// NURBS Book, 2nd ed., Springer 1997):
//   - A2.1 FindSpan: the knot span [U_i, U_{i+1}) of the parameter, by bisection;
//   - A2.3 DersBasisFuns: the p + 1 basis functions N_{i-p..i,p} that do not vanish there and their
//     derivatives, from the triangular table of Cox-de Boor's recurrence (eq. (2.5), (2.9));
//   - A3.2 / A3.6: the derivatives of the B-spline of the weighted control points P^w = (w P, w) in
//     homogeneous space, Σ N^(k)_i P^w_i (and the tensor product for surfaces);
//   - A4.2 / A4.4: the derivatives of the rational curve C = A / w and surface S = A / w from those
//     of A and w by Leibniz's rule (eq. (4.8), (4.20)):
//       C^(k) = (A^(k) - Σ_{i=1..k} binom(k,i) w^(i) C^(k-i)) / w,
//       S_kl = (A_kl - Σ_{j=1..l} binom(l,j) w_0j S_k,l-j
//                    - Σ_{i=1..k} binom(k,i) (w_i0 S_k-i,l + Σ_{j=1..l} binom(l,j) w_ij S_k-i,l-j)) / w_00.
// Knot vectors are full (n + p + 1 knots for n control points, clamped or not); the domain is
// [U_p, U_n]. At an interior knot of multiplicity m the derivatives of order > p - m jump; the
// span on the right of the knot is used (at the domain's upper end, the last span).
//
// Limits: degree 1..kMaxDegree; weights finite and > 0; the derivatives of order 2 of a degree-1
// curve are 0 (exactly, inside a span).
#pragma once
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "geometry/vec.hpp"
#include "parametric/geometry/parametric_curve.hpp"
#include "parametric/geometry/parametric_surface.hpp"

namespace footpoint::nurbs {

inline constexpr int kMaxDegree = 12;

// A definition refused: the field at fault (e.g. "knots", "weights[3]") and why.
struct DefinitionError {
  std::string field;
  std::string message;
};

// A2.1: the span index i in [p, n - 1] with U_i <= u < U_{i+1}, for n control points and the
// knots U (n + p + 1 of them); u at or beyond U_n gives the last non-empty span, u at or below U_p
// the first.
int find_span(int n, int p, double u, const std::vector<double>& U);

// A2.3: the derivatives of order k = 0..d (d <= p) of the p + 1 basis functions that do not vanish
// on span i at u: ders[k * (p + 1) + j] = N^(k)_{i-p+j,p}(u).
void basis_derivatives(int i, double u, int p, int d, const std::vector<double>& U, double* ders);

struct Curve {
  int degree = 0;
  std::vector<double> knots;
  // the control points weighted, (w x, w y, w z, w); z = 0 for a planar curve
  std::vector<std::array<double, 4>> weighted;
  int dimension = 3;  // 2: planar
  bool rational = false;
  double tmin() const { return knots[static_cast<std::size_t>(degree)]; }
  double tmax() const { return knots[weighted.size()]; }
};

struct Surface {
  std::array<int, 2> degree{};
  std::vector<double> knots_u, knots_v;
  int count_u = 0, count_v = 0;
  // the control net weighted, P_ij at i * count_v + j (i along u)
  std::vector<std::array<double, 4>> weighted;
  bool rational = false;
  double umin() const { return knots_u[static_cast<std::size_t>(degree[0])]; }
  double umax() const { return knots_u[static_cast<std::size_t>(count_u)]; }
  double vmin() const { return knots_v[static_cast<std::size_t>(degree[1])]; }
  double vmax() const { return knots_v[static_cast<std::size_t>(count_v)]; }
};

// A curve from its definition: degree, full knot vector, control points of 2 or 3 coordinates,
// weights (empty: all 1, non-rational). Refused with the field at fault: a degree outside
// 1..kMaxDegree, fewer than degree + 1 control points or more than max_points, points of mixed or
// wrong dimension or not finite, a knot vector of the wrong length, decreasing or not finite, an
// empty domain, weights of the wrong count, not finite or <= 0.
struct CurveOrError {
  std::optional<Curve> curve;
  DefinitionError error;
};
CurveOrError make_curve(int degree, const std::vector<double>& knots,
                        const std::vector<std::vector<double>>& control_points,
                        const std::vector<double>& weights, std::size_t max_points);

// A surface from its definition: degrees (u, v), knot vectors, the control net (rows along u,
// control_points[i][j] = P_ij, 3 coordinates each), weights (the same shape, or empty). Refused as
// for curves; also a ragged net.
struct SurfaceOrError {
  std::optional<Surface> surface;
  DefinitionError error;
};
SurfaceOrError make_surface(const std::array<int, 2>& degree, const std::vector<double>& knots_u,
                            const std::vector<double>& knots_v,
                            const std::vector<std::vector<std::vector<double>>>& control_points,
                            const std::vector<std::vector<double>>& weights, std::size_t max_points);

// The point and its first two derivatives at t (clamped to the domain).
CurveJet evaluate(const Curve& curve, double t);
// The point and its partial derivatives to second order at (u, v) (clamped to the domain).
SurfaceJet evaluate(const Surface& surface, double u, double v);

}  // namespace footpoint::nurbs
