#include "mesh/equidistribution.hpp"

#include <algorithm>
#include <cstddef>

namespace footpoint {

namespace {

constexpr double kLengthShare = 0.45, kTurnShare = 0.45;

}  // namespace

Measure total(const std::vector<FineInterval>& fine) {
  Measure m;
  for (const FineInterval& f : fine) {
    m.length += f.length;
    m.turn += f.turn;
  }
  return m;
}

std::vector<double> equidistributed_lines(double lo, double hi, const std::vector<FineInterval>& fine,
                                          int n) {
  const Measure sum = total(fine);
  const std::size_t count = fine.size();
  // Without a turn (a flat piece) its share goes to length; without a length (nothing finite)
  // everything goes by parameter.
  const bool turns = sum.turn > kNoTurn;
  const double length_share = sum.length > 0.0 ? (turns ? kLengthShare : kLengthShare + kTurnShare) : 0.0;
  const double turn_share = sum.length > 0.0 && turns ? kTurnShare : 0.0;
  const double parameter_share = 1.0 - length_share - turn_share;
  std::vector<double> cumulative(count + 1, 0.0);
  for (std::size_t k = 0; k < count; ++k) {
    double w = parameter_share / static_cast<double>(count);
    if (length_share > 0.0) w += length_share * fine[k].length / sum.length;
    if (turn_share > 0.0) w += turn_share * fine[k].turn / sum.turn;
    cumulative[k + 1] = cumulative[k] + w;
  }
  std::vector<double> lines(static_cast<std::size_t>(n) + 1);
  lines.front() = lo;
  lines.back() = hi;
  const double step = (hi - lo) / static_cast<double>(count);
  std::size_t k = 0;
  for (int i = 1; i < n; ++i) {
    const double target = cumulative[count] * static_cast<double>(i) / static_cast<double>(n);
    while (k + 1 < count && cumulative[k + 1] <= target) ++k;
    const double w = cumulative[k + 1] - cumulative[k];  // > 0: every interval has a parameter part
    const double within = std::clamp((target - cumulative[k]) / w, 0.0, 1.0);
    lines[static_cast<std::size_t>(i)] = lo + (static_cast<double>(k) + within) * step;
  }
  return lines;
}

}  // namespace footpoint
