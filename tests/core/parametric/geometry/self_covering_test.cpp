// parametric/geometry/self_covering: the translations δ with s(t + δ) = s(t) that the formulas'
// structure proves, the rectangles they show to add no point, and the parameter copies of a point.
// The references are the shapes' periods worked out by hand:
//  - a torus ((2 + cos v/2) cos u, (2 + cos v/2) sin u, sin v/2) repeats exactly under 2πℤ^2
//    ((cos u, sin u) fixes u mod 2π, (cos v, sin v) fixes v mod 2π): every lattice point
//    lexicographically positive with |δu| < extent_u, |δv| < extent_v is one, shortest first;
//  - a cylinder (cos u, sin u, v) under (2πk, 0) only (z = v moves with any δv != 0);
//  - a sphere (cos u cos v, sin u cos v, sin v) with v in [-π/2, π/2]: (2πk, 0) only (its poles and
//    the reflection (u + π, π - v) are no translations, and v's period 2π exceeds the box);
//  - [GSA] Ex. 1 (u + v, sin u + 2 cos v, sin(u + v)) over [-25, 25]^2: k (2π, -2π), k = 1..7
//    (x = u + v forces δu = -δv, sin u forces δu ∈ 2πℤ, 7·2π < 50 < 8·2π);
//  - a plane, a graph with u/1000 added to a periodic term, a surface constant along v: none.
// Each translation found is checked on the formulas themselves at points of the box.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "parametric/geometry/self_covering.hpp"

using namespace footpoint;

namespace self_covering_test {

constexpr double kPi = std::numbers::pi;
constexpr double kTurn = 2 * kPi;

SurfaceFormulas surface(const std::string& x, const std::string& y, const std::string& z) {
  return SurfaceFormulas(formula::Program::compile({{"x", x}, {"y", y}, {"z", z}}, {"u", "v"}, {}));
}

SurfaceFormulas torus() { return surface("(2+0.5*cos(v))*cos(u)", "(2+0.5*cos(v))*sin(u)", "0.5*sin(v)"); }

// `found` is `expected` in order, each entry to rounding of 2π multiples (1e-12 relative).
void check_translations(const SelfCovering& c, const std::vector<Params<2>>& expected) {
  REQUIRE(c.translations.size() == expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    CAPTURE(i);
    CHECK(c.translations[i][0] == doctest::Approx(expected[i][0]).epsilon(1e-12).scale(1.0));
    CHECK(c.translations[i][1] == doctest::Approx(expected[i][1]).epsilon(1e-12).scale(1.0));
  }
}

// s(t + δ) = s(t) on a 9 x 9 grid of the box wherever t + δ is in the box: the rounding of the
// arguments (a few ulps of |t| <= 50 times |s'| <= 3) is far below 1e-12.
void check_invariance(const SurfaceFormulas& f, const ParamBox& box, const SelfCovering& c) {
  for (const Params<2>& d : c.translations) {
    CHECK((d[0] > 0.0 || (d[0] == 0.0 && d[1] > 0.0)));  // lexicographically positive
    int inside = 0;
    for (int i = 0; i <= 8; ++i) {
      for (int j = 0; j <= 8; ++j) {
        const double u = box.umin + (box.umax - box.umin) * i / 8,
                     v = box.vmin + (box.vmax - box.vmin) * j / 8;
        if (!box.contains(u + d[0], v + d[1])) continue;
        ++inside;
        CHECK(norm(f.point(u + d[0], v + d[1]) - f.point(u, v)) <= 1e-12);
      }
    }
    CHECK(inside > 0);  // each translation fits in the box: some t + δ is in it
  }
  for (std::size_t i = 1; i < c.translations.size(); ++i)  // shortest first
    CHECK(std::hypot(c.translations[i - 1][0], c.translations[i - 1][1]) <=
          std::hypot(c.translations[i][0], c.translations[i][1]) * (1.0 + 1e-15));
}

TEST_CASE(
    "self_covering: a torus over more than a period each way repeats under every 2πℤ^2 point in reach") {
  // extents 4π + 1 and 2π + 1: δu ∈ {0, 2π, 4π}, δv ∈ {-2π, 0, 2π}, lexicographically positive,
  // shortest first and ties in lexicographic order
  const ParamBox box{0, 2 * kTurn + 1, 0, kTurn + 1};
  const SurfaceFormulas f = torus();
  const SelfCovering c = detect_self_covering(f, box);
  check_translations(c, {{0, kTurn},
                         {kTurn, 0},
                         {kTurn, -kTurn},
                         {kTurn, kTurn},
                         {2 * kTurn, 0},
                         {2 * kTurn, -kTurn},
                         {2 * kTurn, kTurn}});
  check_invariance(f, box, c);
  // within one period each way nothing repeats inside the box
  CHECK(detect_self_covering(f, {0, 6, 0, 6}).translations.empty());
}

TEST_CASE("self_covering: a cylinder and a sphere repeat along u only, by whole turns") {
  const SurfaceFormulas cylinder = surface("cos(u)", "sin(u)", "v");
  const ParamBox cbox{-kPi, 4 * kPi, 0, 20};  // extent 5π: 2π and 4π fit, any δv moves z
  const SelfCovering c = detect_self_covering(cylinder, cbox);
  check_translations(c, {{kTurn, 0}, {2 * kTurn, 0}});
  check_invariance(cylinder, cbox, c);

  const SurfaceFormulas sphere = surface("cos(u)*cos(v)", "sin(u)*cos(v)", "sin(v)");
  const ParamBox sbox{-kPi, 3 * kPi, -kPi / 2, kPi / 2};  // extent 4π: 2π fits; v's π does not hold 2π
  const SelfCovering s = detect_self_covering(sphere, sbox);
  check_translations(s, {{kTurn, 0}});
  check_invariance(sphere, sbox, s);
}

TEST_CASE("self_covering: [GSA] Ex. 1 over [-25, 25]^2 repeats under k (2π, -2π), k = 1..7") {
  const SurfaceFormulas f = surface("u+v", "sin(u)+2*cos(v)", "sin(u+v)");
  const ParamBox box{-25, 25, -25, 25};
  const SelfCovering c = detect_self_covering(f, box);
  std::vector<Params<2>> expected;
  for (int k = 1; k <= 7; ++k) expected.push_back({k * kTurn, -k * kTurn});
  check_translations(c, expected);
  check_invariance(f, box, c);
}

TEST_CASE("self_covering: no translation on surfaces that do not repeat") {
  const ParamBox box{-25, 25, -25, 25};
  CHECK(detect_self_covering(surface("u", "v", "u*v"), box).translations.empty());
  // the periodic part repeats, u/1000 does not
  CHECK(detect_self_covering(surface("u+v", "sin(u)+2*cos(v)", "sin(u+v)+u/1000"), box).translations.empty());
  CHECK(detect_self_covering(surface("exp(u)", "v^3", "sin(u)*v"), box).translations.empty());
  // constant along v: every δ = (0, δv) leaves s unchanged, a continuum, no lattice to report
  CHECK(detect_self_covering(surface("cos(u)", "sin(u)", "1"), box).translations.empty());
}

TEST_CASE("self_covering: covered rectangles are translates of the box; the rest still shows every point") {
  // Ex. 1 over [-25, 25]^2: box + kδ ∩ box shrinks with k, so a rectangle is covered exactly when it
  // lies in box + (2π, -2π) = [-25 + 2π, 25 + 2π] x [-25 - 2π, 25 - 2π]. Of the 50 x 50 unit
  // squares [u0, u0 + 1] x [v0, v0 + 1] those are u0 >= -25 + 2π (u0 >= -18) and v0 + 1 <= 25 - 2π
  // (v0 <= 17): 43 x 43 = 1849, the uncovered rest an L-shaped strip along u = -25 and v = 25.
  const SurfaceFormulas f = surface("u+v", "sin(u)+2*cos(v)", "sin(u+v)");
  const ParamBox box{-25, 25, -25, 25};
  const SelfCovering c = detect_self_covering(f, box);
  REQUIRE(c.translations.size() == 7);
  const auto square_covered = [&](double u, double v) {
    const double u0 = std::floor(u), v0 = std::floor(v);
    return c.covered(box, u0, u0 + 1, v0, v0 + 1);
  };
  int covered = 0;
  for (int i = -25; i < 25; ++i) {
    for (int j = -25; j < 25; ++j) {
      const bool expected = i >= -18 && j <= 17;
      CHECK(c.covered(box, i, i + 1, j, j + 1) == expected);
      covered += expected;
    }
  }
  CHECK(covered == 1849);
  // The header's argument, replayed: from a point of a covered square, step down by a translation
  // that maps the square back into the box until the square is not covered; the point reached is
  // in the box and gives the same point of the surface.
  for (int i = 0; i < 40; ++i) {
    for (int j = 0; j < 40; ++j) {
      const double u0 = -24.9 + 49.8 * (i + 0.5) / 40, v0 = -24.9 + 49.8 * (j + 0.5) / 40;
      double u = u0, v = v0;
      int steps = 0;
      while (square_covered(u, v) && steps < 20) {
        const double su = std::floor(u), sv = std::floor(v);
        const auto d = std::find_if(c.translations.begin(), c.translations.end(), [&](const Params<2>& t) {
          return box.contains(su - t[0], sv - t[1]) && box.contains(su + 1 - t[0], sv + 1 - t[1]);
        });
        REQUIRE(d != c.translations.end());  // covered: some translate holds the square
        u -= (*d)[0];
        v -= (*d)[1];
        ++steps;
      }
      CHECK(steps < 20);
      CHECK(box.contains(u, v));
      CHECK(norm(f.point(u, v) - f.point(u0, v0)) <= 1e-12);
    }
  }
  // A rectangle reaching past box + δ (below u = -25 + 2π) is not covered, nor one that only
  // touches box + δ's edge v = 25 - 2π from inside (the margin).
  CHECK_FALSE(c.covered(box, -19, 0, 0, 1));
  CHECK(c.covered(box, -18, 0, 0, 1));
  CHECK_FALSE(c.covered(box, 0, 1, 0, 25 - kTurn));
  // no translation: nothing covered
  CHECK_FALSE(SelfCovering{}.covered(box, 0, 1, 0, 1));
}

TEST_CASE("self_covering: the copies of a point are its translates in the box, each once, sorted") {
  // torus over [0, 4π] x [-1/2, 2π + 1/2]: translations (0, 2π), (2π, -2π), (2π, 0), (2π, 2π)
  // (4π does not fit: |δu| < 4π is asked)
  const SurfaceFormulas f = torus();
  const ParamBox box{0, 2 * kTurn, -0.5, kTurn + 0.5};
  const SelfCovering c = detect_self_covering(f, box);
  REQUIRE(c.translations.size() == 4);
  const auto near = [](const Params<2>& a, const Params<2>& b) {
    return std::abs(a[0] - b[0]) <= 1e-12 && std::abs(a[1] - b[1]) <= 1e-12;
  };
  const auto check_copies = [&](const std::vector<Params<2>>& got, const std::vector<Params<2>>& expected) {
    REQUIRE(got.size() == expected.size());
    for (std::size_t i = 0; i < got.size(); ++i) {
      CAPTURE(i);
      CHECK(near(got[i], expected[i]));
      CHECK(box.contains(got[i][0], got[i][1]));
      CHECK(norm(f.point(got[i][0], got[i][1]) - f.point(expected[0][0], expected[0][1])) <= 1e-12);
    }
    CHECK(std::is_sorted(got.begin(), got.end()));
  };
  bool truncated = true;
  // u in {1, 1 + 2π}, v in {0.2, 0.2 + 2π}; the seed's own translate given as a second seed adds nothing
  check_copies(c.copies(box, {{1.0, 0.2}, {1.0 + kTurn, 0.2}}, 64, &truncated),
               {{1.0, 0.2}, {1.0, 0.2 + kTurn}, {1.0 + kTurn, 0.2}, {1.0 + kTurn, 0.2 + kTurn}});
  CHECK_FALSE(truncated);
  // on the edge: u in {0, 2π, 4π} (4π = 2π + 2π exactly), v in {0, 2π}
  check_copies(c.copies(box, {{0.0, 0.0}}, 64, &truncated),
               {{0, 0}, {0, kTurn}, {kTurn, 0}, {kTurn, kTurn}, {2 * kTurn, 0}, {2 * kTurn, kTurn}});
  CHECK_FALSE(truncated);
  // the cap: at most 3, and said so
  const std::vector<Params<2>> capped = c.copies(box, {{0.0, 0.0}}, 3, &truncated);
  CHECK(capped.size() == 3);
  CHECK(truncated);
  // a box whose far edge 1 + 4π is not 1 + 2π + 2π in doubles: the copy within rounding of the edge
  // is moved onto it, every copy in the box
  const ParamBox shifted{1.0, 1.0 + 2 * kTurn, -0.5, kTurn + 0.5};
  const SelfCovering cs = detect_self_covering(f, shifted);
  const std::vector<Params<2>> edge = cs.copies(shifted, {{1.0, 1.0}}, 64, &truncated);
  CHECK(edge.size() == 3);  // u in {1, 1 + 2π, 1 + 4π}; 1 + 2π exceeds v's reach
  for (const Params<2>& t : edge) CHECK(shifted.contains(t[0], t[1]));
  CHECK(edge.back()[0] == doctest::Approx(1.0 + 2 * kTurn).epsilon(1e-15));
  // nothing repeats: the seeds alone
  CHECK(SelfCovering{}.copies(box, {{3.0, 1.0}}, 64, &truncated).size() == 1);
}

}  // namespace self_covering_test
