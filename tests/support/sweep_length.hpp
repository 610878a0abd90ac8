// The number of random points a statistical sweep visits. Under AddressSanitizer (scripts/
// sanitize.sh) every test runs 5-10x slower; there the sweeps look for memory errors and undefined
// behaviour on a sixth of their points, and the Release run (scripts/test.sh) checks the
// statistics on all of them.
#pragma once

#include <algorithm>

namespace footpoint::test {

#if defined(__SANITIZE_ADDRESS__)
inline constexpr int kSweepDivisor = 6;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
inline constexpr int kSweepDivisor = 6;
#else
inline constexpr int kSweepDivisor = 1;
#endif
#else
inline constexpr int kSweepDivisor = 1;
#endif

// n points in Release, n / kSweepDivisor (at least `least`) under AddressSanitizer.
constexpr int sweep_length(int n, int least = 8) { return std::max(std::min(n, least), n / kSweepDivisor); }

}  // namespace footpoint::test
