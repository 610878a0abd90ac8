// A compiled set of formulas: muparser parses each formula string once, its bytecode is read into
// an immutable expression tape (static single assignment, constants folded, common subexpressions
// shared across the formulas) and that tape is evaluated for plain values, second- or third-order
// jets, intervals or interval jets. A Program is immutable after compile() and safe to evaluate from many
// threads at once without locks (scratch space is thread-local).
#pragma once
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "formula/ball.hpp"
#include "formula/interval.hpp"
#include "formula/interval_jet.hpp"
#include "formula/jet.hpp"

namespace footpoint::formula {

// Why a formula did not compile. `formula` names the formula ("x", "equations[1]", ...),
// `position` is the 0-based position, in characters, of the character at fault (-1 when there is
// none), `suggestion` what to write there instead when something near is known ("sin" for "sinn",
// "_pi" for "pi", "^" for "**"; empty otherwise). The reader that finds them: formula/syntax.hpp.
struct FormulaError : std::runtime_error {
  enum class Kind { syntax, unknown_variable, unknown_function, empty, too_long, too_complex, bad_constant };
  FormulaError(Kind kind, std::string formula, int position, std::string message,
               std::string suggestion = {});
  Kind kind;
  std::string formula;
  int position;
  std::string suggestion;
};

const char* to_string(FormulaError::Kind kind);

struct NamedFormula {
  std::string name;        // e.g. "x", "y", "z" or "equations[0]"
  std::string expression;  // muparser syntax
};

// The longest formula the compiler reads: muparser 2.3 refuses an expression of
// mu::MaxLenExpression = 20000 characters or more (muParserDef.h), after our reader has taken out
// the whitespace between a function's name and its '('.
inline constexpr std::size_t kLongestFormula = 19999;

struct CompileLimits {
  // Characters per formula, at most kLongestFormula. What a formula costs is bounded by max_nodes
  // (evaluation) and the deadline (what `auto` precomputes), not by its length.
  std::size_t max_formula_length = kLongestFormula;
  std::size_t max_nodes = 20000;  // tape length over all formulas
  // When compiling the whole geometry (with what `auto` precomputes) must be done.
  std::chrono::steady_clock::time_point deadline = std::chrono::steady_clock::time_point::max();
  // The most bytes the geometry's search structure may reach while it is built
  // (geometry/compile_budget.hpp); 0: no bound.
  std::size_t max_geometry_bytes = 0;
};

// A truth value for each of some conditions of a tape's selects (c ? a : b), named by the
// condition's node: the formulas with every select on those conditions replaced by the branch the
// value takes, whatever the condition evaluates to. Over a box where conditions are undecided,
// each point has one truth value per condition, so its value is one of the evaluations over the
// choices of values (the pieces of a piecewise formula, each over the whole box).
struct BranchChoice {
  std::vector<std::int32_t> nodes;  // the conditions' nodes (Program::undecided_conditions)
  std::uint32_t take_b = 0;         // bit k set: nodes[k] is false (its selects take b), else true
  // Whether the condition `node` is given a value, and whether that takes b.
  bool forces(std::int32_t node, bool* b) const {
    for (std::size_t k = 0; k < nodes.size(); ++k)
      if (nodes[k] == node) {
        *b = (take_b >> k) & 1u;
        return true;
      }
    return false;
  }
};

class Program {
 public:
  // The value of a formula without variables ("2*_pi", "a/2" with user constants), evaluated
  // once. Throws FormulaError as compile() does.
  static double constant_value(const NamedFormula& formula, const std::map<std::string, double>& constants,
                               const CompileLimits& limits = {});

  // Compiles the formulas over the given variable names (in that order: input i of every
  // evaluation is variables[i]). `constants` are user constants (name -> value) usable in the
  // formulas; `_pi` and `_e` are always defined to full double precision. Throws FormulaError.
  static Program compile(const std::vector<NamedFormula>& formulas, const std::vector<std::string>& variables,
                         const std::map<std::string, double>& constants, const CompileLimits& limits = {});

  int num_inputs() const;
  int num_outputs() const;
  std::size_t num_nodes() const;
  std::size_t memory_bytes() const;
  // Every formula is a sum of monomials as written (no product or multiple of a sum): jets2
  // evaluates them term by term from a table of powers (polynomial.hpp) instead of the tape.
  bool sum_of_monomials() const;

  // out[k] = value of formula k at x (x has num_inputs() entries).
  void values(const double* x, double* out) const;
  // Value, gradient and Hessian of every formula in one forward pass. Requires N == num_inputs().
  template <int N>
  void jets2(const double* x, Jet2<N>* out) const;
  // Up to third derivatives. Requires N == num_inputs().
  template <int N>
  void jets3(const double* x, Jet3<N>* out) const;
  // Rigorous enclosures of every formula's range over the box x[i] (outward rounded).
  void intervals(const Interval* x, Interval* out) const;
  // Rigorous enclosures over the box x[i] of every formula's value, gradient and Hessian, with
  // flags saying which of them hold where the box meets a kink or a jump (the contract:
  // formula/interval_jet.hpp). Requires N == num_inputs().
  template <int N>
  void interval_jets2(const Interval* x, IntervalJet2<N>* out) const;
  // The same enclosures without the Hessians (cheaper): values, gradients and flags.
  template <int N>
  void interval_jets1(const Interval* x, IntervalJet1<N>* out) const;
  // Rigorous enclosures of every formula's value and gradient at the point x, as balls
  // (formula/ball.hpp): a few times the cost of jets2, for the certificates of answers.
  template <int N>
  void ball_jets1(const double* x, BallJet1<N>* out) const;
  // The conditions of selects (c ? a : b) that the interval arithmetic does not decide over the
  // box x, each once (their nodes; empty when the formulas have no select).
  std::vector<std::int32_t> undecided_conditions(const Interval* x) const;
  // interval_jets2 and ball_jets1 of the formulas with the selects on the conditions of `choice`
  // replaced by the branches it names.
  template <int N>
  void interval_jets2(const Interval* x, IntervalJet2<N>* out, const BranchChoice& choice) const;
  template <int N>
  void ball_jets1(const double* x, BallJet1<N>* out, const BranchChoice& choice) const;
  // Rigorous enclosures of every formula's value at the point x whose radius is the rounding of the
  // value itself, u |f(x)|, plus O(u^2) of the magnitudes met (formula/accurate_values.cpp:
  // double-double arithmetic with error-free transformations): where ball_jets1's radius is
  // O(u) of them, too wide to locate a foot point on two nearly tangent surfaces. Polynomial
  // operations only: false (out unspecified) for a tape with any other operation, or out of range.
  bool accurate_values(const double* x, Ball* out) const;

  // The translations δ != 0 of the inputs under which every formula is invariant, f(x + δ) = f(x)
  // for all x, as far as the formulas' structure proves it (formula/invariant_translations.cpp:
  // affine arguments of sin, cos and tan moved by whole periods, everything else unmoved): those
  // with |δ_i| < extent[i], lexicographically positive (of δ and -δ only the one whose first
  // nonzero entry is positive), shortest first, ties in lexicographic order, at most max_count. One or two
  // inputs; empty for more, and where the formulas are constant along a direction (no lattice).
  std::vector<std::vector<double>> invariant_translations(const std::vector<double>& extent,
                                                          std::size_t max_count = 64) const;

  // The same formulas with every repeated factor at the top of a product taken once
  // (formula/product_factors.cpp): formula k, c g_1^m_1 ... g_r^m_r with c a nonzero constant and
  // integer powers m_i >= 1, becomes g_1 ... g_r when some m_i >= 2 or some factor appears twice.
  // It is defined and vanishes exactly where formula k is and does, but to first order on each
  // {g_i = 0}: (x^2 + y^2 - 1)^2 becomes the circle's regular equation. A Program sharing this
  // one's tape when no formula has a repeated factor.
  Program square_free() const;
  // The systems whose common zeros, united, are this one's (formula/product_factors.cpp): one
  // factor of each formula's top-level product, over every choice, where every factor of a formula
  // is defined on all of R^n (a polynomial, or built with exp, sin, cos, ...): (x^2 + y^2 - 1)
  // ((x - 2)^2 + y^2 - 1) = 0 is the union of two circles. Each has one formula per formula of
  // this one, and their zero sets may meet. A formula with more than max_systems factors is not
  // split; when no formula splits, or when there would be more than max_systems systems, the one
  // system square_free().
  std::vector<Program> factor_systems(std::size_t max_systems) const;
  // True when both evaluate the one tape (a copy, or square_free() of a square-free Program).
  bool same_tape(const Program& other) const { return tape_ == other.tape_; }

  struct Tape;  // opaque

 private:
  friend class ExpressionBuilder;
  // The Program of a tape written by ExpressionBuilder (its polynomial form found as compile's).
  static Program from_tape(Tape tape);

  std::shared_ptr<const Tape> tape_;
};

}  // namespace footpoint::formula
