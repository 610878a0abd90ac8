// mesh/equidistribution: the grid lines that give each cell an equal share of de Boor's measure
// (45 % chord length, 45 % turn, 10 % parameter; a flat piece 90 % length), against lines worked
// out by hand from that rule on fine grids of four intervals, and the properties every grid must
// have (ends exact, strictly increasing, nearest where the geometry bends).
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "mesh/equidistribution.hpp"

using footpoint::FineInterval;

namespace {

std::vector<FineInterval> equidistribution_fine(const std::vector<double>& lengths,
                                                const std::vector<double>& turns) {
  std::vector<FineInterval> fine(lengths.size());
  for (std::size_t k = 0; k < lengths.size(); ++k) fine[k] = {lengths[k], turns[k]};
  return fine;
}

}  // namespace

TEST_CASE("equidistribution: the totals and the angle between directions") {
  const footpoint::Measure m = footpoint::total(equidistribution_fine({1, 2, 3.5}, {0.25, 0, 1}));
  CHECK(m.length == 6.5);
  CHECK(m.turn == 1.25);
  using footpoint::turn_angle;
  CHECK(turn_angle({1, 0, 0}, {1, 0, 0}) == 0.0);
  CHECK(turn_angle({1, 0, 0}, {0, 2, 0}) == doctest::Approx(M_PI / 2).epsilon(1e-15));
  CHECK(turn_angle({1, 0, 0}, {-3, 0, 0}) == doctest::Approx(M_PI).epsilon(1e-15));
  // Near 0 the atan2 form keeps the small angle that acos(dot) would round to 0.
  CHECK(turn_angle({1, 0, 0}, {1, 1e-12, 0}) == doctest::Approx(1e-12).epsilon(1e-12));
  CHECK(turn_angle({0, 0, 0}, {1, 0, 0}) == 0.0);
  CHECK(turn_angle({NAN, 0, 0}, {1, 0, 0}) == 0.0);
}

TEST_CASE("equidistribution: a uniform measure gives a uniform grid") {
  const auto lines =
      footpoint::equidistributed_lines(2.0, 6.0, equidistribution_fine({1, 1, 1, 1}, {0, 0, 0, 0}), 4);
  REQUIRE(lines.size() == 5);
  for (int i = 0; i <= 4; ++i)
    CHECK(lines[static_cast<std::size_t>(i)] == doctest::Approx(2.0 + i).epsilon(1e-15));
  // Equal turns as well: still uniform.
  const auto turned =
      footpoint::equidistributed_lines(0.0, 1.0, equidistribution_fine({1, 1, 1, 1}, {1, 1, 1, 1}), 8);
  for (int i = 0; i <= 8; ++i)
    CHECK(turned[static_cast<std::size_t>(i)] == doctest::Approx(i / 8.0).epsilon(1e-15));
}

TEST_CASE("equidistribution: a flat piece goes 90 % by length, 10 % by parameter") {
  // Densities 0.9 * {3, 1, 0, 0} / 4 + 0.1 / 4 = {0.7, 0.25, 0.025, 0.025}: half the measure lies
  // at 0.5 / 0.7 of the first fine interval, three quarters at 0.05 / 0.25 of the second.
  const auto lines =
      footpoint::equidistributed_lines(0.0, 4.0, equidistribution_fine({3, 1, 0, 0}, {0, 0, 0, 0}), 4);
  REQUIRE(lines.size() == 5);
  CHECK(lines[0] == 0.0);
  CHECK(lines[1] == doctest::Approx(0.25 / 0.7).epsilon(1e-14));
  CHECK(lines[2] == doctest::Approx(0.5 / 0.7).epsilon(1e-14));
  CHECK(lines[3] == doctest::Approx(1.0 + 0.05 / 0.25).epsilon(1e-14));
  CHECK(lines[4] == 4.0);
}

TEST_CASE("equidistribution: turns draw the lines to where the geometry bends") {
  // Densities 0.45 / 4 + 0.45 * {0, 0, 0, 1} + 0.1 / 4 = {0.1375, 0.1375, 0.1375, 0.5875}: half the
  // measure lies at (0.5 - 0.4125) / 0.5875 of the last fine interval.
  const auto half =
      footpoint::equidistributed_lines(0.0, 4.0, equidistribution_fine({1, 1, 1, 1}, {0, 0, 0, 2}), 2);
  REQUIRE(half.size() == 3);
  CHECK(half[1] == doctest::Approx(3.0 + 0.0875 / 0.5875).epsilon(1e-14));
  // A turn below kNoTurn is the rounding of a flat piece's normals: ignored, the grid is uniform.
  const auto flat =
      footpoint::equidistributed_lines(0.0, 4.0, equidistribution_fine({1, 1, 1, 1}, {0, 0, 0, 1e-9}), 2);
  CHECK(flat[1] == doctest::Approx(2.0).epsilon(1e-15));
}

TEST_CASE("equidistribution: nothing finite goes by parameter, and every grid increases strictly") {
  // No length anywhere (formulas not finite): the whole measure by parameter, uniform lines.
  const auto none =
      footpoint::equidistributed_lines(-1.0, 1.0, equidistribution_fine({0, 0, 0, 0}, {0, 0, 0, 0}), 4);
  for (int i = 0; i <= 4; ++i)
    CHECK(none[static_cast<std::size_t>(i)] == doctest::Approx(-1.0 + 0.5 * i).epsilon(1e-15));
  // A measure concentrated in one fine interval of a hundred still leaves no cell empty, and no
  // cell longer than the parameter share alone allows (10 % of the measure per 100 % of [lo, hi]).
  std::vector<double> lengths(100, 0.0), turns(100, 0.0);
  lengths[37] = 1.0;
  turns[37] = 3.0;
  const int n = 20;
  const auto lines = footpoint::equidistributed_lines(0.0, 1.0, equidistribution_fine(lengths, turns), n);
  REQUIRE(lines.size() == static_cast<std::size_t>(n) + 1);
  CHECK(lines.front() == 0.0);
  CHECK(lines.back() == 1.0);
  for (int i = 0; i < n; ++i) {
    const double cell = lines[static_cast<std::size_t>(i) + 1] - lines[static_cast<std::size_t>(i)];
    CHECK(cell > 0.0);
    // Each cell holds 1/n of the measure; parameter alone gives 0.1 per unit: cell <= (1/n) / 0.1.
    CHECK(cell <= (1.0 / n) / 0.1 + 1e-12);
  }
  // 90 % of the measure sits in [0.37, 0.38]: so do the lines 1..18 (the 10 % of parameter puts
  // 0.037 of the measure before the interval, below one cell's 0.05, and 0.062 after it).
  for (int i = 1; i <= 18; ++i) {
    CHECK(lines[static_cast<std::size_t>(i)] >= 0.37);
    CHECK(lines[static_cast<std::size_t>(i)] <= 0.38);
  }
}
