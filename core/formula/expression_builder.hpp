// Formulas written in code rather than parsed from text: for geometries whose formulas are data
// (a NURBS patch is a sum of control points times Bernstein polynomials). The nodes go on the same
// expression tape as a parsed formula's (formula/program.hpp), with its constant folding and
// shared subexpressions, so the Program built is evaluated, enclosed and differentiated exactly
// like a compiled formula.
#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "formula/program.hpp"

namespace footpoint::formula {

class TapeBuilder;

class ExpressionBuilder {
 public:
  using Node = std::int32_t;

  // Formulas in num_inputs variables; at most max_nodes operations in all (FormulaError
  // too_complex from program() beyond).
  explicit ExpressionBuilder(int num_inputs, std::size_t max_nodes = CompileLimits{}.max_nodes);
  ~ExpressionBuilder();
  ExpressionBuilder(const ExpressionBuilder&) = delete;
  ExpressionBuilder& operator=(const ExpressionBuilder&) = delete;

  Node input(int index);
  Node constant(double value);
  Node add(Node a, Node b);
  Node sub(Node a, Node b);
  Node mul(Node a, Node b);
  Node div(Node a, Node b);
  Node power(Node a, int exponent);  // a^k by the power rule (any sign of a)

  // The Program whose formula k is outputs[k]. The builder is spent.
  Program program(const std::vector<Node>& outputs);

 private:
  int num_inputs_;
  std::size_t max_nodes_;
  std::unique_ptr<TapeBuilder> tape_;
};

}  // namespace footpoint::formula
