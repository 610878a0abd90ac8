// Program::square_free (formula/square_free.cpp): a formula with a repeated factor becomes the
// product of its distinct factors, compared at random points with the square-free product
// written out by hand and compiled on its own (an independent tape); a formula without one keeps
// its tape; the reduced formula is undefined exactly where the written one is.
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
