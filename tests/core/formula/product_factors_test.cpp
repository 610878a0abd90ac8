// The factors of a formula's top-level product (formula/product_factors.cpp).
// Program::square_free: a formula with a repeated factor becomes the product of its distinct
// factors, compared at random points with the square-free product written out by hand and
// compiled on its own (an independent tape); a formula without one keeps its tape; the reduced
// formula is undefined exactly where the written one is.
// Program::factor_systems: each system against the factors written by hand and compiled on their
// own, and the systems' union of zeros against the written formulas' zeros.
#include <doctest/doctest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "formula/program.hpp"

using footpoint::formula::Program;

namespace {

Program compile(const std::vector<std::string>& formulas, int inputs) {
  std::vector<footpoint::formula::NamedFormula> named;
  for (std::size_t i = 0; i < formulas.size(); ++i)
    named.push_back({"equations[" + std::to_string(i) + "]", formulas[i]});
  const std::vector<std::string> all{"x", "y", "z"};
  return Program::compile(named, std::vector<std::string>(all.begin(), all.begin() + inputs), {});
}

// The reduced `written` against `expected` at random points (and their zeros at the same points).
void check_against(const std::vector<std::string>& written, const std::vector<std::string>& expected,
                   int inputs) {
  CAPTURE(written[0]);
  const Program w = compile(written, inputs);
  const Program e = compile(expected, inputs);
  const Program r = w.square_free();
  CHECK_FALSE(r.same_tape(w));
  REQUIRE(r.num_outputs() == e.num_outputs());
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  for (int i = 0; i < 2000; ++i) {
    const double x[3] = {u(rng), u(rng), u(rng)};
    double got[2] = {}, want[2] = {};
    r.values(x, got);
    e.values(x, want);
    for (int k = 0; k < e.num_outputs(); ++k) {
      if (std::isnan(want[k])) {
        CHECK(std::isnan(got[k]));
        continue;
      }
      // The same factors multiplied in possibly another order: a few roundings apart.
      CHECK(std::abs(got[k] - want[k]) <= 1e-14 * std::abs(want[k]) + 1e-300);
    }
  }
}

}  // namespace

TEST_CASE("square_free: repeated factors at the top of a product are taken once") {
  check_against({"(x^2+y^2-1)^2"}, {"x^2+y^2-1"}, 2);
  check_against({"(x^2+y^2-1)*(x^2+y^2-1)"}, {"x^2+y^2-1"}, 2);
  check_against({"-3*(x^2+y^2-1)^3*(y-x)^2/7"}, {"(x^2+y^2-1)*(y-x)"}, 2);
  check_against({"(x-0.5)*(x^2+y^2-1)^2*sin(y)"}, {"(x-0.5)*(x^2+y^2-1)*sin(y)"}, 2);
  check_against({"x^4"}, {"x"}, 2);
  // A product as long as a formula may be: x*x*...*x, 1500 factors.
  std::string chain = "x";
  for (int i = 1; i < 1500; ++i) chain += "*x";
  check_against({chain}, {"x"}, 2);
  // A factor that is not a polynomial keeps its domain: sqrt(x) is undefined for x < 0 both ways.
  check_against({"sqrt(x)^2*(y-1)"}, {"sqrt(x)*(y-1)"}, 2);
  // Spatial: each equation on its own, a square-free one unchanged.
  check_against({"(x^2+y^2+z^2-4)^2", "(x-1)^2+y^2-1"}, {"x^2+y^2+z^2-4", "(x-1)^2+y^2-1"}, 3);
}

TEST_CASE("square_free: formulas without a repeated factor keep their tape") {
  for (const char* f : {"x*y", "2*(x^2+y^2-1)", "(x-1)*(1-x)", "(x^2+y^2-1)^2+y", "x^2+y^2-1",
                        "sqrt(x^2+y^2)-1", "(x-1)^-2", "(x^2+y^2-1)^0.5"}) {
    CAPTURE(f);
    const Program w = compile({f}, 2);
    CHECK(w.square_free().same_tape(w));
  }
}

namespace {

// The factor systems of `written` against `expected` (one system per entry, in order) at random
// points.
void check_systems(const std::vector<std::string>& written,
                   const std::vector<std::vector<std::string>>& expected, int inputs) {
  CAPTURE(written[0]);
  const std::vector<Program> systems = compile(written, inputs).factor_systems(16);
  REQUIRE(systems.size() == expected.size());
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  for (std::size_t s = 0; s < systems.size(); ++s) {
    const Program e = compile(expected[s], inputs);
    REQUIRE(systems[s].num_outputs() == e.num_outputs());
    for (int i = 0; i < 500; ++i) {
      const double x[3] = {u(rng), u(rng), u(rng)};
      double got[2] = {}, want[2] = {};
      systems[s].values(x, got);
      e.values(x, want);
      for (int k = 0; k < e.num_outputs(); ++k) CHECK(got[k] == want[k]);  // the same operations
    }
  }
}

}  // namespace

TEST_CASE("factor_systems: a product of factors defined everywhere splits into its factors") {
  check_systems({"(x^2+y^2-1)*((x-2)^2+y^2-1)"}, {{"x^2+y^2-1"}, {"(x-2)^2+y^2-1"}}, 2);
  // Constants, signs and repeated factors go; each distinct factor once.
  check_systems({"-2*(x-y)^3*(x+y)/5*(x-y)"}, {{"x-y"}, {"x+y"}}, 2);
  check_systems({"x*sin(y)*exp(x)"}, {{"x"}, {"sin(y)"}, {"exp(x)"}}, 2);
  // Spatial: one factor of each equation, every choice (the second equation's factor varies last).
  check_systems({"x*(x-1)", "y*(z+1)"}, {{"x", "y"}, {"x", "z+1"}, {"x-1", "y"}, {"x-1", "z+1"}}, 3);
  check_systems({"(x^2+y^2+z^2-4)*(z-1)", "(x-1)^2+y^2-1"},
                {{"x^2+y^2+z^2-4", "(x-1)^2+y^2-1"}, {"z-1", "(x-1)^2+y^2-1"}}, 3);
}

TEST_CASE("factor_systems: no split where a factor may be undefined, or too many systems") {
  // sqrt(x) is undefined for x < 0, where the product is too: the union would add the line y = 1
  // there. The one system is square_free().
  for (const char* f : {"sqrt(x)*(y-1)", "(x-1)/(y-2)*x", "ln(x^2+1)*y*(y-1)^2", "x^2+y^2-1", "(x-1)^-2*y"}) {
    CAPTURE(f);
    const Program w = compile({f}, 2);
    const std::vector<Program> systems = w.factor_systems(16);
    REQUIRE(systems.size() == 1);
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(-2.0, 2.0);
    const Program r = w.square_free();
    for (int i = 0; i < 200; ++i) {
      const double x[2] = {u(rng), u(rng)};
      double got = 0.0, want = 0.0;
      systems[0].values(x, &got);
      r.values(x, &want);
      CHECK((got == want || (std::isnan(got) && std::isnan(want))));
    }
  }
  CHECK(compile({"x*(x-1)*(x-2)", "y*(y-1)*(y-2)"}, 3).factor_systems(8).size() == 1);
  CHECK(compile({"x*(x-1)*(x-2)", "y*(y-1)*(y-2)"}, 3).factor_systems(9).size() == 9);
  // A formula with more factors than systems allowed stays whole; the other one splits.
  CHECK(compile({"x*(x-1)*(x-2)", "y*(y-1)*(y-2)"}, 3).factor_systems(2).size() == 1);
  const std::vector<Program> one_split = compile({"x*(x-1)*(x-2)", "y*(y-1)"}, 3).factor_systems(2);
  REQUIRE(one_split.size() == 2);
  const double at[3] = {0.5, 0.25, 0.0};
  double f[2] = {};
  one_split[1].values(at, f);
  CHECK(f[0] == 0.5 * -0.5 * -1.5);  // x (x - 1) (x - 2) whole
  CHECK(f[1] == 0.25 - 1.0);         // the second factor of y (y - 1)
}

TEST_CASE("factor_systems: the union of the systems' zeros is the formulas' zero set") {
  // On a grid that holds zeros of every factor (integers and halves): f = 0 exactly where some
  // system's formulas all vanish.
  const std::vector<std::string> written{"x*(x-1)*(y+0.5)^2*(x*x+y*y-1)", "(y-0.5)*(z+1)*z"};
  const Program w = compile(written, 3);
  const std::vector<Program> systems = w.factor_systems(16);
  REQUIRE(systems.size() == 12);
  for (int i = -4; i <= 4; ++i)
    for (int j = -4; j <= 4; ++j)
      for (int k = -4; k <= 4; ++k) {
        const double x[3] = {0.5 * i, 0.5 * j, 0.5 * k};
        double f[2] = {};
        w.values(x, f);
        bool in_union = false;
        for (const Program& s : systems) {
          double g[2] = {};
          s.values(x, g);
          in_union = in_union || (g[0] == 0.0 && g[1] == 0.0);
        }
        CHECK(in_union == (f[0] == 0.0 && f[1] == 0.0));
      }
}
