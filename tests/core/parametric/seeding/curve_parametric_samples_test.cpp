// parametric/seeding/curve_parametric_samples: the adaptive samples of a parametric curve, against
// what the bisection rule gives in closed form. A segment of length 1 (bounding box diagonal 1,
// chord bound 1/256) ends as the 64 coarse intervals halved twice: 257 samples at t = k/256. On the
// unit circle every pair of neighbours is within the chord bound, each sample is (cos t, sin t) at
// its parameter, and `spacing` bounds the arc Δt between neighbours. Where the formulas are finite
// on a part of the domain only (√t on [-1, 1]) the samples cover that part, from its end t = 0.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "formula/program.hpp"
#include "geometry/compile_budget.hpp"
#include "parametric/geometry/parametric_curve.hpp"
#include "parametric/seeding/curve_parametric_samples.hpp"

using namespace footpoint;

namespace {

CurveFormulas sampled_curve(const std::string& x, const std::string& y) {
  return CurveFormulas(formula::Program::compile({{"x", x}, {"y", y}}, {"t"}, {}));
}

// The samples form one chain from the first to the last, in increasing t, ends marked.
void check_one_chain(const CurveSamples& s) {
  const auto n = static_cast<std::int32_t>(s.points.size());
  REQUIRE(n >= 2);
  CHECK(s.prev[0] == -1);
  CHECK(s.next[static_cast<std::size_t>(n) - 1] == -1);
  CHECK(s.kind.front() == SampleKind::endpoint);
  CHECK(s.kind.back() == SampleKind::endpoint);
  for (std::int32_t k = 0; k + 1 < n; ++k) {
    CHECK(s.next[static_cast<std::size_t>(k)] == k + 1);
    CHECK(s.prev[static_cast<std::size_t>(k) + 1] == k);
    CHECK(s.params[static_cast<std::size_t>(k)] < s.params[static_cast<std::size_t>(k) + 1]);
  }
}

}  // namespace

TEST_CASE("parametric samples: a unit segment is halved to the chord bound 1/256") {
  CompileBudget sampling_budget;
  const CurveSamples s = sample_parametric_curve(sampled_curve("t", "0"), {0.0, 1.0}, sampling_budget);
  REQUIRE(s.points.size() == 257);
  check_one_chain(s);
  for (std::size_t k = 0; k < s.points.size(); ++k) {
    CHECK(s.params[k] == static_cast<double>(k) / 256.0);
    CHECK(s.points[k].x == s.params[k]);
    CHECK(s.points[k].y == 0.0);
  }
  // Neighbours are 1/256 apart; the arc bound adds 1 % and 1/cos(0.15) to the longest chord.
  CHECK(s.spacing == doctest::Approx(1.01 / 256 / std::cos(0.15)).epsilon(1e-15));
}

TEST_CASE("parametric samples: the unit circle, chords within the bound and arcs within spacing") {
  const double two_pi = 2 * std::numbers::pi;
  CompileBudget sampling_budget;
  const CurveSamples s =
      sample_parametric_curve(sampled_curve("cos(t)", "sin(t)"), {0.0, two_pi}, sampling_budget);
  check_one_chain(s);
  CHECK(s.params.front() == 0.0);
  CHECK(s.params.back() == two_pi);
  // The bounding box of the coarse samples is (nearly) [-1, 1]^2: chords at most 2√2 / 256.
  const double h_max = 2 * std::sqrt(2.0) / 256;
  for (std::size_t k = 0; k < s.points.size(); ++k) {
    CHECK(s.points[k].x == doctest::Approx(std::cos(s.params[k])).epsilon(1e-15));
    CHECK(s.points[k].y == doctest::Approx(std::sin(s.params[k])).epsilon(1e-15));
    if (k + 1 == s.points.size()) break;
    const double dt = s.params[k + 1] - s.params[k];
    CHECK(2 * std::sin(dt / 2) <= h_max * (1 + 1e-12));  // the chord of an arc dt
    CHECK(dt <= s.spacing);                              // the arc itself
  }
  // Halving keeps the count near the least the bound allows: 2π / (2 asin(h_max / 2)) ≈ 570.
  CHECK(s.points.size() >= 570);
  CHECK(s.points.size() <= 2 * 570);
}

TEST_CASE("parametric samples: formulas finite on part of the domain are sampled from its end") {
  // √t is finite for t >= 0 only; the coarse sample at t = 0 (the 33rd of 65 on [-1, 1]) starts it.
  CompileBudget sampling_budget;
  const CurveSamples s = sample_parametric_curve(sampled_curve("t", "sqrt(t)"), {-1.0, 1.0}, sampling_budget);
  check_one_chain(s);
  CHECK(s.params.front() == 0.0);
  CHECK(s.params.back() == 1.0);
  for (std::size_t k = 0; k < s.points.size(); ++k)
    CHECK(s.points[k].y == doctest::Approx(std::sqrt(s.params[k])).epsilon(1e-15));
}
