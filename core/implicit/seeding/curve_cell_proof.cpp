#include "implicit/seeding/curve_cell_proof.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/dense_solve.hpp"

namespace footpoint {
namespace {

namespace iv = formula::interval;

bool strictly_inside_face(const Box3& face, int axis, const Box3& e, int dims) {
  for (int k = 0; k < dims; ++k)
    if (k != axis && !(face.lo[k] < e.lo[k] && e.hi[k] < face.hi[k])) return false;
  return true;
}

// Widths and midpoints of interval vectors, summed in quadrature (rounding does not matter here:
// this only decides where to bisect).
void accumulate(const IVec3& v, double& width2, double& mid2) {
  for (const Interval& x : v) {
    width2 += (x.hi - x.lo) * (x.hi - x.lo);
    mid2 += iv::mid(x) * iv::mid(x);
  }
}

double ratio(double width2, double mid2) { return width2 > 0.0 ? std::sqrt(width2 / mid2) : 0.0; }

double relative_width(const IVec3& v) {
  double w = 0.0, m = 0.0;
  accumulate(v, w, m);
  return ratio(w, m);
}

bool combination_excludes(const ImplicitIntervalJet& j, const ImplicitIntervalJet& jc, const IVec3& offset) {
  const Vec3 g1 = ivec::mid(jc.grad[0]), g2 = ivec::mid(jc.grad[1]);
  Matrix<2> a{{{dot(g1, g1), dot(g1, g2)}, {dot(g2, g1), dot(g2, g2)}}};
  Vector<2> w{iv::mid(jc.f[0]), iv::mid(jc.f[1])};
  if (!dense_solve<2>(a, w)) return false;
  const Interval w1 = iv::point(w[0]), w2 = iv::point(w[1]);
  const Interval g_c = iv::add(iv::mul(w1, jc.f[0]), iv::mul(w2, jc.f[1]));
  const IVec3 grad_c = ivec::add(ivec::scale(w1, jc.grad[0]), ivec::scale(w2, jc.grad[1]));
  Interval quadratic{0.0, 0.0};
  for (int r = 0; r < 3; ++r) {
    const IVec3 row = ivec::add(ivec::scale(w1, j.hess[0][r]), ivec::scale(w2, j.hess[1][r]));
    quadratic = iv::add(quadratic, iv::mul(offset[r], ivec::dot(row, offset)));
  }
  return iv::add(iv::add(g_c, ivec::dot(grad_c, offset)), iv::mul(0.5, quadratic)).excludes_zero();
}

}  // namespace

double looseness(const CellBounds& b, double edge) {
  double w = 0.0, m = 0.0;
  for (const IVec3& row : b.tangent_derivatives) accumulate(row, w, m);
  // ∂T/∂x_j against the larger of itself and |T| / edge, the scale at which it moves T across the
  // cell (near an inflection ∂T is small, and so is what its width matters for).
  double wt = 0.0, mt = 0.0;
  accumulate(b.tangent, wt, mt);
  const double scale2 = std::max(m, mt / (edge * edge));
  return std::max({relative_width(b.grad[0]), relative_width(b.grad[1]), ratio(wt, mt), ratio(w, scale2)});
}

EnlargedBounds enlarged_bounds(const ImplicitEquations& equations, const Box3& cell, const Box3& domain) {
  EnlargedBounds e;
  for (int k = 0; k < 3; ++k) {
    const double half = 1.0 * (cell.hi[k] - cell.lo[k]);
    e.box.lo[k] = std::max(domain.lo[k], cell.lo[k] - half);
    e.box.hi[k] = std::min(domain.hi[k], cell.hi[k] + half);
  }
  const ImplicitIntervalJet j = equations.interval_jet(e.box);
  e.valid = j.smooth;
  e.grad = j.grad;
  e.tangent = j.tangent();
  e.tangent_derivatives = j.tangent_derivatives();
  return e;
}

CellProof prove_cell(const ImplicitEquations& equations, const Box3& cell, double max_looseness,
                     FaceCrossingCache* faces) {
  CellProof proof;
  const int dims = equations.planar() ? 2 : 3;
  ++proof.evaluations;
  const ImplicitIntervalJet j = equations.interval_jet(cell);
  if (j.f[0].excludes_zero() || j.f[1].excludes_zero()) {
    proof.verdict = CellVerdict::empty;
    return proof;
  }
  if (!j.smooth) {
    proof.reason = UnprovedReason::not_smooth;
    return proof;
  }
  const Vec3 c = cell.center();
  ++proof.evaluations;
  const ImplicitIntervalJet jc = equations.interval_gradient({c, c});
  const IVec3 offset = ivec::sub(ivec::of_box(cell), ivec::of_point(c));
  for (int i = 0; i < 2; ++i) {
    // The mean value form, and Taylor's formula with the Lagrange remainder:
    // f(c + δ) ∈ f(c) + ∇f(c)·δ + ½ δᵀ H(B) δ (the quadratic term row by row: δ_r (H δ)_r).
    Interval quadratic{0.0, 0.0};
    for (int r = 0; r < 3; ++r)
      quadratic = iv::add(quadratic, iv::mul(offset[r], ivec::dot(j.hess[i][r], offset)));
    const Interval taylor = iv::add(iv::add(jc.f[i], ivec::dot(jc.grad[i], offset)), iv::mul(0.5, quadratic));
    if (iv::add(jc.f[i], ivec::dot(j.grad[i], offset)).excludes_zero() || taylor.excludes_zero()) {
      proof.verdict = CellVerdict::empty;
      return proof;
    }
  }
  // Both surfaces may pass through the cell without meeting there: g = w1 f1 + w2 f2 with
  // w = (J Jᵀ)⁻¹ f(c) (J the gradients at c) vanishes, to first order, on the plane through the
  // nearest point of the linearised curve orthogonal to the step to it; Taylor's formula for g
  // (any fixed w is allowed) excludes the cell when it lies beyond that plane.
  if (combination_excludes(j, jc, offset)) {
    proof.verdict = CellVerdict::empty;
    return proof;
  }
  const IMat3 dt = j.tangent_derivatives();
  IVec3 mean = jc.tangent();
  for (int k = 0; k < 3; ++k) mean = ivec::add(mean, ivec::scale(offset[k], dt[k]));
  const IVec3 t = ivec::intersect(j.tangent(), mean);

  // The coordinate the curve runs along most: the largest |T_k| bounded away from 0, against |T|.
  // In space, claim (a) needs more than T_k ≠ 0 at every point: the mean value theorem takes each
  // row of the slice's Jacobian at a point of its own, and the determinants of such mixed matrices
  // range over the natural cross product ∇f1(B) × ∇f2(B) (each entry once in the 2x2 determinant:
  // its range), so T_k must be bounded away from 0 there too. In the plane the slice is a segment
  // and one row, taken at one point.
  const IVec3 mixed = j.tangent();
  int axis = -1;
  double best = 0.0;
  for (int k = 0; k < dims; ++k) {
    const double m = iv::mig(t[k]);
    if (m > best && (dims == 2 || mixed[k].excludes_zero())) best = m, axis = k;
  }
  if (axis < 0) {
    proof.reason = UnprovedReason::tangent_may_vanish;
    return proof;
  }
  proof.bounds = {c, jc.f, j.grad, t, jc.tangent(), dt};
  if (looseness(proof.bounds, cell.max_edge()) > max_looseness) {
    proof.reason = UnprovedReason::loose;
    return proof;
  }

  for (int a = 0; a < dims; ++a)
    for (int side = 0; side < 2; ++side) {
      Box3 face = cell;
      face.lo[a] = face.hi[a] = side == 0 ? cell.lo[a] : cell.hi[a];
      const std::size_t first = proof.crossings.size();
      const bool decided =
          faces ? faces->locate(face, a, proof.crossings, proof.evaluations)
                : locate_face_crossings(equations, face, a, proof.crossings, proof.evaluations);
      if (!decided) {
        proof.reason = UnprovedReason::faces_undecided;
        proof.crossings.clear();
        return proof;
      }
      for (std::size_t i = first; i < proof.crossings.size(); ++i)
        if (!strictly_inside_face(face, a, proof.crossings[i].enclosure, dims)) {
          proof.reason = UnprovedReason::faces_undecided;
          proof.crossings.clear();
          return proof;
        }
    }
  if (proof.crossings.size() % 2 != 0) {
    proof.reason = UnprovedReason::faces_undecided;
    proof.crossings.clear();
    return proof;
  }
  if (proof.crossings.empty()) {
    proof.verdict = CellVerdict::empty;
    return proof;
  }
  std::sort(proof.crossings.begin(), proof.crossings.end(),
            [axis](const FaceCrossing& x, const FaceCrossing& y) { return x.point[axis] < y.point[axis]; });
  // Consecutive ends must be told apart along x_k (their boxes disjoint), or the pairing is unsure.
  for (std::size_t i = 1; i < proof.crossings.size(); ++i)
    if (!(proof.crossings[i - 1].enclosure.hi[axis] < proof.crossings[i].enclosure.lo[axis])) {
      proof.reason = UnprovedReason::faces_undecided;
      proof.crossings.clear();
      return proof;
    }
  proof.verdict = CellVerdict::arcs;
  proof.axis = axis;
  for (std::size_t i = 0; i + 1 < proof.crossings.size(); i += 2)
    proof.capsules.push_back(arc_capsule(proof.bounds, axis, proof.crossings[i], proof.crossings[i + 1]));
  return proof;
}

ArcCapsule arc_capsule(const CellBounds& bounds, int axis, const FaceCrossing& start,
                       const FaceCrossing& end) {
  const Interval tk = bounds.tangent[axis];
  const IMat3& dt = bounds.tangent_derivatives;  // row m: ∂T/∂x_m
  const double length = formula::next_up(end.enclosure.hi[axis] - start.enclosure.lo[axis]);
  double deviation2 = 0.0;
  for (int j = 0; j < 3; ++j) {
    if (j == axis) continue;
    const Interval slope = iv::div(bounds.tangent[j], tk);
    Interval second{0.0, 0.0};
    for (int m = 0; m < 3; ++m) {
      const Interval d_slope =
          iv::div(iv::sub(iv::mul(dt[m][j], tk), iv::mul(bounds.tangent[j], dt[m][axis])), iv::sqr(tk));
      second = iv::add(second, iv::mul(d_slope, iv::div(bounds.tangent[m], tk)));
    }
    const double by_slope = formula::next_up(slope.hi - slope.lo) * length * 0.5;
    const double by_curvature = iv::mag(second) * length * length * 0.125;
    const double deviation = std::fmin(by_slope, by_curvature);
    deviation2 += deviation * deviation;
  }
  double diameter = 0.0;
  for (const FaceCrossing* e : {&start, &end}) {
    double sum = 0.0;
    for (int k = 0; k < 3; ++k) sum += e->enclosure.hi[k] - e->enclosure.lo[k];
    diameter = std::fmax(diameter, sum);
  }
  // A few roundings on upper bounds of non-negative quantities: covered by the factor.
  const double radius = (std::sqrt(deviation2) + diameter) * (1.0 + 0x1p-40);
  return {start.point, end.point, std::isfinite(radius) ? radius : std::numeric_limits<double>::infinity()};
}

Box3 capsule_box(const ArcCapsule& c) {
  Box3 b;
  for (int k = 0; k < 3; ++k) {
    b.lo[k] = formula::next_down(std::fmin(c.a[k], c.b[k]) - c.radius);
    b.hi[k] = formula::next_up(std::fmax(c.a[k], c.b[k]) + c.radius);
  }
  return b;
}

}  // namespace footpoint
