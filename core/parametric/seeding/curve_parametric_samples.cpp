#include "parametric/seeding/curve_parametric_samples.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "geometry/compile_budget.hpp"
#include "parametric/geometry/parametric_curve.hpp"

namespace footpoint {
namespace {

double turn(Vec3 a, Vec3 b) {
  if (norm2(a) == 0.0 || norm2(b) == 0.0) return 0.0;  // a stationary point: judged by the chord
  return std::atan2(norm(cross(a, b)), dot(a, b));
}

struct Node {
  double t;
  CurveJet j;
};

}  // namespace

CurveSamples sample_parametric_curve(const CurveFormulas& formulas, const ParamInterval& domain,
                                     const ParametricSampling& settings) {
  const int n0 = settings.initial_intervals;
  std::vector<Node> coarse;
  coarse.reserve(static_cast<std::size_t>(n0) + 1);
  Vec3 lo{}, hi{};
  for (int i = 0; i <= n0; ++i) {
    const double t = i == n0 ? domain.tmax : domain.tmin + (domain.tmax - domain.tmin) * i / n0;
    coarse.push_back({t, formulas.jet(t)});
    for (int k = 0; k < 3; ++k) {
      lo[k] = i == 0 ? coarse.back().j.c[k] : std::min(lo[k], coarse.back().j.c[k]);
      hi[k] = i == 0 ? coarse.back().j.c[k] : std::max(hi[k], coarse.back().j.c[k]);
    }
  }
  const double h_max = std::max(norm(hi - lo) * settings.chord_fraction, 1e-300);
  const double min_dt = (domain.tmax - domain.tmin) * settings.min_interval_fraction;

  // Depth-first bisection of each coarse interval, emitting samples in order of t.
  std::vector<Node> out;
  out.push_back(coarse.front());
  std::vector<std::pair<Node, Node>> stack;
  double longest = 0.0;
  for (int i = 0; i < n0; ++i) {
    stack.push_back({coarse[static_cast<std::size_t>(i)], coarse[static_cast<std::size_t>(i) + 1]});
    while (!stack.empty()) {
      CompileBudget::check();
      auto [a, b] = stack.back();
      stack.pop_back();
      const double tm = 0.5 * (a.t + b.t);
      const Node m{tm, formulas.jet(tm)};
      const double chord = norm(b.j.c - a.j.c);
      const bool fine = chord <= h_max && turn(a.j.d1, m.j.d1) <= settings.max_turn &&
                        turn(m.j.d1, b.j.d1) <= settings.max_turn && norm(m.j.c - a.j.c) <= h_max &&
                        norm(b.j.c - m.j.c) <= h_max;
      if (fine || b.t - a.t <= min_dt || out.size() + stack.size() >= settings.max_samples) {
        out.push_back(b);
        longest = std::max(longest, chord);
        continue;
      }
      stack.push_back({m, b});  // the right half is processed after the left
      stack.push_back({a, m});
    }
  }

  CurveSamples s;
  s.points.reserve(out.size());
  s.params.reserve(out.size());
  for (std::size_t i = 0; i < out.size(); ++i) {
    const bool end = i == 0 || i + 1 == out.size();
    const std::int32_t k = s.add(out[i].j.c, end ? SampleKind::endpoint : SampleKind::regular);
    s.params.push_back(out[i].t);
    if (i > 0) s.link(k - 1, k);
  }
  // The arc between neighbours: at most chord / cos(max_turn) for tangents turning at most
  // max_turn from the chord direction; 1 % more for rounding.
  s.spacing = 1.01 * longest / std::cos(settings.max_turn);
  return s;
}

}  // namespace footpoint
