#include "parametric/geometry/surface_closure.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include "formula/interval.hpp"
#include "geometry/geometry_error.hpp"
#include "parametric/geometry/closure_sampling.hpp"
#include "parametric/geometry/params.hpp"

namespace footpoint {

const char* to_string(BoxEdge edge) {
  switch (edge) {
    case BoxEdge::umin:
      return "u=umin";
    case BoxEdge::umax:
      return "u=umax";
    case BoxEdge::vmin:
      return "v=vmin";
    case BoxEdge::vmax:
      return "v=vmax";
  }
  return "unknown";
}

namespace {

using formula::Interval;
using IntervalJets = std::array<formula::IntervalJet2<2>, 3>;
using closure_sampling::kSamples;

// Unit normals of the two sides differing by more than this make a crease; a normal counts only
// where |s_u x s_v| >= kWellDefinedNormal |s_u| |s_v| (there its rounding is below 1e-11).
constexpr double kNormalMismatch = 1e-6;
constexpr double kWellDefinedNormal = 1e-4;
// Interior grid lines (each way) sampled for the size and the magnitudes.
constexpr int kGridLines = 5;
// Pieces of a pole's edge enclosed separately.
constexpr int kPolePieces = 4;
constexpr double kInfinity = std::numeric_limits<double>::infinity();

// A parameter direction: its edges are {p = lo_edge} and {p = hi_edge} (p = u for index 0, v for
// 1), each running along the other parameter t over [lo, hi].
struct Direction {
  int index;
  double lo_edge, hi_edge, lo, hi;
  int along() const { return 1 - index; }
  // (u, v) at edge parameter a and parameter t along the edge.
  Params<2> at(double a, double t) const { return index == 0 ? std::array{a, t} : std::array{t, a}; }
};

Direction direction(const ParamBox& box, int index) {
  return index == 0 ? Direction{0, box.umin, box.umax, box.vmin, box.vmax}
                    : Direction{1, box.vmin, box.vmax, box.umin, box.umax};
}

SurfaceJet jet_at(const SurfaceFormulas& f, const Direction& d, double a, double t) {
  const auto [u, v] = d.at(a, t);
  return f.jet(u, v);
}

IntervalJets interval_jets_at(const SurfaceFormulas& f, const Direction& d, double a, Interval t) {
  Interval x[2];
  x[d.index] = {a, a};
  x[d.along()] = t;
  IntervalJets out;
  f.program().interval_jets2<2>(x, out.data());
  return out;
}

// How two sides agree at the samples: side_a[k] against side_b[k].
struct Match {
  double max_gap = 0.0;  // over the samples where both are defined
  int worst = 0;         // the sample of max_gap
  int defined = 0;       // samples where both are defined
  int one_sided = -1;    // a sample where only one is (-1: none)
  // (A limit that overflowed to infinity - parameters near the largest doubles - accepts nothing.)
  bool within(double limit) const {
    return one_sided < 0 && 2 * defined >= kSamples && max_gap <= limit && std::isfinite(limit);
  }
};

Match match(const std::vector<SurfaceJet>& side_a, const std::vector<SurfaceJet>& side_b) {
  Match m;
  for (int k = 0; k < kSamples; ++k) {
    const Vec3 a = side_a[static_cast<std::size_t>(k)].s, b = side_b[static_cast<std::size_t>(k)].s;
    const bool fa = is_finite(a), fb = is_finite(b);
    if (fa != fb && m.one_sided < 0) m.one_sided = k;
    if (!fa || !fb) continue;
    ++m.defined;
    const double gap = norm(a - b);
    if (gap > m.max_gap) {
      m.max_gap = gap;
      m.worst = k;
    }
  }
  return m;
}

// The unit normal where the tangent plane is well defined, else 0.
Vec3 well_defined_normal(const SurfaceJet& j) {
  const Vec3 n = cross(j.su, j.sv);
  const double length = norm(n);
  if (!(length >= kWellDefinedNormal * norm(j.su) * norm(j.sv)) || !(length > 0.0) || !is_finite(n))
    return {};
  return n / length;
}

// The tangent planes agree across the seam at every sample where both are well defined (and at
// one at least): n(hi side) = sign x n(lo side), sign -1 for a reversed seam.
bool smooth_across(const std::vector<SurfaceJet>& hi_side, const std::vector<SurfaceJet>& lo_side,
                   double sign) {
  int compared = 0;
  for (int k = 0; k < kSamples; ++k) {
    const Vec3 a = well_defined_normal(hi_side[static_cast<std::size_t>(k)]);
    const Vec3 b = well_defined_normal(lo_side[static_cast<std::size_t>(k)]);
    if (norm2(a) == 0.0 || norm2(b) == 0.0) continue;
    ++compared;
    if (norm(a - sign * b) > kNormalMismatch) return false;
  }
  return compared > 0;
}

// The largest |p| over the points p of an interval vector, or infinity where an enclosure is
// empty, partial (the formula undefined somewhere) or unbounded.
double magnitude(const std::array<Interval, 3>& v) {
  for (const Interval& c : v)
    if (c.partial || !(std::isfinite(c.lo) && std::isfinite(c.hi))) return kInfinity;
  namespace iv = formula::interval;
  return closure_sampling::norm_bound(iv::mag(v[0]), iv::mag(v[1]), iv::mag(v[2]));
}

// Enclosures of the gap d(t) = s(hi_edge, t) - s(lo_edge, σ(t)) and its derivatives, from the two
// sides' interval jets: order 0, 1 (along t; σ' = sign) or 2 (σ'^2 = 1).
std::array<Interval, 3> difference(const IntervalJets& hi, const IntervalJets& lo, int order, int along,
                                   double sign) {
  std::array<Interval, 3> d;
  for (std::size_t c = 0; c < 3; ++c) {
    const auto& a = hi[c];
    const auto& b = lo[c];
    const auto ia = static_cast<std::size_t>(along);
    const Interval x = order == 0 ? a.v : order == 1 ? a.g[ia] : a.h[ia][ia];
    const Interval y = order == 0 ? b.v : order == 1 ? b.g[ia] : b.h[ia][ia];
    d[c] = sign > 0.0 || order != 1 ? formula::interval::sub(x, y) : formula::interval::add(x, y);
    d[c].partial = a.v.partial || b.v.partial;
  }
  return d;
}

bool all(const IntervalJets& a, const IntervalJets& b, bool formula::IntervalJet2<2>::*flag) {
  for (std::size_t c = 0; c < 3; ++c)
    if (!(a[c].*flag) || !(b[c].*flag)) return false;
  return true;
}

// A rigorous bound of |s(hi_edge, t) - s(lo_edge, σ(t))| over t in [lo, hi] (header: Taylor's
// theorem from the nearer sample, piece by piece between the samples `ts`).
double gap_bound(const SurfaceFormulas& f, const Direction& d, bool reversed, const std::vector<double>& ts) {
  namespace iv = formula::interval;
  const Interval mirror = iv::add(iv::point(d.lo), iv::point(d.hi));
  const auto sigma = [&](Interval t) { return reversed ? iv::sub(mirror, t) : t; };
  const double sign = reversed ? -1.0 : 1.0;
  const int along = d.along();
  std::vector<double> d0(kSamples), d1(kSamples);  // |d(t_k)|, |d'(t_k)| bounds
  for (std::size_t k = 0; k < static_cast<std::size_t>(kSamples); ++k) {
    const Interval t = iv::point(ts[k]);
    const IntervalJets hi = interval_jets_at(f, d, d.hi_edge, t),
                       lo = interval_jets_at(f, d, d.lo_edge, sigma(t));
    d0[k] = magnitude(difference(hi, lo, 0, along, sign));
    d1[k] = all(hi, lo, &formula::IntervalJet2<2>::lipschitz) ? magnitude(difference(hi, lo, 1, along, sign))
                                                              : kInfinity;
  }
  double bound = 0.0;
  for (std::size_t k = 0; k + 1 < static_cast<std::size_t>(kSamples); ++k) {
    const Interval piece{ts[k], ts[k + 1]};
    const IntervalJets hi = interval_jets_at(f, d, d.hi_edge, piece),
                       lo = interval_jets_at(f, d, d.lo_edge, sigma(piece));
    // Every t of the piece is within `half` of its nearer end.
    const double half = 0.5 * formula::next_up(ts[k + 1] - ts[k]);
    double piece_bound = magnitude(difference(hi, lo, 0, along, sign));  // order 0
    if (all(hi, lo, &formula::IntervalJet2<2>::lipschitz)) {
      const double first = std::max(d0[k], d0[k + 1]) + magnitude(difference(hi, lo, 1, along, sign)) * half;
      piece_bound = std::min(piece_bound, first);
    }
    if (all(hi, lo, &formula::IntervalJet2<2>::smooth)) {
      const double second = std::max(d0[k] + d1[k] * half, d0[k + 1] + d1[k + 1] * half) +
                            0.5 * magnitude(difference(hi, lo, 2, along, sign)) * half * half;
      piece_bound = std::min(piece_bound, second);
    }
    bound = std::max(bound, piece_bound);
  }
  // The few roundings of these sums and products stay far below 16 ulps.
  return std::isfinite(bound) ? formula::up(bound, 16) : kInfinity;
}

// A rigorous bound of |s - point| over the edge {p = a} of direction d.
double radius_bound(const SurfaceFormulas& f, const Direction& d, double a, Vec3 point) {
  double worst = 0.0;
  double start = d.lo;
  for (int j = 1; j <= kPolePieces; ++j) {
    const double end = j == kPolePieces ? d.hi : d.lo + (d.hi - d.lo) * j / kPolePieces;
    Interval x[2], out[3];
    x[d.index] = {a, a};
    x[d.along()] = {start, end};
    f.program().intervals(x, out);
    // The largest distance of a corner of the enclosure from the point, per coordinate.
    std::array<double, 3> far{};
    for (int c = 0; c < 3; ++c) {
      if (out[c].partial || !(std::isfinite(out[c].lo) && std::isfinite(out[c].hi))) return kInfinity;
      far[static_cast<std::size_t>(c)] = std::max(closure_sampling::difference_bound(out[c].lo, point[c]),
                                                  closure_sampling::difference_bound(out[c].hi, point[c]));
    }
    worst = std::max(worst, closure_sampling::norm_bound(far[0], far[1], far[2]));
    start = end;
  }
  return worst;
}

[[noreturn]] void not_periodic(const Direction& d, const Match& same, const Match& reversed, double limit,
                               double size, const std::vector<double>& ts) {
  const char* p = d.index == 0 ? "u" : "v";
  const char* t = d.index == 0 ? "v" : "u";
  const std::string edges = std::string("the edges ") + p + " = " + p + "min and " + p + " = " + p + "max";
  std::string why;
  if (same.one_sided >= 0)
    why = "the formulas are defined on one of " + edges + " and not on the other at " + t + " = " +
          closure_sampling::format(ts[static_cast<std::size_t>(same.one_sided)]);
  else if (2 * same.defined < kSamples)
    why = "the formulas are undefined at most samples of " + edges;
  else
    why = edges + " are " + closure_sampling::format(same.max_gap) + " apart at " + t + " = " +
          closure_sampling::format(ts[static_cast<std::size_t>(same.worst)]) +
          " (a periodic direction needs them within " + closure_sampling::format(limit) +
          ", 1e-6 of the geometry's size " + closure_sampling::format(size) + ")";
  if (reversed.within(limit))
    why += "; they coincide with " + std::string(t) +
           " reversed, a seam that is found without declaring it and " + "is not periodic";
  throw GeometryError("not_periodic", "periodic", -1, std::string(p) + " is declared periodic, but " + why);
}

}  // namespace

SurfaceClosure detect_surface_closure(const SurfaceFormulas& formulas, const ParamBox& box,
                                      std::array<bool, 2> declared_periodic) {
  SurfaceClosure closure;
  // The four edges' samples (by BoxEdge) and the parameters along each direction's edges.
  std::array<std::vector<SurfaceJet>, 4> edges;
  std::array<std::vector<double>, 2> along;
  closure_sampling::Extent extent;
  double speed_u = 0.0, speed_v = 0.0;
  for (int i = 0; i < 2; ++i) {
    const Direction d = direction(box, i);
    along[static_cast<std::size_t>(i)] = closure_sampling::samples(d.lo, d.hi);
    for (int side = 0; side < 2; ++side) {
      auto& edge = edges[static_cast<std::size_t>(2 * i + side)];
      for (double t : along[static_cast<std::size_t>(i)]) {
        const SurfaceJet j = jet_at(formulas, d, side == 0 ? d.lo_edge : d.hi_edge, t);
        edge.push_back(j);
        if (!is_finite(j.s)) continue;
        extent.add(j.s);
        if (is_finite(j.su)) speed_u = std::max(speed_u, norm(j.su));
        if (is_finite(j.sv)) speed_v = std::max(speed_v, norm(j.sv));
      }
    }
  }
  for (int i = 1; i < kGridLines + 1; ++i)
    for (int j = 1; j < kGridLines + 1; ++j) {
      const Vec3 p = formulas.point(box.umin + (box.umax - box.umin) * i / (kGridLines + 1),
                                    box.vmin + (box.vmax - box.vmin) * j / (kGridLines + 1));
      if (is_finite(p)) extent.add(p);
    }
  const double u_magnitude = std::max(std::abs(box.umin), std::abs(box.umax));
  const double v_magnitude = std::max(std::abs(box.vmin), std::abs(box.vmax));
  closure.tolerance =
      closure_sampling::rounding_tolerance(extent.magnitude + speed_u * u_magnitude + speed_v * v_magnitude);
  const double declared_limit = closure_sampling::declared_limit(closure.tolerance, extent.size());

  for (int i = 0; i < 2; ++i) {
    const Direction d = direction(box, i);
    const std::vector<double>& ts = along[static_cast<std::size_t>(i)];
    const auto& lo_side = edges[static_cast<std::size_t>(2 * i)];
    const auto& hi_side = edges[static_cast<std::size_t>(2 * i + 1)];
    SurfaceSeam& seam = closure.seams[static_cast<std::size_t>(i)];
    const Match same = match(hi_side, lo_side);
    // The lo side at the mirrored parameters lo + hi - t_k, for a reversed seam.
    std::vector<SurfaceJet> mirrored;
    Match reversed;
    if (same.within(closure.tolerance)) {
      seam.closed = true;
    } else {
      for (double t : ts) mirrored.push_back(jet_at(formulas, d, d.lo_edge, d.lo + d.hi - t));
      reversed = match(hi_side, mirrored);
      seam.closed = seam.reversed = reversed.within(closure.tolerance);
    }
    if (declared_periodic[static_cast<std::size_t>(i)]) {
      if (!seam.periodic() && !same.within(declared_limit))
        not_periodic(d, same, reversed, declared_limit, extent.size(), ts);
      seam.closed = seam.declared = true;
      seam.reversed = false;
    }
    if (!seam.closed) continue;
    seam.max_gap = (seam.reversed ? reversed : same).max_gap;
    seam.smooth = smooth_across(hi_side, seam.reversed ? mirrored : lo_side, seam.reversed ? -1.0 : 1.0);
    seam.gap_bound = gap_bound(formulas, d, seam.reversed, ts);
  }

  for (std::size_t e = 0; e < 4; ++e) {
    const std::vector<SurfaceJet>& edge = edges[e];
    Vec3 sum;
    bool finite = true;
    for (const SurfaceJet& j : edge) {
      finite = finite && is_finite(j.s);
      sum += j.s;
    }
    if (!finite) continue;
    const Vec3 mean = sum / static_cast<double>(edge.size());
    double spread = 0.0;
    for (const SurfaceJet& j : edge) spread = std::max(spread, norm(j.s - mean));
    if (!(spread <= closure.tolerance) || !std::isfinite(closure.tolerance)) continue;
    SurfacePole& pole = closure.poles[e];
    const Direction d = direction(box, static_cast<int>(e / 2));
    pole.collapsed = true;
    pole.point = mean;
    pole.radius_bound = radius_bound(formulas, d, e % 2 == 0 ? d.lo_edge : d.hi_edge, mean);
  }
  return closure;
}

}  // namespace footpoint
