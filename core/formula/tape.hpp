// The expression tape: a list of nodes in static single assignment form. Node i only refers to
// nodes before it, so one forward pass evaluates every formula. Internal to core/formula.
#pragma once
#include <cstdint>
#include <optional>
#include <vector>

#include "formula/polynomial.hpp"
#include "formula/program.hpp"

namespace footpoint::formula {

enum class Op : std::uint8_t {
  // leaves
  constant,
  variable,
  // arithmetic
  add,
  sub,
  mul,
  div,
  neg,
  // arithmetic with a constant operand k (node.k): cheaper jets than the general rules
  add_k,     // a + k   (a - k is a + (-k), exact)
  mul_k,     // a * k
  div_k,     // a / k
  rsub_k,    // k - a
  rdiv_k,    // k / a
  pow,       // a^b while building only: the tape holds pow_int, pow_real or exp(b ln a)
  pow_int,   // a^k, k integer (node.k): ordinary power rule, fine for a < 0
  pow_real,  // a^c, c a non-integer constant (node.k)
  // elementary functions of one argument
  sqrt,
  exp,
  ln,
  log2,
  log10,
  sin,
  cos,
  tan,
  asin,
  acos,
  atan,
  sinh,
  cosh,
  tanh,
  asinh,
  acosh,
  atanh,
  abs,
  sign,
  // two arguments, piecewise
  min,
  max,
  // comparisons and logic (value 0 or 1, zero derivatives)
  lt,
  le,
  gt,
  ge,
  eq,
  ne,
  logical_and,
  logical_or,
  // c ? a : b
  select,
};

struct Node {
  Op op;
  std::int32_t a = -1, b = -1, c = -1;  // operand node indices
  double k = 0.0;                       // constant value, variable index or exponent
};

struct Program::Tape {
  std::vector<Node> nodes;
  std::vector<std::int32_t> outputs;  // node index of each formula's result
  int num_inputs = 0;
  std::optional<PolynomialForm> polynomial;  // set when every formula is a sum of monomials
};

// The nodes the outputs depend on, in their order, renumbered (tape_builder.cpp); no polynomial form.
Program::Tape live_part(const Program::Tape& tape);

// The formulas as sums of monomials in the tape's order of summation, if every one of them is.
std::optional<PolynomialForm> polynomial_form(const Program::Tape& tape);

// Reads muparser's bytecode of every formula into one tape (tape_builder.cpp).
Program::Tape build_tape(const std::vector<NamedFormula>& formulas, const std::vector<std::string>& variables,
                         const std::map<std::string, double>& constants, const CompileLimits& limits);

// f and its first three derivatives at x, for the unary ops (elementary.cpp-style table in program.cpp).
bool is_unary(Op op);

}  // namespace footpoint::formula
