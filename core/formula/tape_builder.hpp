// The tape's writer: appends nodes with constant folding and common-subexpression sharing. The
// muparser front end (tape_builder.cpp) and ExpressionBuilder (expression_builder.hpp) write
// through it. Internal to core/formula.
#pragma once
#include <cmath>
#include <cstdint>
#include <cstring>
#include <unordered_map>
#include <utility>
#include <vector>

#include "formula/elementary.hpp"
#include "formula/tape.hpp"

namespace footpoint::formula {

// Appends nodes with constant folding and common-subexpression sharing.
class TapeBuilder {
 public:
  explicit TapeBuilder(std::size_t max_nodes) : max_nodes_(max_nodes) {}

  std::int32_t constant(double value) { return add({Op::constant, -1, -1, -1, value}); }
  std::int32_t variable(int index) { return add({Op::variable, -1, -1, -1, static_cast<double>(index)}); }

  std::int32_t unary(Op op, std::int32_t a, double k = 0.0) {
    if (is_constant(a)) return constant(unary_value(op, value(a), k));
    return add({op, a, -1, -1, k});
  }

  std::int32_t binary(Op op, std::int32_t a, std::int32_t b) {
    if (op == Op::pow) return power(a, b);  // the tape holds pow_int, pow_real or exp(b ln a)
    if (is_constant(a) && is_constant(b)) return constant(binary_value(op, value(a), value(b)));
    if (is_constant(b)) {
      const double k = value(b);
      if (op == Op::add) return k == 0.0 ? a : add({Op::add_k, a, -1, -1, k});
      if (op == Op::sub) return k == 0.0 ? a : add({Op::add_k, a, -1, -1, -k});
      if (op == Op::mul) return k == 1.0 ? a : add({Op::mul_k, a, -1, -1, k});
      if (op == Op::div) return k == 1.0 ? a : add({Op::div_k, a, -1, -1, k});
    }
    if (is_constant(a)) {
      const double k = value(a);
      if (op == Op::add) return k == 0.0 ? b : add({Op::add_k, b, -1, -1, k});
      if (op == Op::sub) return add({Op::rsub_k, b, -1, -1, k});
      if (op == Op::mul) return k == 1.0 ? b : add({Op::mul_k, b, -1, -1, k});
      if (op == Op::div) return add({Op::rdiv_k, b, -1, -1, k});
    }
    if ((op == Op::add || op == Op::mul || op == Op::min || op == Op::max || op == Op::eq || op == Op::ne) &&
        a > b)
      std::swap(a, b);  // commutative: one canonical order, so a+b and b+a share a node
    return add({op, a, b, -1, 0.0});
  }

  std::int32_t select(std::int32_t c, std::int32_t a, std::int32_t b) {
    if (is_constant(c)) return value(c) != 0.0 ? a : b;
    return add({Op::select, a, b, c, 0.0});
  }

  // The tape of the nodes the outputs depend on (constants absorbed into *_k ops drop out).
  Program::Tape take(std::vector<std::int32_t> outputs, int num_inputs) {
    Program::Tape all;
    all.nodes = std::move(nodes_);
    all.outputs = std::move(outputs);
    all.num_inputs = num_inputs;
    return live_part(all);
  }
  bool full() const { return nodes_.size() > max_nodes_; }

 private:
  // a^b: a constant integer exponent uses the ordinary power rule (valid for a < 0); a constant real
  // exponent the general one; a variable exponent is exp(b ln a), defined for a > 0.
  std::int32_t power(std::int32_t a, std::int32_t b) {
    if (is_constant(a) && is_constant(b)) return constant(std::pow(value(a), value(b)));
    if (is_constant(b)) {
      const double k = value(b);
      if (k == 1.0) return a;
      if (k == 0.0) return constant(1.0);
      // Any integral exponent uses the power rule (binary powering: O(log k) products).
      if (k == std::floor(k) && std::fabs(k) <= 1073741824.0) return unary(Op::pow_int, a, k);
      return unary(Op::pow_real, a, k);
    }
    return unary(Op::exp, binary(Op::mul, b, unary(Op::ln, a)));
  }

  bool is_constant(std::int32_t i) const { return nodes_[i].op == Op::constant; }
  double value(std::int32_t i) const { return nodes_[i].k; }

  struct Key {
    Op op;
    std::int32_t a, b, c;
    std::uint64_t k;
    bool operator==(const Key&) const = default;
  };
  struct KeyHash {
    std::size_t operator()(const Key& key) const {
      std::size_t h = static_cast<std::size_t>(key.op);
      for (std::uint64_t part : {std::uint64_t(std::uint32_t(key.a)), std::uint64_t(std::uint32_t(key.b)),
                                 std::uint64_t(std::uint32_t(key.c)), key.k})
        h = (h ^ part) * 0x100000001b3ULL + (h >> 17);
      return h;
    }
  };

  std::int32_t add(const Node& node) {
    std::uint64_t bits;
    std::memcpy(&bits, &node.k, sizeof bits);
    const Key key{node.op, node.a, node.b, node.c, bits};
    if (auto it = index_.find(key); it != index_.end()) return it->second;
    const auto i = static_cast<std::int32_t>(nodes_.size());
    nodes_.push_back(node);
    index_.emplace(key, i);
    return i;
  }

  std::size_t max_nodes_;
  std::vector<Node> nodes_;
  std::unordered_map<Key, std::int32_t, KeyHash> index_;
};

}  // namespace footpoint::formula
