#include "parametric/seeding/parametric_curve_cells.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/compile_budget.hpp"

namespace footpoint {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

ParametricCurveCell make_cell(const CurveFormulas& f, double t0, double t1) {
  ParametricCurveCell c;
  c.t0 = t0;
  c.t1 = t1;
  c.enclosure = enclose_box<1>(f.program(), {t0}, {t1});
  c.centre = f.jet(c.tc());
  const PointEnclosure<1> exact = enclose_point<1>(f.program(), {c.tc()});
  c.centre_valid = exact.valid && is_finite(c.centre.c) && is_finite(c.centre.d1);
  c.rho = kInf;
  if (!c.centre_valid) return c;
  for (int k = 0; k < 3; ++k) {
    c.c_rad[k] = (std::abs(c.centre.c[k] - exact.s[k]) + exact.s_rad[k]) * (1.0 + 0x1p-50);
    c.d1_rad[k] = (std::abs(c.centre.d1[k] - exact.ds[0][k]) + exact.ds_rad[0][k]) * (1.0 + 0x1p-50);
  }
  if (!c.enclosure.smooth) return c;
  // per coordinate: the centre's rounding, c' 's rounding times h, and ½ h^2 |c''|
  const double h = 0.5 * (t1 - t0);
  double rho2 = 0.0;
  for (int k = 0; k < 3; ++k) {
    const double second = std::abs(c.enclosure.d2_mid[0][k]) + c.enclosure.d2_rad[0][k];
    const double ek = c.c_rad[k] + c.d1_rad[k] * h + 0.5 * h * h * second;
    rho2 += ek * ek;
  }
  c.rho = std::sqrt(rho2) * (1.0 + 0x1p-46);
  if (std::isnan(c.rho)) c.rho = kInf;
  return c;
}

}  // namespace

ParametricCurveCells::ParametricCurveCells(const CurveFormulas& formulas, const ParamInterval& domain,
                                           std::vector<double> breaks, CompileBudget& budget, int per_cell) {
  breaks.push_back(domain.tmin);
  breaks.push_back(domain.tmax);
  std::sort(breaks.begin(), breaks.end());
  breaks.erase(std::unique(breaks.begin(), breaks.end()), breaks.end());
  breaks.erase(std::remove_if(breaks.begin(), breaks.end(),
                              [&](double t) { return !(t >= domain.tmin && t <= domain.tmax); }),
               breaks.end());
  const std::size_t step = static_cast<std::size_t>(std::max(per_cell, 1));
  for (std::size_t i = 0; i + 1 < breaks.size(); i += step) {
    budget.check();
    const std::size_t j = std::min(i + step, breaks.size() - 1);
    cells_.push_back(make_cell(formulas, breaks[i], breaks[j]));
  }
  if (cells_.size() > 1) {
    Vec3 lo, hi;
    nodes_.reserve(cells_.size());
    build(0, cells_.size(), &lo, &hi);
  }
}

// A node over cells [begin, end) (at least two), its box the union of its children's; nodes come
// before their children (the root is nodes_[0]).
std::int32_t ParametricCurveCells::build(std::size_t begin, std::size_t end, Vec3* lo, Vec3* hi) {
  const auto index = static_cast<std::int32_t>(nodes_.size());
  nodes_.emplace_back();
  const std::size_t mid = begin + (end - begin) / 2;
  Vec3 lo_k[2], hi_k[2];
  const std::size_t range[3] = {begin, mid, end};
  std::int32_t child[2];
  for (int k = 0; k < 2; ++k) {
    if (range[k + 1] - range[k] == 1) {
      const ParametricCurveCell& c = cells_[range[k]];
      child[k] = ~static_cast<std::int32_t>(range[k]);
      for (int a = 0; a < 3; ++a) {
        const bool bounded = c.enclosure.bounded;
        lo_k[k][a] = bounded ? c.enclosure.s_mid[a] - c.enclosure.s_rad[a] * (1.0 + 0x1p-50) : -kInf;
        hi_k[k][a] = bounded ? c.enclosure.s_mid[a] + c.enclosure.s_rad[a] * (1.0 + 0x1p-50) : kInf;
        // mid ± rad computed in round to nearest: one step outwards
        lo_k[k][a] = std::nextafter(lo_k[k][a], -kInf);
        hi_k[k][a] = std::nextafter(hi_k[k][a], kInf);
      }
    } else {
      child[k] = build(range[k], range[k + 1], &lo_k[k], &hi_k[k]);
    }
  }
  ParametricCurveCellNode& n = nodes_[static_cast<std::size_t>(index)];
  for (int a = 0; a < 3; ++a) {
    n.lo[a] = std::min(lo_k[0][a], lo_k[1][a]);
    n.hi[a] = std::max(hi_k[0][a], hi_k[1][a]);
  }
  n.child[0] = child[0];
  n.child[1] = child[1];
  *lo = n.lo;
  *hi = n.hi;
  return index;
}

}  // namespace footpoint
