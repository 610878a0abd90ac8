// Timing for the benchmarks: the thread's CPU time (the machine is shared: wall time would include
// descheduling), the timer's own overhead (subtracted from every per-point time), quantiles of
// the per-point times, and the load average printed beside them.
#pragma once

#include <algorithm>
#include <cmath>
#include <ctime>
#include <fstream>
#include <string>
#include <vector>

namespace footpoint::bench {

inline double thread_cpu_ns() {
  timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) * 1e9 + static_cast<double>(ts.tv_nsec);
}

// Median back-to-back delta of the CPU clock.
inline double timer_overhead_ns() {
  std::vector<double> d;
  for (int i = 0; i < 2001; ++i) {
    const double a = thread_cpu_ns(), b = thread_cpu_ns();
    d.push_back(b - a);
  }
  std::nth_element(d.begin(), d.begin() + 1000, d.end());
  return d[1000];
}

// The q-quantile (0 <= q <= 1) of v, the nearest rank.
inline double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  const auto k = static_cast<std::size_t>(std::lround(q * static_cast<double>(v.size() - 1)));
  std::nth_element(v.begin(), v.begin() + static_cast<long>(k), v.end());
  return v[k];
}

// "load average 1.00 0.50 0.25" (/proc/loadavg): how busy the machine was during a measurement.
inline std::string load_average() {
  std::ifstream in("/proc/loadavg");
  std::string a, b, c;
  in >> a >> b >> c;
  return "load average " + a + " " + b + " " + c;
}

}  // namespace footpoint::bench
