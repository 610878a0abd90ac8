// Compilation errors are precise (which formula, what, where) and non-finite values are reported
// as such, never as crashes.
#include <doctest/doctest.h>

#include <cmath>

#include "formula/program.hpp"

using footpoint::formula::FormulaError;
using footpoint::formula::Program;

namespace {

FormulaError error_of(const std::vector<footpoint::formula::NamedFormula>& formulas,
                      const std::vector<std::string>& vars = {"u", "v"},
                      const std::map<std::string, double>& constants = {},
                      footpoint::formula::CompileLimits limits = {}) {
  try {
    Program::compile(formulas, vars, constants, limits);
  } catch (const FormulaError& e) {
    return e;
  }
  FAIL("expected a FormulaError");
  return FormulaError(FormulaError::Kind::syntax, "", -1, "");
}

}  // namespace

TEST_CASE("syntax errors name the formula and the position") {
  const auto e = error_of({{"x", "u+v"}, {"y", "u*(v+"}});
  CHECK(e.kind == FormulaError::Kind::syntax);
  CHECK(e.formula == "y");
  CHECK(e.position == 4);  // the '+' that lacks its operand
  const auto e2 = error_of({{"z", "sin(u))"}});
  CHECK(e2.kind == FormulaError::Kind::syntax);
  CHECK(e2.position == 6);
}

TEST_CASE("a variable that may not be used is an error, not a silent zero") {
  const auto e = error_of({{"x", "u + x"}});
  CHECK(e.kind == FormulaError::Kind::unknown_variable);
  CHECK(e.formula == "x");
  CHECK(e.position == 4);
  CHECK(std::string(e.what()).find("'x'") != std::string::npos);
  const auto f = error_of({{"x", "foo(u)"}});
  CHECK(f.kind == FormulaError::Kind::unknown_function);
  CHECK(std::string(f.what()).find("'foo'") != std::string::npos);
}

TEST_CASE("empty, over-long and over-complex formulas are rejected") {
  CHECK(error_of({{"x", "   "}}).kind == FormulaError::Kind::empty);
  CHECK(error_of({{"x", ""}}).kind == FormulaError::Kind::empty);
  footpoint::formula::CompileLimits limits;
  limits.max_formula_length = 20;
  CHECK(error_of({{"x", "u+u+u+u+u+u+u+u+u+u+u+u"}}, {"u", "v"}, {}, limits).kind ==
        FormulaError::Kind::too_long);
  limits = {};
  limits.max_nodes = 10;
  std::string big = "u";
  for (int i = 0; i < 20; ++i) big = "sin(" + big + "+v*" + std::to_string(i) + ")";
  CHECK(error_of({{"x", big}}, {"u", "v"}, {}, limits).kind == FormulaError::Kind::too_complex);
}

TEST_CASE("deep nesting and huge numbers compile or fail cleanly") {
  std::string deep(500, '(');
  deep += "u";
  deep += std::string(500, ')');
  const Program p = Program::compile({{"x", deep}}, {"u"}, {});
  const double u = 2.0;
  double v;
  p.values(&u, &v);
  CHECK(v == 2.0);
  // 1e400 is no double: a clean syntax error at its position.
  const auto e = error_of({{"x", "u+1e400"}}, {"u"});
  CHECK(e.kind == FormulaError::Kind::syntax);
  CHECK(e.position == 2);
  const Program q = Program::compile({{"x", "1e300*1e300*u"}}, {"u"}, {});
  q.values(&u, &v);
  CHECK(std::isinf(v));
}

TEST_CASE("assignments, several expressions and bad constants are rejected") {
  CHECK(error_of({{"x", "u=3"}}).kind == FormulaError::Kind::syntax);
  CHECK(error_of({{"x", "u, v"}}).kind == FormulaError::Kind::syntax);
  CHECK(error_of({{"x", "u"}}, {"u", "v"}, {{"u", 1.0}}).kind == FormulaError::Kind::bad_constant);
  CHECK(error_of({{"x", "u"}}, {"u", "v"}, {{"2bad", 1.0}}).kind == FormulaError::Kind::bad_constant);
  CHECK(error_of({{"x", "u"}}, {"u", "v"}, {{"R", NAN}}).kind == FormulaError::Kind::bad_constant);
}

TEST_CASE("division by zero and domain errors give non-finite values, not crashes") {
  const Program p =
      Program::compile({{"a", "1/u"}, {"b", "sqrt(u-1)"}, {"c", "ln(u)"}, {"d", "u^v"}}, {"u", "v"}, {});
  const double pt[2] = {0.0, 0.5};
  double out[4];
  p.values(pt, out);
  CHECK(std::isinf(out[0]));
  CHECK(std::isnan(out[1]));
  CHECK(std::isinf(out[2]));
  footpoint::formula::Jet2<2> j[4];
  p.jets2<2>(pt, j);
  CHECK(!std::isfinite(j[0].g[0]));
  CHECK(!std::isfinite(j[3].g[0]));
}

TEST_CASE("formulas up to the compiler's longest compile; a longer one is too_long, naming the limit") {
  // 1*u*v+2*u*v+...: a plain sum, one term more at a time until the next would pass the limit.
  std::string sum;
  for (int k = 1;; ++k) {
    std::string term = sum.empty() ? "" : "+";
    term += std::to_string(k);
    term += "*u*v";
    if (sum.size() + term.size() > footpoint::formula::kLongestFormula) break;
    sum += term;
  }
  while (sum.size() < footpoint::formula::kLongestFormula) sum += "+0";
  if (sum.size() > footpoint::formula::kLongestFormula) sum.resize(sum.size() - 2);
  REQUIRE(sum.size() >= footpoint::formula::kLongestFormula - 1);
  const Program p = Program::compile({{"x", sum}}, {"u", "v"}, {});
  const double uv[2] = {0.5, 2.0};
  double value = 0.0;
  p.values(uv, &value);
  const double terms = std::count(sum.begin(), sum.end(), '*') / 2.0;
  CHECK(value == doctest::Approx(terms * (terms + 1) / 2));  // sum of k * 0.5 * 2

  // 30,000 characters: refused before muparser sees them, in words that name the limit.
  std::string longer = sum;
  while (longer.size() < 30000) longer += "+u*v";
  footpoint::formula::CompileLimits limits;
  limits.max_formula_length = 1 << 20;
  const auto e = error_of({{"x", longer}}, {"u", "v"}, {}, limits);
  CHECK(e.kind == FormulaError::Kind::too_long);
  CHECK(e.formula == "x");
  CHECK(std::string(e.what()).find("reads at most 19999") != std::string::npos);
}
