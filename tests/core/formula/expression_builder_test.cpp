// ExpressionBuilder (core/formula/expression_builder.hpp): formulas written in code become a
// Program evaluated, differentiated and enclosed like a parsed one. Checked against closed-form
// values, gradients and Hessians (exact jets: 1e-12 relative), against the same formula parsed
// from text (the same tape, so the same bits), for the power rule at negative bases, for shared
// subexpressions and folded constants, and for the node budget (FormulaError too_complex).
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "formula/expression_builder.hpp"

using footpoint::formula::ExpressionBuilder;
using footpoint::formula::FormulaError;
using footpoint::formula::Interval;
using footpoint::formula::Jet2;
using footpoint::formula::Program;

namespace expression_builder_test {

// f0 = x y - 3, f1 = (x - y) / (x + 1), f2 = x^3, f3 = y^-2, f4 = 5 - x, f5 = 2 / y.
Program six_formulas() {
  ExpressionBuilder b(2);
  const auto x = b.input(0), y = b.input(1);
  return b.program({b.sub(b.mul(x, y), b.constant(3.0)), b.div(b.sub(x, y), b.add(x, b.constant(1.0))),
                    b.power(x, 3), b.power(y, -2), b.sub(b.constant(5.0), x), b.div(b.constant(2.0), y)});
}

struct Expected {
  double v;
  std::array<double, 2> g;
  std::array<std::array<double, 2>, 2> h;
};

// The closed forms of six_formulas() and their derivatives at (x, y).
std::vector<Expected> six_closed_forms(double x, double y) {
  const double s = x + 1.0;
  return {
      {x * y - 3.0, {y, x}, {{{0.0, 1.0}, {1.0, 0.0}}}},
      {(x - y) / s,
       {(1.0 + y) / (s * s), -1.0 / s},
       {{{-2.0 * (1.0 + y) / (s * s * s), 1.0 / (s * s)}, {1.0 / (s * s), 0.0}}}},
      {x * x * x, {3.0 * x * x, 0.0}, {{{6.0 * x, 0.0}, {0.0, 0.0}}}},
      {1.0 / (y * y), {0.0, -2.0 / (y * y * y)}, {{{0.0, 0.0}, {0.0, 6.0 / (y * y * y * y)}}}},
      {5.0 - x, {-1.0, 0.0}, {{{0.0, 0.0}, {0.0, 0.0}}}},
      {2.0 / y, {0.0, -2.0 / (y * y)}, {{{0.0, 0.0}, {0.0, 4.0 / (y * y * y)}}}},
  };
}

void check_close(double got, double want) {
  CHECK(std::abs(got - want) <= 1e-12 * std::max(1.0, std::abs(want)));
}

}  // namespace expression_builder_test

TEST_CASE("expression builder: values, gradients and Hessians are the closed forms") {
  const Program program = expression_builder_test::six_formulas();
  CHECK(program.num_inputs() == 2);
  CHECK(program.num_outputs() == 6);
  // Negative bases too: x^3 and y^-2 by the power rule, not exp(k ln a).
  for (const std::array<double, 2> at :
       {std::array<double, 2>{0.75, 1.25}, {-1.5, 0.7}, {-2.5, -0.4}, {3.0, -2.0}}) {
    CAPTURE(at[0]);
    CAPTURE(at[1]);
    std::array<double, 6> values{};
    program.values(at.data(), values.data());
    std::array<Jet2<2>, 6> jets{};
    program.jets2<2>(at.data(), jets.data());
    const auto want = expression_builder_test::six_closed_forms(at[0], at[1]);
    for (std::size_t k = 0; k < want.size(); ++k) {
      CAPTURE(k);
      expression_builder_test::check_close(values[k], want[k].v);
      expression_builder_test::check_close(jets[k].v, want[k].v);
      for (std::size_t i = 0; i < 2; ++i) {
        expression_builder_test::check_close(jets[k].g[i], want[k].g[i]);
        for (std::size_t j = 0; j < 2; ++j)
          expression_builder_test::check_close(jets[k].h[i][j], want[k].h[i][j]);
      }
    }
  }
}

TEST_CASE("expression builder: the same tape as the formula parsed from text") {
  ExpressionBuilder b(2);
  const auto u = b.input(0), v = b.input(1);
  // (u - v) / (u + 1) + 3 u v^2 - u^4
  const auto built = b.sub(
      b.add(b.div(b.sub(u, v), b.add(u, b.constant(1.0))), b.mul(b.constant(3.0), b.mul(u, b.power(v, 2)))),
      b.power(u, 4));
  const Program from_builder = b.program({built});
  const Program parsed = Program::compile({{"x", "(u - v) / (u + 1) + 3 * (u * v^2) - u^4"}}, {"u", "v"}, {});
  CHECK(from_builder.num_nodes() == parsed.num_nodes());
  for (const std::array<double, 2> at : {std::array<double, 2>{0.3, -1.7}, {-0.6, 2.2}, {4.0, 0.5}}) {
    double a = 0.0, c = 0.0;
    from_builder.values(at.data(), &a);
    parsed.values(at.data(), &c);
    CHECK(a == c);
    Jet2<2> ja, jc;
    from_builder.jets2<2>(at.data(), &ja);
    parsed.jets2<2>(at.data(), &jc);
    CHECK(ja.g == jc.g);
    CHECK(ja.h == jc.h);
  }
  const std::array<Interval, 2> box{Interval{-0.5, 0.5}, Interval{1.0, 2.0}};
  Interval ia, ic;
  from_builder.intervals(box.data(), &ia);
  parsed.intervals(box.data(), &ic);
  CHECK(ia.lo == ic.lo);
  CHECK(ia.hi == ic.hi);
}

TEST_CASE("expression builder: enclosures hold every sampled value, x^3 over [-2, 1] is [-8, 1]") {
  ExpressionBuilder b(2);
  const auto x = b.input(0), y = b.input(1);
  const Program program = b.program({b.power(x, 3), b.div(b.sub(x, y), b.add(x, b.constant(3.0)))});
  const std::array<Interval, 2> box{Interval{-2.0, 1.0}, Interval{-1.0, 0.5}};
  std::array<Interval, 2> range{};
  program.intervals(box.data(), range.data());
  // x^3 is increasing: its range over [-2, 1] is [(-2)^3, 1^3].
  CHECK(range[0].lo <= -8.0);
  CHECK(range[0].hi >= 1.0);
  CHECK(range[0].lo >= -8.0 * (1.0 + 1e-12));
  CHECK(range[0].hi <= 1.0 + 1e-12);
  for (int i = 0; i <= 30; ++i)
    for (int j = 0; j <= 30; ++j) {
      const std::array<double, 2> at{-2.0 + 3.0 * i / 30.0, -1.0 + 1.5 * j / 30.0};
      std::array<double, 2> values{};
      program.values(at.data(), values.data());
      for (std::size_t k = 0; k < 2; ++k) {
        CHECK(range[k].lo <= values[k]);
        CHECK(values[k] <= range[k].hi);
      }
    }
}

TEST_CASE("expression builder: shared subexpressions and folded constants") {
  ExpressionBuilder b(2);
  const auto x = b.input(0), y = b.input(1);
  // Commutative operations in either order, and a repeated expression, are one node.
  CHECK(b.add(x, y) == b.add(y, x));
  CHECK(b.mul(x, y) == b.mul(y, x));
  CHECK(b.sub(x, y) == b.sub(x, y));
  CHECK(b.sub(x, y) != b.sub(y, x));
  CHECK(b.input(0) == x);
  // Constants fold: (2 + 3) * 4 - 6 / 3 is the constant 18; x^0 is 1 and x^1 is x.
  const auto folded = b.sub(b.mul(b.add(b.constant(2.0), b.constant(3.0)), b.constant(4.0)),
                            b.div(b.constant(6.0), b.constant(3.0)));
  CHECK(b.power(x, 1) == x);
  const Program program = b.program({folded, b.power(x, 0), b.add(b.mul(x, y), b.mul(y, x))});
  for (const std::array<double, 2> at : {std::array<double, 2>{0.0, 0.0}, {-7.0, 2.5}}) {
    std::array<double, 3> values{};
    program.values(at.data(), values.data());
    CHECK(values[0] == 18.0);
    CHECK(values[1] == 1.0);
    CHECK(values[2] == 2.0 * at[0] * at[1]);
  }
}

TEST_CASE("expression builder: more nodes than max_nodes is too_complex, fewer compile") {
  // x^(2^k) by k squarings: one input and k products, each a new node.
  const auto build = [](std::size_t max_nodes, int squarings) {
    ExpressionBuilder b(1, max_nodes);
    auto e = b.input(0);
    for (int k = 0; k < squarings; ++k) e = b.mul(e, e);
    return b.program({e});
  };
  const Program ok = build(20, 10);
  const double at = std::pow(2.0, 1.0 / 1024.0);
  double value = 0.0;
  ok.values(&at, &value);
  CHECK(value == doctest::Approx(2.0).epsilon(1e-12));
  try {
    build(6, 10);
    FAIL("a tape of 11 nodes passed a bound of 6");
  } catch (const FormulaError& e) {
    CHECK(e.kind == FormulaError::Kind::too_complex);
    CHECK(std::string(e.what()).find("more than 6 operations") != std::string::npos);
  }
}
