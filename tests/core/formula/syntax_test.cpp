// The formula reader (formula/syntax.hpp): each fault its kind, its character position and its
// suggestion; and the reader accepts exactly what muparser, configured as the tape builder
// configures it, accepts (random formulas from a token alphabet), so that muparser's own errors
// never reach a user.
#include <doctest/doctest.h>
#include <muParser.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "formula/program.hpp"
#include "formula/syntax.hpp"

using footpoint::formula::check_syntax;
using footpoint::formula::FormulaError;
using footpoint::formula::Program;

namespace {

FormulaError syntax_error_of(const std::string& text, const std::vector<std::string>& variables = {"u", "v"},
                             const std::map<std::string, double>& constants = {}) {
  try {
    Program::compile({{"x", text}}, variables, constants);
  } catch (const FormulaError& e) {
    return e;
  }
  FAIL("expected a FormulaError for " << text);
  return FormulaError(FormulaError::Kind::syntax, "", -1, "");
}

struct Expected {
  std::string text;
  FormulaError::Kind kind;
  int position;
  std::string suggestion;
  std::string in_message;  // a part of the message
};

}  // namespace

TEST_CASE("each fault: its kind, its character position, its suggestion, in our words") {
  using K = FormulaError::Kind;
  const std::vector<Expected> cases = {
      // unknown functions and names, with the nearest valid one
      {"sinn(u)", K::unknown_function, 0, "sin", "unknown function 'sinn' at position 0; did you mean sin?"},
      {"2*Cos(v)", K::unknown_function, 2, "cos", "did you mean cos?"},
      {"cs(u)", K::unknown_function, 0, "cos", "unknown function 'cs' at position 0; did you mean cos?"},
      {"1+ab(u)", K::unknown_function, 2, "abs", ""},
      {"qz(u)", K::unknown_function, 0, "", "the functions: sin, cos"},
      {"pow(u,2)", K::unknown_function, 0, "u^2", "did you mean u^2?"},
      {"1+pow(u+v, 1/3)", K::unknown_function, 2, "(u+v)^(1/3)", "unknown function 'pow'"},
      {"pow(sin(u),v)", K::unknown_function, 0, "sin(u)^v", ""},
      {"pow(u", K::unknown_function, 0, "a^b", ""},
      {"hypot(u,v)", K::unknown_function, 0, "sqrt(u^2+v^2)", ""},
      {"arcsin(u)", K::unknown_function, 0, "asin", ""},
      {"floor(u)", K::unknown_function, 0, "", "the functions: sin, cos"},
      {"pi*u", K::unknown_variable, 0, "_pi", "unknown name 'pi' at position 0; did you mean _pi?"},
      {"u*PI", K::unknown_variable, 2, "_pi", ""},
      {"u+w", K::unknown_variable, 2, "", "(the variables: u, v; the constants: _pi, _e)"},
      {"U+v", K::unknown_variable, 0, "u", ""},
      {"_pi2*u", K::unknown_variable, 0, "_pi", ""},
      // operators from elsewhere
      {"u**2", K::syntax, 1, "^", "'**' at position 1 is not an operator: powers are written ^"},
      {"u=2", K::syntax, 1, "==", "write == to compare"},
      {"u<>v", K::syntax, 1, "!=", ""},
      {"u=>v", K::syntax, 1, ">=", ""},
      {"u&v", K::syntax, 1, "&&", ""},
      {"!u", K::syntax, 0, "", "'!' at position 0 is not an operator"},
      // characters of typeset mathematics; positions count characters, not bytes
      {"2\u00B73", K::syntax, 1, "*",
       "unexpected character '\u00B7' (U+00B7) at position 1; write * instead"},
      {"\u03C0*u", K::syntax, 0, "_pi", ""},
      {"u\u00B2+v", K::syntax, 1, "^2", ""},
      {"\u03C0\u03C0+u%v", K::syntax, 0, "_pi", ""},
      {"u+v\u2212\u00B2", K::syntax, 3, "-", ""},
      {"u+\u00E9", K::syntax, 2, "", "unexpected character '\u00E9' (U+00E9) at position 2"},
      {"u%v", K::syntax, 1, "", "(U+0025) at position 1"},
      // structure: the position of the character at fault, never past the formula's end
      {"sin(u", K::syntax, 3, "", "'(' at position 3 (the call of sin) is not closed"},
      {"(u+v", K::syntax, 0, "", "'(' at position 0 is not closed"},
      {"((u)", K::syntax, 0, "", ""},
      {"u*(v+", K::syntax, 4, "", "the formula ends after '+' at position 4: an operand is missing"},
      {"sin(u))", K::syntax, 6, "", "')' at position 6 closes no '('"},
      {"u+", K::syntax, 1, "", ""},
      {"-", K::syntax, 0, "", ""},
      {"(u+)", K::syntax, 3, "", "an operand is missing before ')' at position 3"},
      {"()", K::syntax, 1, "", "nothing between '(' at position 0 and ')'"},
      {"u*/v", K::syntax, 2, "", "'/' at position 2 stands where an operand is expected"},
      {"2u", K::syntax, 1, "", "an operator is missing before 'u' at position 1 (products are written a*b)"},
      {"u v", K::syntax, 2, "", ""},
      {"u(2)", K::syntax, 1, "", "an operator is missing before '('"},
      {"sin(u)(v)", K::syntax, 6, "", ""},
      {"--u", K::syntax, 1, "", "a second sign '-' at position 1"},
      {"u^-+v", K::syntax, 3, "", ""},
      {"sin+1", K::syntax, 0, "", "sin at position 0 is a function: write sin(x)"},
      {"sin()", K::syntax, 0, "", "sin at position 0 needs an argument"},
      {"sin(u,v)", K::syntax, 0, "", "sin at position 0 takes 1 argument, not 2"},
      {"min(u,)", K::syntax, 6, "", ""},
      {"min(,u)", K::syntax, 4, "", ""},
      {"u,v", K::syntax, 1, "", "a formula is one expression"},
      {"(u,v)", K::syntax, 2, "", ""},
      {"u?v", K::syntax, 1, "", "'?' at position 1 has no ':'"},
      {"u:v", K::syntax, 1, "", "':' at position 1 belongs to no '?'"},
      {"u?(1:2)", K::syntax, 4, "", ""},
      {"(?u)", K::syntax, 1, "", "follows no condition"},
      {"1e", K::syntax, 0, "", "number '1e' at position 0 has an exponent without digits"},
      {"u+2e+v", K::syntax, 2, "", ""},
      {"u+1e400", K::syntax, 2, "", "beyond the largest double"},
      // exponents beyond a long: their sign still decides (a fuzzer's input overflowed the sum)
      {"u+1e9223372036854775807", K::syntax, 2, "", "beyond the largest double"},
      {"u+10e99999999999999999999", K::syntax, 2, "", "beyond the largest double"},
      {"1.5.3", K::syntax, 3, "", ""},
      {"u.v", K::syntax, 1, "", ""},
  };
  for (const auto& c : cases) {
    CAPTURE(c.text);
    const FormulaError e = syntax_error_of(c.text);
    CHECK(e.kind == c.kind);
    CHECK(e.formula == "x");
    CHECK(e.position == c.position);
    CHECK(e.suggestion == c.suggestion);
    const std::string message = e.what();
    CHECK(message.rfind("formula x: ", 0) == 0);
    CHECK(message.find(c.in_message) != std::string::npos);
    // no muparser wording
    CHECK(message.find("Unexpected") == std::string::npos);
    CHECK(message.find("found at") == std::string::npos);
  }
}

TEST_CASE("what the reader accepts compiles to what the formula says") {
  const std::vector<std::pair<std::string, double>> cases = {
      {"sin (u)", std::sin(0.5)},          // a space before a call's '(' is allowed
      {"min ( u , v , 1 )", 0.5},          // and anywhere between tokens
      {"u?v?1:2:3", 1.0},                  // nested conditionals
      {"-u^2", -0.25},                     // ^ binds tighter than the sign
      {"2^-1", 0.5},                       // a sign after an operator
      {"u--v", 1.0},                       // a binary and a unary minus
      {"1e-400+u", 0.5},                   // below the smallest double: 0, as muparser reads it
      {"1e-99999999999999999999+u", 0.5},  // an exponent beyond a long, too
      {".5+5.+1.e1", 15.5},                // number forms
      {"_pi-_e", std::numbers::pi - std::numbers::e},
      {"log(_e)", 1.0},              // natural logarithm
      {"u<v || u>=v && u==v", 1.0},  // comparisons and logic (&& before ||)
  };
  for (const auto& c : cases) {
    const std::string& text = c.first;
    const double value = c.second;
    CAPTURE(text);
    const Program p = Program::compile({{"x", text}}, {"u", "v"}, {});
    const double x[2] = {0.5, 0.5};
    double out = 0.0;
    p.values(x, &out);
    CHECK(out == doctest::Approx(value).epsilon(1e-15));
  }
}

TEST_CASE("nesting beyond the reader's bound is too_complex, below it compiles") {
  std::string deep = std::string(footpoint::formula::kMaxNesting + 5, '(') + "u" +
                     std::string(footpoint::formula::kMaxNesting + 5, ')');
  const FormulaError e = syntax_error_of(deep);
  CHECK(e.kind == FormulaError::Kind::too_complex);
  const std::string ok = std::string(500, '(') + "u" + std::string(500, ')');
  CHECK_NOTHROW(Program::compile({{"x", ok}}, {"u", "v"}, {}));
}

namespace {

double unary_minus(double x) { return -x; }
double unary_plus(double x) { return x; }
double one_argument(void*, double x) { return x; }
double arguments(void*, const double* a, int) { return a[0]; }

// Whether muparser, configured as the tape builder configures it, reads `text` as one expression.
bool muparser_accepts(const std::string& text) {
  mu::Parser p;
  double u = 0.5, v = 0.5;
  static int tag;
  try {
    p.ClearFun();
    p.ClearConst();
    p.ClearInfixOprt();
    p.ClearPostfixOprt();
    p.EnableOptimizer(false);
    p.DefineInfixOprt("-", unary_minus);
    p.DefineInfixOprt("+", unary_plus);
    for (const auto& f : footpoint::formula::function_signatures()) {
      if (f.arity == 1)
        p.DefineFunUserData(std::string(f.name), one_argument, &tag);
      else
        p.DefineFunUserData(std::string(f.name), arguments, &tag);
    }
    p.DefineConst("_pi", 3.0);
    p.DefineConst("_e", 2.0);
    p.DefineVar("u", &u);
    p.DefineVar("v", &v);
    p.SetExpr(text);
    p.Eval();
    return p.GetNumResults() == 1;
  } catch (const mu::ParserError&) {
    return false;
  }
}

}  // namespace

TEST_CASE("the reader and muparser accept the same formulas (random token sequences)") {
  const std::vector<std::string> alphabet = {
      "u", "v", "2", "1.5", ".5", "1e3", "_pi", "sin", "min", "max", "(",  "(",  ")", ")", ",",  "?", ":",
      "+", "-", "-", "*",   "/",  "^",   "<",   "<=",  "==",  "!=",  "&&", "||", " ", "e", "1e", "w", "."};
  std::mt19937 rng(19);
  std::uniform_int_distribution<std::size_t> pick(0, alphabet.size() - 1), length(1, 9);
  int accepted = 0;
  for (int n = 0; n < 60000; ++n) {
    std::string text;
    for (std::size_t k = length(rng); k-- > 0;) text += alphabet[pick(rng)];
    if (text.find_first_not_of(' ') == std::string::npos) continue;
    std::string parsed;
    bool ours = true;
    try {
      parsed = check_syntax({"x", text}, {"u", "v"}, {});
    } catch (const FormulaError& e) {
      ours = false;
      CAPTURE(text);
      CHECK(e.position >= 0);
      CHECK(e.position < static_cast<int>(text.size()));
    }
    CAPTURE(text);
    if (ours) {
      ++accepted;
      CHECK(muparser_accepts(parsed));
    } else {
      CHECK_FALSE(muparser_accepts(text));
    }
  }
  // The alphabet makes enough valid formulas for the agreement to mean something.
  CHECK(accepted > 1500);
}
