#include "parametric/solvers/curve_kink_minimum.hpp"

#include <algorithm>
#include <cmath>

namespace footpoint::curve {

namespace {

constexpr double kU = 0x1p-53;

struct Slope {
  double g = 0.0;     // φ'(t)
  double dg = 0.0;    // |φ''(t)|
  double size = 0.0;  // |c'| |c - p|: the scale of φ'(t)'s rounding
  double phi = 0.0;   // φ(t)
};

Slope slope_at(const CurveFormulas& formulas, Vec3 p, double t) {
  const CurveJet j = formulas.jet(t);
  const Vec3 d = j.c - p;
  return {dot(d, j.d1), std::abs(dot(j.d1, j.d1) + dot(d, j.d2)), norm(j.d1) * norm(d), 0.5 * dot(d, d)};
}

}  // namespace

bool kink_minimum(const CurveFormulas& formulas, Vec3 p, double scale, double& t) {
  const double h = 16.0 * kU * std::max(std::abs(t), scale);
  double a = t - h, b = t + h;
  Slope sa = slope_at(formulas, p, a), sb = slope_at(formulas, p, b);
  const auto kink = [](const Slope& l, const Slope& r, double width) {
    const double smooth = 1e3 * width * std::max(l.dg, r.dg) + 64.0 * kU * std::max(l.size, r.size);
    return l.g <= 0.0 && r.g >= 0.0 && r.g - l.g > smooth;
  };
  if (!std::isfinite(sa.g) || !std::isfinite(sb.g) || !kink(sa, sb, b - a)) return false;
  // φ' keeps its signs on each side of the kink: bisect on them to adjacent doubles
  for (int i = 0; i < 64; ++i) {
    const double m = 0.5 * (a + b);
    if (!(m > a && m < b)) break;
    const Slope sm = slope_at(formulas, p, m);
    if (!std::isfinite(sm.g)) return false;
    if (sm.g <= 0.0)
      a = m, sa = sm;
    else
      b = m, sb = sm;
  }
  t = sa.phi <= sb.phi ? a : b;
  return true;
}

}  // namespace footpoint::curve
