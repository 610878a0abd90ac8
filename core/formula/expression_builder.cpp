#include "formula/expression_builder.hpp"

#include <string>

#include "formula/tape_builder.hpp"

namespace footpoint::formula {

ExpressionBuilder::ExpressionBuilder(int num_inputs, std::size_t max_nodes)
    : num_inputs_(num_inputs), max_nodes_(max_nodes), tape_(std::make_unique<TapeBuilder>(max_nodes)) {}
ExpressionBuilder::~ExpressionBuilder() = default;

ExpressionBuilder::Node ExpressionBuilder::input(int index) { return tape_->variable(index); }
ExpressionBuilder::Node ExpressionBuilder::constant(double value) { return tape_->constant(value); }
ExpressionBuilder::Node ExpressionBuilder::add(Node a, Node b) { return tape_->binary(Op::add, a, b); }
ExpressionBuilder::Node ExpressionBuilder::sub(Node a, Node b) { return tape_->binary(Op::sub, a, b); }
ExpressionBuilder::Node ExpressionBuilder::mul(Node a, Node b) { return tape_->binary(Op::mul, a, b); }
ExpressionBuilder::Node ExpressionBuilder::div(Node a, Node b) { return tape_->binary(Op::div, a, b); }
ExpressionBuilder::Node ExpressionBuilder::power(Node a, int exponent) {
  return tape_->binary(Op::pow, a, tape_->constant(static_cast<double>(exponent)));
}

Program ExpressionBuilder::program(const std::vector<Node>& outputs) {
  if (tape_->full())
    throw FormulaError(FormulaError::Kind::too_complex, "", -1,
                       "formulas are too complex: more than " + std::to_string(max_nodes_) + " operations");
  return Program::from_tape(tape_->take(outputs, num_inputs_));
}

}  // namespace footpoint::formula
