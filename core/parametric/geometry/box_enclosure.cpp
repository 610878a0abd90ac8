#include "parametric/geometry/box_enclosure.hpp"

#include <cmath>

#include "formula/interval.hpp"
#include "formula/interval_arith.hpp"

namespace footpoint {

namespace {

bool finite(const formula::Interval& x) { return std::isfinite(x.lo) && std::isfinite(x.hi); }

}  // namespace

template <int N>
BoxEnclosure<N> enclose_box(const formula::Program& program, const Params<N>& lo, const Params<N>& hi,
                            const formula::BranchChoice* choice) {
  using formula::Interval;
  BoxEnclosure<N> e;
  e.lo = lo;
  e.hi = hi;
  Interval x[N];
  for (int i = 0; i < N; ++i) x[i] = {lo[i], hi[i]};
  formula::IntervalJet2<N> out[3];
  if (choice)
    program.interval_jets2<N>(x, out, *choice);
  else
    program.interval_jets2<N>(x, out);
  const int dim = program.num_outputs();
  // a planar curve's z is 0, exactly
  for (int k = dim; k < 3; ++k) out[k] = formula::IntervalJet2<N>{};

  e.bounded = true;
  e.smooth = true;
  e.finite_part = true;
  for (int k = 0; k < 3; ++k) {
    const formula::IntervalJet2<N>& c = out[k];
    e.empty = e.empty || formula::IntervalArith::bad(c.v);
    e.finite_part = e.finite_part && finite(c.v);
    e.bounded = e.bounded && !c.v.partial && finite(c.v);
    e.smooth = e.smooth && c.smooth;
    e.s_mid[k] = formula::interval::mid(c.v);
    e.s_rad[k] = formula::interval::rad(c.v);
    for (int i = 0; i < N; ++i)
      for (int j = i; j < N; ++j) {
        const Interval& h = c.h[i][j];
        e.smooth = e.smooth && finite(h) && finite(c.g[i]);
        e.d2_mid[BoxEnclosure<N>::pair(i, j)][k] = formula::interval::mid(h);
        e.d2_rad[BoxEnclosure<N>::pair(i, j)][k] = formula::interval::rad(h);
      }
  }
  e.finite_part = e.finite_part && !e.empty;
  e.smooth = e.smooth && e.bounded;
  if (!e.smooth) return e;
  // <s_i, s_j> as an interval sum of interval products (outward rounded)
  for (int i = 0; i < N; ++i)
    for (int j = i; j < N; ++j) {
      Interval sum{0.0, 0.0};
      for (int k = 0; k < 3; ++k)
        sum = formula::interval::add(sum, i == j ? formula::interval::sqr(out[k].g[i])
                                                 : formula::interval::mul(out[k].g[i], out[k].g[j]));
      e.metric_lo[BoxEnclosure<N>::pair(i, j)] = i == j ? std::fmax(sum.lo, 0.0) : sum.lo;
      e.metric_hi[BoxEnclosure<N>::pair(i, j)] = sum.hi;
    }
  return e;
}

template <int N>
PointEnclosure<N> enclose_point(const formula::Program& program, const Params<N>& t,
                                const formula::BranchChoice* choice) {
  PointEnclosure<N> e;
  formula::BallJet1<N> out[3];
  if (choice)
    program.ball_jets1<N>(t.data(), out, *choice);
  else
    program.ball_jets1<N>(t.data(), out);
  const int dim = program.num_outputs();
  e.valid = true;
  for (int k = 0; k < dim; ++k) {
    const formula::BallJet1<N>& b = out[k];
    e.valid = e.valid && b.defined && b.differentiable;
    e.s[k] = b.v.mid;
    e.s_rad[k] = b.v.rad;
    for (int i = 0; i < N; ++i) {
      e.ds[i][k] = b.g[i].mid;
      e.ds_rad[i][k] = b.g[i].rad;
      e.valid = e.valid && std::isfinite(b.g[i].mid) && std::isfinite(b.g[i].rad);
    }
  }
  return e;
}

BoxEnclosure<2> derive_enclosure(const BoxEnclosure<2>& ancestor, const Params<2>& lo, const Params<2>& hi,
                                 const PointEnclosure<2>& centre) {
  using formula::Interval;
  BoxEnclosure<2> e;
  e.lo = lo;
  e.hi = hi;
  // Taylor's theorem needs the ancestor's second derivatives: without them nothing is derived,
  // and the enclosure holds nothing (not bounded, so that intersect keeps the other one whole).
  e.bounded = ancestor.bounded && ancestor.smooth && centre.valid;
  e.smooth = e.bounded;
  if (!e.smooth) return e;
  e.d2_mid = ancestor.d2_mid;
  e.d2_rad = ancestor.d2_rad;
  // radii computed in round to nearest: a few dozen operations, covered by 2^-44 relative
  constexpr double up = 1.0 + 0x1p-44;
  const double h[2] = {(0.5 * (hi[0] - lo[0])) * up, (0.5 * (hi[1] - lo[1])) * up};
  Interval J[2][3];
  for (int k = 0; k < 3; ++k) {
    auto mag = [&](int pair) { return std::abs(ancestor.d2_mid[pair][k]) + ancestor.d2_rad[pair][k]; };
    const double muu = mag(0), muv = mag(1), mvv = mag(2);
    const double ju = std::abs(centre.ds[0][k]) + centre.ds_rad[0][k];
    const double jv = std::abs(centre.ds[1][k]) + centre.ds_rad[1][k];
    e.s_mid[k] = centre.s[k];
    e.s_rad[k] = (centre.s_rad[k] + ju * h[0] + jv * h[1] +
                  0.5 * (muu * h[0] * h[0] + 2.0 * muv * h[0] * h[1] + mvv * h[1] * h[1])) *
                 up;
    const double ru = (centre.ds_rad[0][k] + muu * h[0] + muv * h[1]) * up;
    const double rv = (centre.ds_rad[1][k] + muv * h[0] + mvv * h[1]) * up;
    J[0][k] = formula::interval::outward(centre.ds[0][k] - ru, centre.ds[0][k] + ru);
    J[1][k] = formula::interval::outward(centre.ds[1][k] - rv, centre.ds[1][k] + rv);
  }
  for (int i = 0; i < 2; ++i)
    for (int j = i; j < 2; ++j) {
      Interval sum{0.0, 0.0};
      for (int k = 0; k < 3; ++k)
        sum = formula::interval::add(
            sum, i == j ? formula::interval::sqr(J[i][k]) : formula::interval::mul(J[i][k], J[j][k]));
      e.metric_lo[BoxEnclosure<2>::pair(i, j)] = i == j ? std::fmax(sum.lo, 0.0) : sum.lo;
      e.metric_hi[BoxEnclosure<2>::pair(i, j)] = sum.hi;
    }
  for (int k = 0; k < 3; ++k)
    if (!std::isfinite(e.s_rad[k])) e.bounded = e.smooth = false;
  return e;
}

BoxEnclosure<2> intersect(const BoxEnclosure<2>& a, const BoxEnclosure<2>& b) {
  if (!a.bounded) return b;
  if (!b.bounded) return a;
  BoxEnclosure<2> e = a;
  // mid ± rad per coordinate: the intersection's hull, written back as mid ± rad (rounded up)
  auto meet = [](double ma, double ra, double mb, double rb, double* m, double* r) {
    const double lo = std::fmax(ma - ra, mb - rb), hi = std::fmin(ma + ra, mb + rb);
    if (!(lo <= hi)) return;  // cannot happen for two enclosures of one range: keep a's
    const double mid = 0.5 * lo + 0.5 * hi;
    const double rad = std::fmax(mid - lo, hi - mid);
    // the ends were rounded: widen by their rounding
    *m = mid;
    *r = (rad + 0x1p-52 * (std::abs(lo) + std::abs(hi))) * (1.0 + 0x1p-50);
  };
  for (int k = 0; k < 3; ++k) meet(a.s_mid[k], a.s_rad[k], b.s_mid[k], b.s_rad[k], &e.s_mid[k], &e.s_rad[k]);
  e.smooth = a.smooth || b.smooth;
  if (a.smooth && b.smooth) {
    for (int pair = 0; pair < 3; ++pair) {
      for (int k = 0; k < 3; ++k)
        meet(a.d2_mid[pair][k], a.d2_rad[pair][k], b.d2_mid[pair][k], b.d2_rad[pair][k], &e.d2_mid[pair][k],
             &e.d2_rad[pair][k]);
      e.metric_lo[pair] = std::fmax(a.metric_lo[pair], b.metric_lo[pair]);
      e.metric_hi[pair] = std::fmin(a.metric_hi[pair], b.metric_hi[pair]);
    }
  } else if (b.smooth) {
    e.d2_mid = b.d2_mid;
    e.d2_rad = b.d2_rad;
    e.metric_lo = b.metric_lo;
    e.metric_hi = b.metric_hi;
  }
  return e;
}

template BoxEnclosure<1> enclose_box<1>(const formula::Program&, const Params<1>&, const Params<1>&,
                                        const formula::BranchChoice*);
template BoxEnclosure<2> enclose_box<2>(const formula::Program&, const Params<2>&, const Params<2>&,
                                        const formula::BranchChoice*);
template PointEnclosure<1> enclose_point<1>(const formula::Program&, const Params<1>&,
                                            const formula::BranchChoice*);
template PointEnclosure<2> enclose_point<2>(const formula::Program&, const Params<2>&,
                                            const formula::BranchChoice*);

}  // namespace footpoint
