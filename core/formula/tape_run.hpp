// The forward pass over the tape, for any arithmetic (plain values, jets, intervals, interval
// jets). Internal to core/formula.
#pragma once
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "formula/tape.hpp"

namespace footpoint::formula {

inline bool is_binary(Op op) {
  return (op >= Op::add && op <= Op::div) || (op >= Op::min && op <= Op::logical_or);
}

// Evaluates every node in order (node i only reads nodes before it) in `Arith`'s number type and
// writes each formula's result. Registers are thread-local scratch, so one tape serves many threads.
// Operands are passed as references to their registers: a node used for both operands (x * x) is
// one object, which the interval arithmetics recognise (a square has no dependency problem).
// `choice`: selects replaced by a branch (Program::interval_jets2 with a BranchChoice).
// `undecided`: receives the conditions of selects that Arith::decided says are undecided, once each.
template <class Arith>
void run(const Program::Tape& tape, const typename Arith::Input* inputs, typename Arith::Output* outputs,
         const BranchChoice* choice = nullptr, std::vector<std::int32_t>* undecided = nullptr) {
  using T = typename Arith::T;
  thread_local std::vector<T> regs;
  if (regs.size() < tape.nodes.size()) regs.resize(tape.nodes.size());
  const Node* nodes = tape.nodes.data();
  const std::size_t n = tape.nodes.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Node& node = nodes[i];
    // The frequent ops get a case with a constant Op, so that the inlined arithmetic's own switch
    // folds away; the rest share the generic calls.
    switch (node.op) {
      case Op::constant:
        regs[i] = Arith::constant(node.k);
        break;
      case Op::variable:
        regs[i] = Arith::variable(inputs, static_cast<int>(node.k));
        break;
      case Op::select: {
        bool take_b = false;
        if (choice && choice->forces(node.c, &take_b)) {
          regs[i] = take_b ? regs[node.b] : regs[node.a];
          break;
        }
        if constexpr (requires(const T& c) { Arith::decided(c); })
          if (undecided && !Arith::decided(regs[node.c]) &&
              std::find(undecided->begin(), undecided->end(), node.c) == undecided->end())
            undecided->push_back(node.c);
        regs[i] = Arith::select(regs[node.c], regs[node.a], regs[node.b]);
        break;
      }
      case Op::add:
        regs[i] = Arith::binary(Op::add, regs[node.a], regs[node.b]);
        break;
      case Op::sub:
        regs[i] = Arith::binary(Op::sub, regs[node.a], regs[node.b]);
        break;
      case Op::mul:
        regs[i] = Arith::binary(Op::mul, regs[node.a], regs[node.b]);
        break;
      case Op::div:
        regs[i] = Arith::binary(Op::div, regs[node.a], regs[node.b]);
        break;
      case Op::add_k:
        regs[i] = Arith::unary(Op::add_k, regs[node.a], node.k);
        break;
      case Op::mul_k:
        regs[i] = Arith::unary(Op::mul_k, regs[node.a], node.k);
        break;
      case Op::pow_int:
        regs[i] = Arith::unary(Op::pow_int, regs[node.a], node.k);
        break;
      case Op::sin:
        regs[i] = Arith::unary(Op::sin, regs[node.a], node.k);
        break;
      case Op::cos:
        regs[i] = Arith::unary(Op::cos, regs[node.a], node.k);
        break;
      default:
        if (is_binary(node.op))
          regs[i] = Arith::binary(node.op, regs[node.a], regs[node.b]);
        else
          regs[i] = Arith::unary(node.op, regs[node.a], node.k);
    }
  }
  for (std::size_t k = 0; k < tape.outputs.size(); ++k) outputs[k] = Arith::output(regs[tape.outputs[k]]);
}

}  // namespace footpoint::formula
