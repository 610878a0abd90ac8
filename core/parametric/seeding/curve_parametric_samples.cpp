#include "parametric/seeding/curve_parametric_samples.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "geometry/compile_budget.hpp"
#include "parametric/geometry/parametric_curve.hpp"

namespace footpoint {
namespace {

double turn(Vec3 a, Vec3 b) {
  // a stationary point, or an infinite tangent (sqrt(t) at 0): judged by the chord
  if (norm2(a) == 0.0 || norm2(b) == 0.0 || !is_finite(a) || !is_finite(b)) return 0.0;
  return std::atan2(norm(cross(a, b)), dot(a, b));
}

struct Node {
  double t;
  CurveJet j;
  bool finite() const { return is_finite(j.c); }
};

// A sample and whether the curve runs on from the sample before it (no point where the formulas
// are not finite was met between them).
struct Emitted {
  Node node;
  bool linked;
};

}  // namespace

CurveSamples sample_parametric_curve(const CurveFormulas& formulas, const ParamInterval& domain,
                                     CompileBudget& budget, const ParametricSampling& settings) {
  const int n0 = settings.initial_intervals;
  std::vector<Node> coarse;
  coarse.reserve(static_cast<std::size_t>(n0) + 1);
  Vec3 lo{}, hi{};
  bool any = false;
  for (int i = 0; i <= n0; ++i) {
    const double t = i == n0 ? domain.tmax : domain.tmin + (domain.tmax - domain.tmin) * i / n0;
    coarse.push_back({t, formulas.jet(t)});
    if (!coarse.back().finite()) continue;  // the box of the part where the formulas are finite
    for (int k = 0; k < 3; ++k) {
      lo[k] = !any ? coarse.back().j.c[k] : std::min(lo[k], coarse.back().j.c[k]);
      hi[k] = !any ? coarse.back().j.c[k] : std::max(hi[k], coarse.back().j.c[k]);
    }
    any = true;
  }
  const double h_max = std::max(norm(hi - lo) * settings.chord_fraction, 1e-300);
  const double min_dt = (domain.tmax - domain.tmin) * settings.min_interval_fraction;

  // Depth-first bisection of each coarse interval, emitting the finite samples in order of t. An
  // interval with one finite end holds an end of the part where the formulas are finite: it is
  // bisected down to neighbouring doubles, so that the part's end is a sample. An interval with
  // no finite end is left (a finite part inside it, between two coarse samples, is not looked for).
  std::vector<Emitted> out;
  auto emit = [&](const Node& node, bool linked) {
    budget.grow(settings.bytes_per_sample);
    out.push_back({node, linked});
  };
  if (coarse.front().finite()) emit(coarse.front(), false);
  std::vector<std::pair<Node, Node>> stack;
  for (int i = 0; i < n0; ++i) {
    stack.push_back({coarse[static_cast<std::size_t>(i)], coarse[static_cast<std::size_t>(i) + 1]});
    while (!stack.empty()) {
      budget.check();
      auto [a, b] = stack.back();
      stack.pop_back();
      const double tm = 0.5 * (a.t + b.t);
      const bool room = tm > a.t && tm < b.t && out.size() + stack.size() < settings.max_samples;
      if (!a.finite() || !b.finite()) {
        if (!a.finite() && !b.finite()) continue;
        if (!room) {
          if (b.finite()) emit(b, false);  // the part starts at b
          continue;
        }
        const Node m{tm, formulas.jet(tm)};
        if (!m.finite()) {  // the end lies on the finite end's side
          stack.push_back(a.finite() ? std::pair{a, m} : std::pair{m, b});
          continue;
        }
        stack.push_back({m, b});  // the right half is processed after the left
        stack.push_back({a, m});
        continue;
      }
      const Node m{tm, formulas.jet(tm)};
      const double chord = norm(b.j.c - a.j.c);
      const bool fine = m.finite() && chord <= h_max && turn(a.j.d1, m.j.d1) <= settings.max_turn &&
                        turn(m.j.d1, b.j.d1) <= settings.max_turn && norm(m.j.c - a.j.c) <= h_max &&
                        norm(b.j.c - m.j.c) <= h_max;
      if (((fine || b.t - a.t <= min_dt) && m.finite()) || !room) {
        emit(b, true);
        continue;
      }
      stack.push_back({m, b});
      stack.push_back({a, m});
    }
  }

  CurveSamples s;
  s.points.reserve(out.size());
  s.params.reserve(out.size());
  double longest = 0.0;
  for (std::size_t i = 0; i < out.size(); ++i) {
    // the domain's ends, and the ends of each part where the formulas are finite
    const bool end = !out[i].linked || i + 1 == out.size() || !out[i + 1].linked;
    const std::int32_t k = s.add(out[i].node.j.c, end ? SampleKind::endpoint : SampleKind::regular);
    s.params.push_back(out[i].node.t);
    if (out[i].linked) {
      s.link(k - 1, k);
      longest = std::max(longest, norm(out[i].node.j.c - out[i - 1].node.j.c));
    }
  }
  // The arc between neighbours: at most chord / cos(max_turn) for tangents turning at most
  // max_turn from the chord direction; 1 % more for rounding.
  s.spacing = 1.01 * longest / std::cos(settings.max_turn);
  return s;
}

}  // namespace footpoint
