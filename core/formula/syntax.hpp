// The formula language's own reader. Every formula is read by it before muparser sees it, so that
// a formula that does not compile is answered in our words, with the 0-based position (in
// characters, not bytes) of the character at fault and, where one is near, a suggestion:
//   unknown_function  sinn(u) -> sin, pow(u,2) -> u^2, arcsin -> asin
//   unknown_variable  pi -> _pi, w in a surface (the variables are u, v)
//   syntax            u**2 -> ^, sin(u (the '(' at 3 is not closed), 2·3 (· is not an operator: *)
// The grammar is muparser's as this library configures it (tests/core/formula/syntax_test.cpp checks that
// both accept the same formulas):
//   formula  := ternary
//   ternary  := chain [ '?' ternary ':' ternary ]
//   chain    := operand { binary-operator operand }     || && == != < > <= >= + - * / ^
//   operand  := [ '+' | '-' ] primary                    (one sign at most)
//   primary  := number | name | function '(' ternary { ',' ternary } ')' | '(' ternary ')'
//   number   := digits [ '.' digits ] [ ('e'|'E') ['+'|'-'] digits ]  or  '.' digits [...]
//   name     := [A-Za-z_][A-Za-z0-9_]*   (a variable, a user constant, _pi or _e)
// Whitespace (bytes 1-32) separates tokens.
#pragma once
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "formula/program.hpp"

namespace footpoint::formula {

// A function of the language: its name and how many arguments it takes (-1: one or more).
struct FunctionSignature {
  std::string_view name;
  int arity;
};
// Every function, in the order the documentation lists them.
const std::vector<FunctionSignature>& function_signatures();

// Parentheses, calls and conditionals nested deeper than this are refused (too_complex): the
// reader descends recursively and must not exhaust a thread's stack.
inline constexpr int kMaxNesting = 1000;

// Reads `formula` over these variables and user constants (plus _pi and _e). Throws FormulaError
// (syntax, unknown_function, unknown_variable, too_complex) at the first fault, left to right.
// Returns the text to give muparser: the formula with the whitespace between a function's name
// and its '(' removed (muparser requires them adjacent; the reader does not).
std::string check_syntax(const NamedFormula& formula, const std::vector<std::string>& variables,
                         const std::map<std::string, double>& constants);

}  // namespace footpoint::formula
