#include "solvers/auto_result.hpp"

#include <algorithm>

namespace footpoint::curve {

void add_distinct_minimum(std::vector<Minimum>& minima, Vec3 x, double same, const Minimum& m) {
  const bool known = std::any_of(minima.begin(), minima.end(), [&](const Minimum& k) {
    return norm(Vec3{k.foot[0], k.foot[1], k.foot[2]} - x) <= same;
  });
  if (!known) minima.push_back(m);
}

void finish_auto_result(ProjectionResult& r, bool met, int iterations, double step, int starts,
                        const Options& options, std::vector<Minimum> minima,
                        std::vector<std::array<double, 3>> trace) {
  r.summary.iterations = iterations;
  r.summary.step_norm = step;
  r.summary.starts = starts;
  r.summary.status = met ? Status::converged : Status::degenerate;
  if (options.all_minima) {
    std::sort(minima.begin(), minima.end(),
              [](const Minimum& a, const Minimum& b) { return a.distance < b.distance; });
    r.minima = std::move(minima);
    cap_minima(r, options);
  }
  // auto's answer is the global one: farther than max_distance, no point is within it
  if (r.distance > options.max_distance) withhold_answer(r);
  if (options.trace) r.trace = std::move(trace);
}

}  // namespace footpoint::curve
