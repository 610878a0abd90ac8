// Program::invariant_translations against translations worked out by hand from the formulas'
// periods, and every translation it reports checked by evaluation: f(x + δ) = f(x) to rounding at
// points spread over the extents.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "formula/program.hpp"

using footpoint::formula::Program;

namespace {

constexpr double kPi = std::numbers::pi;

Program compile(const std::vector<std::string>& formulas, const std::vector<std::string>& vars = {"u", "v"}) {
  std::vector<footpoint::formula::NamedFormula> named;
  for (std::size_t i = 0; i < formulas.size(); ++i)
    named.push_back({std::string(1, static_cast<char>('a' + i)), formulas[i]});
  return Program::compile(named, vars, {});
}

// Every reported δ leaves every formula unchanged at 200 points of [-extent, extent]^n (to 1e-12
// of the values' size: evaluating sin at 50 loses a few ulps of 50).
void check_invariant(const Program& p, const std::vector<std::vector<double>>& translations,
                     const std::vector<double>& extent) {
  const int n = p.num_inputs();
  std::vector<double> x(static_cast<std::size_t>(n)), y(x.size());
  std::vector<double> fx(static_cast<std::size_t>(p.num_outputs())), fy(fx.size());
  for (const auto& d : translations)
    for (int k = 0; k < 200; ++k) {
      for (int i = 0; i < n; ++i) {
        const double e = extent[static_cast<std::size_t>(i)];
        x[static_cast<std::size_t>(i)] = -e + 2.0 * e * std::fmod(0.618034 * (k + 1) * (i + 1.7), 1.0);
        y[static_cast<std::size_t>(i)] = x[static_cast<std::size_t>(i)] + d[static_cast<std::size_t>(i)];
      }
      p.values(x.data(), fx.data());
      p.values(y.data(), fy.data());
      for (std::size_t o = 0; o < fx.size(); ++o)
        CHECK(std::abs(fx[o] - fy[o]) <= 1e-12 * (1.0 + std::abs(fx[o])));
    }
}

void check_equal(const std::vector<std::vector<double>>& got, const std::vector<std::vector<double>>& want) {
  REQUIRE(got.size() == want.size());
  for (std::size_t i = 0; i < got.size(); ++i)
    for (std::size_t k = 0; k < want[i].size(); ++k)
      CHECK(got[i][k] == doctest::Approx(want[i][k]).epsilon(1e-14));
}

}  // namespace

TEST_CASE("[GSA] Ex. 1 repeats along (2π, -2π) only") {
  // u + v fixes δu + δv = 0; sin u and cos v then need δu ∈ 2πℤ
  const Program p = compile({"u+v", "sin(u)+2*cos(v)", "sin(u+v)"});
  const auto t = p.invariant_translations({50.0, 50.0});
  std::vector<std::vector<double>> want;
  for (int k = 1; k <= 7; ++k) want.push_back({2 * kPi * k, -2 * kPi * k});  // 8·2π > 50
  check_equal(t, want);
  check_invariant(p, t, {25.0, 25.0});
  CHECK(p.invariant_translations({6.0, 6.0}).empty());  // [-3,3]^2 holds no whole period
  CHECK(p.invariant_translations({50.0, 50.0}, 3).size() == 3);
}

TEST_CASE("a torus repeats along both axes; the lattice's shortest vectors come first") {
  const Program p = compile({"(3+cos(v))*cos(u)", "(3+cos(v))*sin(u)", "sin(v)"});
  const auto t = p.invariant_translations({4 * kPi + 1, 2 * kPi + 1});
  // δu ∈ {2π, 4π} (positive), δv ∈ {-2π, 0, 2π}; and (0, 2π)
  REQUIRE(t.size() == 7);
  check_equal({t[0], t[1]}, {{0, 2 * kPi}, {2 * kPi, 0}});
  check_invariant(p, t, {10.0, 10.0});
  CHECK(p.invariant_translations({2 * kPi, 2 * kPi}).empty());  // one period each way: nothing inside
}

TEST_CASE("a lattice that is not the axes' product: sin(u + v), cos(u - v)") {
  const Program p = compile({"sin(u+v)", "cos(u-v)", "1"});
  const auto t = p.invariant_translations({4.0, 4.0});
  // δu + δv ∈ 2πℤ and δu - δv ∈ 2πℤ: (π, ±π)
  check_equal(t, {{kPi, -kPi}, {kPi, kPi}});
  check_invariant(p, t, {4.0, 4.0});
}

TEST_CASE("periods of tan, of half angles, and of a product with an unmoved factor") {
  check_equal(compile({"tan(u)"}, {"u"}).invariant_translations({7.0}), {{kPi}, {2 * kPi}});
  check_equal(compile({"sin(u/2)", "cos(u)"}, {"u"}).invariant_translations({13.0}), {{4 * kPi}});
  // exp(v) must not move: only δv = 0, δu ∈ 2πℤ
  const Program p = compile({"exp(v)*cos(u)", "v", "sin(u)^2"});
  const auto t = p.invariant_translations({13.0, 13.0});
  check_equal(t, {{2 * kPi, 0}, {4 * kPi, 0}});
  check_invariant(p, t, {6.0, 6.0});
  // sin(2u) + cos(3u): the common period 2π
  check_equal(compile({"sin(2*u)+cos(3*u)"}, {"u"}).invariant_translations({7.0}), {{2 * kPi}});
}

TEST_CASE("no translation where none is, or where the rule cannot prove one") {
  const std::vector<double> e{100.0, 100.0};
  CHECK(compile({"sin(u)+u", "cos(v)", "v"}).invariant_translations(e).empty());  // u and v move
  // ... but sin(u) + u, cos(v), 0 repeats in v
  check_equal(compile({"sin(u)+u", "cos(v)", "0"}).invariant_translations({9.0, 9.0}), {{0, 2 * kPi}});
  CHECK(compile({"cos(u)", "sin(v)", "u*v"}).invariant_translations(e).empty());           // u*v moves
  CHECK(compile({"sin(u)+sin(sqrt(2)*u)"}, {"u"}).invariant_translations({1e4}).empty());  // incommensurable
  CHECK(compile({"abs(sin(u))", "v", "0"}).invariant_translations(e).size() == 15);  // 2π steps (π unread)
  CHECK(compile({"sin(u)"}, {"u"}).invariant_translations({6.0}).empty());           // shorter than 2π
  // constant along a direction: a continuous symmetry, no lattice
  CHECK(compile({"cos(u+v)", "sin(u+v)", "u+v"}).invariant_translations(e).empty());
  CHECK(compile({"cos(u)", "sin(u)", "1"}).invariant_translations(e).empty());
  // three inputs are beyond the rule's reach
  CHECK(compile({"sin(x)", "sin(y)", "sin(z)"}, {"x", "y", "z"})
            .invariant_translations({9.0, 9.0, 9.0})
            .empty());
}
