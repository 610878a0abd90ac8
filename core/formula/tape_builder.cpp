// muparser front end: the only place that knows muparser. Each formula is read by our own reader
// first (formula/syntax.hpp: the errors, their positions and suggestions), then parsed once by
// muparser (its precedence), with the optimizer off so that the bytecode is plain reverse Polish
// notation, and that bytecode is read into our own SSA tape. Built-in functions are
// registered by us with a user-data pointer naming our Op, so no comparison with muparser's internal
// function pointers is needed.
#include <muParser.h>

#include <algorithm>
#include <cctype>
#include <cstring>
#include <numbers>
#include <unordered_map>

#include "formula/elementary.hpp"
#include "formula/syntax.hpp"
#include "formula/tape.hpp"
#include "formula/tape_builder.hpp"

namespace footpoint::formula {

FormulaError::FormulaError(Kind kind, std::string formula, int position, std::string message,
                           std::string suggestion)
    : std::runtime_error(std::move(message)),
      kind(kind),
      formula(std::move(formula)),
      position(position),
      suggestion(std::move(suggestion)) {}

const char* to_string(FormulaError::Kind kind) {
  switch (kind) {
    case FormulaError::Kind::syntax:
      return "formula_syntax";
    case FormulaError::Kind::unknown_variable:
      return "unknown_variable";
    case FormulaError::Kind::unknown_function:
      return "unknown_function";
    case FormulaError::Kind::empty:
      return "empty_formula";
    case FormulaError::Kind::too_long:
      return "formula_too_long";
    case FormulaError::Kind::too_complex:
      return "formula_too_complex";
    case FormulaError::Kind::bad_constant:
      return "bad_constant";
  }
  return "formula_error";
}

namespace {

// The functions users may call, with the Op each one becomes. Their addresses are the user data
// handed to muparser, so a bytecode token identifies its function exactly.
struct FunctionEntry {
  const char* name;
  Op op;
  int arity;  // 1, or -1 for min/max (two or more arguments)
};
constexpr FunctionEntry kFunctions[] = {
    {"sin", Op::sin, 1},     {"cos", Op::cos, 1},     {"tan", Op::tan, 1},     {"asin", Op::asin, 1},
    {"acos", Op::acos, 1},   {"atan", Op::atan, 1},   {"sinh", Op::sinh, 1},   {"cosh", Op::cosh, 1},
    {"tanh", Op::tanh, 1},   {"asinh", Op::asinh, 1}, {"acosh", Op::acosh, 1}, {"atanh", Op::atanh, 1},
    {"exp", Op::exp, 1},     {"ln", Op::ln, 1},       {"log", Op::ln, 1},      {"log2", Op::log2, 1},
    {"log10", Op::log10, 1}, {"sqrt", Op::sqrt, 1},   {"abs", Op::abs, 1},     {"sign", Op::sign, 1},
    {"min", Op::min, -1},    {"max", Op::max, -1},
};

}  // namespace

const std::vector<FunctionSignature>& function_signatures() {
  static const std::vector<FunctionSignature> signatures = [] {
    std::vector<FunctionSignature> v;
    for (const auto& f : kFunctions) v.push_back({f.name, f.arity});
    return v;
  }();
  return signatures;
}

namespace {

mu::value_type call_unary(void* entry, mu::value_type x) {
  return unary_value(static_cast<const FunctionEntry*>(entry)->op, x, 0.0);
}
mu::value_type call_variadic(void* entry, const mu::value_type* args, int n) {
  const Op op = static_cast<const FunctionEntry*>(entry)->op;
  double r = args[0];
  for (int i = 1; i < n; ++i) r = binary_value(op, r, args[i]);
  return r;
}
mu::value_type unary_minus(mu::value_type x) { return -x; }
mu::value_type unary_plus(mu::value_type x) { return x; }

bool is_identifier(const std::string& s) {
  if (s.empty() || !(std::isalpha(static_cast<unsigned char>(s[0])) || s[0] == '_')) return false;
  return std::all_of(s.begin(), s.end(),
                     [](char ch) { return std::isalnum(static_cast<unsigned char>(ch)) || ch == '_'; });
}

Op binary_op_of(mu::ECmdCode code) {
  switch (code) {
    case mu::cmLE:
      return Op::le;
    case mu::cmGE:
      return Op::ge;
    case mu::cmNEQ:
      return Op::ne;
    case mu::cmEQ:
      return Op::eq;
    case mu::cmLT:
      return Op::lt;
    case mu::cmGT:
      return Op::gt;
    case mu::cmADD:
      return Op::add;
    case mu::cmSUB:
      return Op::sub;
    case mu::cmMUL:
      return Op::mul;
    case mu::cmDIV:
      return Op::div;
    case mu::cmPOW:
      return Op::pow;
    case mu::cmLAND:
      return Op::logical_and;
    case mu::cmLOR:
      return Op::logical_or;
    default:
      return Op::constant;
  }
}

}  // namespace

Program::Tape live_part(const Program::Tape& tape) {
  std::vector<char> live(tape.nodes.size(), 0);
  for (const std::int32_t o : tape.outputs) live[static_cast<std::size_t>(o)] = 1;
  for (std::size_t i = tape.nodes.size(); i-- > 0;) {
    if (!live[i]) continue;
    for (const std::int32_t operand : {tape.nodes[i].a, tape.nodes[i].b, tape.nodes[i].c})
      if (operand >= 0) live[static_cast<std::size_t>(operand)] = 1;
  }
  std::vector<std::int32_t> renumber(tape.nodes.size(), -1);
  Program::Tape out;
  out.num_inputs = tape.num_inputs;
  for (std::size_t i = 0; i < tape.nodes.size(); ++i) {
    if (!live[i]) continue;
    Node n = tape.nodes[i];
    for (std::int32_t* operand : {&n.a, &n.b, &n.c})
      if (*operand >= 0) *operand = renumber[static_cast<std::size_t>(*operand)];
    renumber[i] = static_cast<std::int32_t>(out.nodes.size());
    out.nodes.push_back(n);
  }
  for (const std::int32_t o : tape.outputs) out.outputs.push_back(renumber[static_cast<std::size_t>(o)]);
  return out;
}

Program::Tape build_tape(const std::vector<NamedFormula>& formulas, const std::vector<std::string>& variables,
                         const std::map<std::string, double>& constants, const CompileLimits& limits) {
  TapeBuilder builder(limits.max_nodes);
  std::vector<std::int32_t> outputs;
  std::vector<double> var_storage(variables.size(), 0.5);

  for (const auto& [name, value] : constants) {
    if (!is_identifier(name) || name == "_pi" || name == "_e")
      throw FormulaError(FormulaError::Kind::bad_constant, "constants." + name, -1,
                         "constant name '" + name + "' is not a valid identifier or is reserved");
    if (std::find(variables.begin(), variables.end(), name) != variables.end())
      throw FormulaError(FormulaError::Kind::bad_constant, "constants." + name, -1,
                         "constant '" + name + "' has the name of a variable");
    if (!std::isfinite(value))
      throw FormulaError(FormulaError::Kind::bad_constant, "constants." + name, -1,
                         "constant '" + name + "' is not a finite number");
  }

  for (const auto& formula : formulas) {
    const std::string& text = formula.expression;
    if (text.size() > limits.max_formula_length)
      throw FormulaError(FormulaError::Kind::too_long, formula.name,
                         static_cast<int>(limits.max_formula_length),
                         "formula " + formula.name + " has " + std::to_string(text.size()) +
                             " characters; the limit is " + std::to_string(limits.max_formula_length));
    if (std::all_of(text.begin(), text.end(),
                    [](char ch) { return std::isspace(static_cast<unsigned char>(ch)); }))
      throw FormulaError(FormulaError::Kind::empty, formula.name, -1,
                         "formula " + formula.name + " is empty");

    // Our reader first: every fault it finds is reported in our words at its character position.
    const std::string parsed_text = check_syntax(formula, variables, constants);
    static_assert(kLongestFormula + 1 == static_cast<std::size_t>(mu::MaxLenExpression));
    if (parsed_text.size() > kLongestFormula)
      throw FormulaError(FormulaError::Kind::too_long, formula.name, static_cast<int>(kLongestFormula),
                         "formula " + formula.name + " has " + std::to_string(parsed_text.size()) +
                             " characters; the formula compiler (muparser) reads at most " +
                             std::to_string(kLongestFormula));
    mu::Parser parser;
    try {
      parser.ClearFun();
      parser.ClearConst();
      parser.ClearInfixOprt();
      parser.ClearPostfixOprt();
      parser.EnableOptimizer(false);
      parser.DefineInfixOprt("-", unary_minus);
      parser.DefineInfixOprt("+", unary_plus);
      for (const auto& f : kFunctions) {
        void* entry = const_cast<FunctionEntry*>(&f);
        if (f.arity == 1)
          parser.DefineFunUserData(f.name, call_unary, entry);
        else
          parser.DefineFunUserData(f.name, call_variadic, entry);
      }
      parser.DefineConst("_pi", std::numbers::pi);  // muparser's own _pi has 13 digits only
      parser.DefineConst("_e", std::numbers::e);
      for (const auto& [name, value] : constants) parser.DefineConst(name, value);
      for (std::size_t i = 0; i < variables.size(); ++i) parser.DefineVar(variables[i], &var_storage[i]);
      parser.SetExpr(parsed_text);
      parser.Eval();  // muparser builds the bytecode on the first evaluation
    } catch (const mu::ParserError& e) {
      // The grammars agree (tests/core/formula/syntax_test.cpp), so this is not expected; muparser's own
      // words are not passed on, its position is kept within the formula.
      const int last = std::max(0, static_cast<int>(parsed_text.size()) - 1);
      const int pos = std::clamp(static_cast<int>(e.GetPos()), 0, last);
      throw FormulaError(FormulaError::Kind::syntax, formula.name, pos,
                         "formula " + formula.name + " does not parse near position " + std::to_string(pos));
    }

    const mu::ParserByteCode& bytecode = parser.GetByteCode();
    const mu::SToken* tokens = bytecode.GetBase();
    std::vector<std::int32_t> stack, conditions;
    auto pop = [&] {
      const std::int32_t top = stack.back();
      stack.pop_back();
      return top;
    };
    auto variable_of = [&](const mu::value_type* ptr) {
      return builder.variable(static_cast<int>(ptr - var_storage.data()));
    };
    for (std::size_t i = 0; i < bytecode.GetSize() && tokens[i].Cmd != mu::cmEND; ++i) {
      const mu::SToken& tok = tokens[i];
      switch (tok.Cmd) {
        case mu::cmVAL:
          stack.push_back(builder.constant(tok.Val.data2));
          break;
        case mu::cmVAR: {
          // muparser's variable token means data * var + data2 (1 and 0 with the optimizer off).
          std::int32_t v = variable_of(tok.Val.ptr);
          if (tok.Val.data != 1.0) v = builder.binary(Op::mul, builder.constant(tok.Val.data), v);
          if (tok.Val.data2 != 0.0) v = builder.binary(Op::add, v, builder.constant(tok.Val.data2));
          stack.push_back(v);
          break;
        }
        case mu::cmVARPOW2:
        case mu::cmVARPOW3:
        case mu::cmVARPOW4:
          stack.push_back(
              builder.unary(Op::pow_int, variable_of(tok.Val.ptr), 2.0 + (tok.Cmd - mu::cmVARPOW2)));
          break;
        case mu::cmVARMUL:
          stack.push_back(builder.binary(
              Op::add, builder.binary(Op::mul, builder.constant(tok.Val.data), variable_of(tok.Val.ptr)),
              builder.constant(tok.Val.data2)));
          break;
        case mu::cmIF:
          conditions.push_back(pop());
          break;
        case mu::cmELSE:
          break;
        case mu::cmENDIF: {
          const std::int32_t b = pop(), a = pop(), c = conditions.back();
          conditions.pop_back();
          stack.push_back(builder.select(c, a, b));
          break;
        }
        case mu::cmFUNC: {
          const void* ud = tok.Fun.cb._pUserData;
          if (ud == nullptr) {  // our infix operators
            const std::int32_t a = pop();
            if (reinterpret_cast<void*>(tok.Fun.cb._pRawFun) == reinterpret_cast<void*>(&unary_minus))
              stack.push_back(builder.unary(Op::neg, a));
            else
              stack.push_back(a);
            break;
          }
          const auto* entry = static_cast<const FunctionEntry*>(ud);
          if (entry->arity == 1) {
            stack.push_back(builder.unary(entry->op, pop()));
          } else {
            const int n = -tok.Fun.argc;  // muparser: negative count for variadic functions
            std::vector<std::int32_t> args(stack.end() - n, stack.end());
            stack.resize(stack.size() - n);
            std::int32_t r = args[0];
            for (int k = 1; k < n; ++k) r = builder.binary(entry->op, r, args[k]);
            stack.push_back(r);
          }
          break;
        }
        default: {
          const Op op = binary_op_of(tok.Cmd);
          if (op == Op::constant)
            throw FormulaError(FormulaError::Kind::syntax, formula.name, -1,
                               "formula " + formula.name + ": unsupported construct in expression");
          const std::int32_t b = pop(), a = pop();
          stack.push_back(builder.binary(op, a, b));
        }
      }
      if (builder.full())
        throw FormulaError(
            FormulaError::Kind::too_complex, formula.name, -1,
            "formulas are too complex: more than " + std::to_string(limits.max_nodes) + " operations");
    }
    if (stack.size() != 1)
      throw FormulaError(FormulaError::Kind::syntax, formula.name, -1,
                         "formula " + formula.name + " must be a single expression");
    outputs.push_back(stack.back());
  }
  return builder.take(std::move(outputs), static_cast<int>(variables.size()));
}

}  // namespace footpoint::formula
