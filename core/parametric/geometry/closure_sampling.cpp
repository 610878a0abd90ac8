#include "parametric/geometry/closure_sampling.hpp"

#include <charconv>

namespace footpoint::closure_sampling {

std::vector<double> samples(double lo, double hi) {
  constexpr double kOffset = 0.3819660112501051;  // (3 - √5) / 2
  std::vector<double> t;
  t.reserve(kSamples);
  t.push_back(lo);
  for (int k = 0; k < kInside; ++k) t.push_back(lo + (hi - lo) * ((k + kOffset) / kInside));
  t.push_back(hi);
  return t;
}

std::string format(double x) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, x, std::chars_format::general, 3);
  return std::string(buf, r.ptr);
}

}  // namespace footpoint::closure_sampling
