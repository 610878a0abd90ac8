// The formula reader (syntax.hpp): a lexer and a recursive descent over the grammar, failing at the
// first fault with our own message, the character position and a suggestion where one is near.
#include "formula/syntax.hpp"

#include <algorithm>
#include <charconv>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <system_error>
#include <utility>

namespace footpoint::formula {

namespace {

bool is_digit(char c) { return c >= '0' && c <= '9'; }
bool is_name_start(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_'; }
bool is_name_char(char c) { return is_name_start(c) || is_digit(c); }
bool is_space(char c) { return c > 0 && c <= ' '; }

char lower(char c) { return c >= 'A' && c <= 'Z' ? static_cast<char>(c - 'A' + 'a') : c; }

bool equal_ignoring_case(std::string_view a, std::string_view b) {
  return a.size() == b.size() &&
         std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) { return lower(x) == lower(y); });
}

// Edits (insertion, deletion, substitution, transposition of neighbours) between a and b, ignoring
// case: the optimal string alignment distance.
std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::vector<std::size_t>> d(a.size() + 1, std::vector<std::size_t>(b.size() + 1));
  for (std::size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (std::size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i)
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t cost = lower(a[i - 1]) == lower(b[j - 1]) ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && lower(a[i - 1]) == lower(b[j - 2]) && lower(a[i - 2]) == lower(b[j - 1]))
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  return d[a.size()][b.size()];
}

// The candidate nearest to `name`: the same letters in another case, else the fewest edits within
// what a typo makes (one edit from three letters on, two from six; a two-letter name only the one
// letter it lacks, as cs of cos, for every other two letters are one edit from it; none for one
// letter). "" when none is near.
std::string nearest(std::string_view name, const std::vector<std::string_view>& candidates) {
  for (const auto c : candidates)
    if (equal_ignoring_case(name, c)) return std::string(c);
  const std::size_t allowed = name.size() >= 6 ? 2 : name.size() >= 2 ? 1 : 0;
  std::string best;
  std::size_t best_distance = allowed + 1;
  for (const auto c : candidates) {
    if (name.size() == 2 && c.size() != 3) continue;
    const std::size_t d = edit_distance(name, c);
    if (d < best_distance) {
      best_distance = d;
      best = std::string(c);
    }
  }
  return best;
}

// Names from other notations, and what the language writes instead. In a replacement, $a and $b
// stand for the call's first and second argument.
struct Alias {
  std::string_view name;
  std::string_view replacement;
};
constexpr Alias kFunctionAliases[] = {
    {"pow", "$a^$b"},     {"power", "$a^$b"},  {"sqr", "$a^2"},      {"hypot", "sqrt($a^2+$b^2)"},
    {"exp2", "2^$a"},     {"exp10", "10^$a"},  {"arcsin", "asin"},   {"arccos", "acos"},
    {"arctan", "atan"},   {"arsinh", "asinh"}, {"arcsinh", "asinh"}, {"arcosh", "acosh"},
    {"arccosh", "acosh"}, {"artanh", "atanh"}, {"arctanh", "atanh"}, {"sgn", "sign"},
    {"signum", "sign"},   {"fabs", "abs"},     {"lg", "log10"},      {"ld", "log2"},
    {"lb", "log2"},       {"loge", "ln"},      {"fmin", "min"},      {"fmax", "max"},
};
constexpr Alias kNameAliases[] = {{"pi", "_pi"}, {"e", "_e"}, {"M_PI", "_pi"}, {"M_E", "_e"}};

// Characters from typeset mathematics, and what the language writes instead.
struct CharacterHint {
  char32_t code;
  std::string_view replacement;
};
constexpr CharacterHint kCharacterHints[] = {
    {U'\u00B7', "*"},  {U'\u00D7', "*"},  {U'\u22C5', "*"},    {U'\u2217', "*"},   {U'\u2219', "*"},
    {U'\u00F7', "/"},  {U'\u2215', "/"},  {U'\u2044', "/"},    {U'\u2212', "-"},   {U'\u2013', "-"},
    {U'\u2014', "-"},  {U'\u00B2', "^2"}, {U'\u00B3', "^3"},   {U'\u03C0', "_pi"}, {U'\u2264', "<="},
    {U'\u2265', ">="}, {U'\u2260', "!="}, {U'\u221A', "sqrt"}, {U'\u00A0', " "},   {U'[', "("},
    {U']', ")"},       {U'{', "("},       {U'}', ")"},
};

enum class Tok { end, number, name, open, close, comma, question, colon, op };

struct Token {
  Tok kind = Tok::end;
  std::size_t begin = 0, end = 0;  // bytes of the formula
};

class Reader {
 public:
  Reader(const NamedFormula& formula, const std::vector<std::string>& variables,
         const std::map<std::string, double>& constants)
      : formula_(formula), text_(formula.expression), variables_(variables), constants_(constants) {}

  std::string read() {
    ternary(0);
    const Token t = peek();
    switch (t.kind) {
      case Tok::end:
        break;
      case Tok::close:
        fail(FormulaError::Kind::syntax, t.begin, "')' at position " + at(t) + " closes no '('");
      case Tok::comma:
        fail(FormulaError::Kind::syntax, t.begin,
             "',' at position " + at(t) + " outside a function's arguments: a formula is one expression");
      case Tok::colon:
        stray_colon(t);
      default:
        unexpected(t);
    }
    std::string muparser_text;
    std::size_t from = 0;
    for (const auto& [begin, end] : removed_) {
      muparser_text.append(text_, from, begin - from);
      from = end;
    }
    muparser_text.append(text_, from, std::string::npos);
    return muparser_text;
  }

 private:
  // ---- errors ---------------------------------------------------------------------------------
  // The 0-based position, in characters (UTF-8 sequences), of the byte `byte`.
  int position(std::size_t byte) const {
    int n = 0;
    for (std::size_t i = 0; i < byte && i < text_.size(); ++i)
      n += (static_cast<unsigned char>(text_[i]) & 0xC0) != 0x80;
    return n;
  }
  std::string at(const Token& t) const { return std::to_string(position(t.begin)); }
  std::string_view text(const Token& t) const {
    return std::string_view(text_).substr(t.begin, t.end - t.begin);
  }
  std::string quoted(const Token& t) const {
    std::string q = "'";
    q.append(text(t));
    q += '\'';
    return q;
  }

  [[noreturn]] void fail(FormulaError::Kind kind, std::size_t byte, const std::string& message,
                         std::string suggestion = {}) const {
    throw FormulaError(kind, formula_.name, position(byte), "formula " + formula_.name + ": " + message,
                       std::move(suggestion));
  }
  [[noreturn]] void unexpected(const Token& t) const {
    fail(FormulaError::Kind::syntax, t.begin, "unexpected " + quoted(t) + " at position " + at(t));
  }
  [[noreturn]] void stray_colon(const Token& t) const {
    fail(FormulaError::Kind::syntax, t.begin,
         "':' at position " + at(t) + " belongs to no '?' (a conditional is c ? a : b)");
  }
  // An operand is missing where `t` stands.
  [[noreturn]] void operand_expected(const Token& t) const {
    switch (t.kind) {
      case Tok::end:
        if (!last_) fail(FormulaError::Kind::syntax, 0, "an operand is missing");
        fail(FormulaError::Kind::syntax, last_->begin,
             "the formula ends after " + quoted(*last_) + " at position " + at(*last_) +
                 ": an operand is missing");
      case Tok::close:
      case Tok::comma:
        fail(FormulaError::Kind::syntax, t.begin,
             "an operand is missing before " + quoted(t) + " at position " + at(t));
      case Tok::question:
        fail(FormulaError::Kind::syntax, t.begin,
             "'?' at position " + at(t) + " follows no condition (a conditional is c ? a : b)");
      default:
        fail(FormulaError::Kind::syntax, t.begin,
             quoted(t) + " at position " + at(t) + " stands where an operand is expected");
    }
  }

  // ---- tokens ---------------------------------------------------------------------------------
  std::size_t skip_space(std::size_t i) const {
    while (i < text_.size() && is_space(text_[i])) ++i;
    return i;
  }

  Token peek() const { return lex(skip_space(pos_)); }
  Token next() {
    const Token t = peek();
    pos_ = t.end;
    last_ = t;
    return t;
  }

  Token lex(std::size_t i) const {
    if (i >= text_.size()) return {Tok::end, i, i};
    const char c = text_[i];
    const char d = i + 1 < text_.size() ? text_[i + 1] : '\0';
    auto one = [&](Tok kind) { return Token{kind, i, i + 1}; };
    if (is_digit(c) || (c == '.' && is_digit(d))) return number(i);
    if (is_name_start(c)) {
      std::size_t e = i;
      while (e < text_.size() && is_name_char(text_[e])) ++e;
      return {Tok::name, i, e};
    }
    switch (c) {
      case '(':
        return one(Tok::open);
      case ')':
        return one(Tok::close);
      case ',':
        return one(Tok::comma);
      case '?':
        return one(Tok::question);
      case ':':
        return one(Tok::colon);
      case '+':
      case '-':
      case '/':
      case '^':
        return one(Tok::op);
      case '*':
        if (d == '*')
          fail(
              FormulaError::Kind::syntax, i,
              "'**' at position " + std::to_string(position(i)) + " is not an operator: powers are written ^",
              "^");
        return one(Tok::op);
      case '<':
      case '>':
        if (d == '=') return {Tok::op, i, i + 2};
        if (c == '<' && d == '>')
          fail(FormulaError::Kind::syntax, i,
               "'<>' at position " + std::to_string(position(i)) +
                   " is not an operator: write != for 'not equal'",
               "!=");
        return one(Tok::op);
      case '=':
        if (d == '=') return {Tok::op, i, i + 2};
        if (d == '<' || d == '>') {
          const std::string fix = std::string(1, d) + "=";
          fail(FormulaError::Kind::syntax, i,
               "'=" + std::string(1, d) + "' at position " + std::to_string(position(i)) +
                   " is not an operator: write " + fix,
               fix);
        }
        fail(FormulaError::Kind::syntax, i,
             "'=' at position " + std::to_string(position(i)) +
                 " would assign, which a formula cannot: write == to compare",
             "==");
      case '!':
        if (d == '=') return {Tok::op, i, i + 2};
        fail(FormulaError::Kind::syntax, i,
             "'!' at position " + std::to_string(position(i)) +
                 " is not an operator: write != for 'not equal', x == 0 for 'not x'");
      case '&':
      case '|':
        if (d == c) return {Tok::op, i, i + 2};
        fail(FormulaError::Kind::syntax, i,
             std::string("'") + c + "' at position " + std::to_string(position(i)) +
                 " is not an operator: write " + c + c,
             std::string(2, c));
      default:
        bad_character(i);
    }
  }

  // digits [. digits] [e [+-] digits], or . digits [...]; the value must fit a double.
  Token number(std::size_t i) const {
    std::size_t e = i;
    while (e < text_.size() && is_digit(text_[e])) ++e;
    if (e < text_.size() && text_[e] == '.') {
      ++e;
      while (e < text_.size() && is_digit(text_[e])) ++e;
    }
    if (e < text_.size() && (text_[e] == 'e' || text_[e] == 'E')) {
      std::size_t x = e + 1;
      if (x < text_.size() && (text_[x] == '+' || text_[x] == '-')) ++x;
      if (x < text_.size() && is_digit(text_[x])) {
        while (x < text_.size() && is_digit(text_[x])) ++x;
        e = x;
      } else if (x == e + 1 ? !(x < text_.size() && is_name_char(text_[x])) : true) {
        // "2e", "2e+", "2e-u": an exponent without digits (a name such as "2ex" is a missing operator)
        fail(FormulaError::Kind::syntax, i,
             "number '" + text_.substr(i, x - i) + "' at position " + std::to_string(position(i)) +
                 " has an exponent without digits (write e.g. 2e5 or 2.5e-3)");
      }
    }
    double value = 0.0;
    const auto r = std::from_chars(text_.data() + i, text_.data() + e, value);
    if (r.ec == std::errc::result_out_of_range && overflows(i, e))
      fail(FormulaError::Kind::syntax, i,
           "number '" + text_.substr(i, e - i) + "' at position " + std::to_string(position(i)) +
               " is beyond the largest double (about 1.8e308)");
    return {Tok::number, i, e};
  }

  // Whether the number in [i, e), out of a double's range, is too large rather than too small (a
  // too small one reads as 0, as muparser reads it).
  bool overflows(std::size_t i, std::size_t e) const {
    long exponent = 0;  // decimal exponent of the first significant digit
    std::size_t k = i;
    long integer_digits = 0;
    bool significant = false;
    for (; k < e && is_digit(text_[k]); ++k) {
      significant = significant || text_[k] != '0';
      integer_digits += significant;
    }
    if (integer_digits > 0) {
      exponent = integer_digits - 1;
    } else if (k < e && text_[k] == '.') {
      long zeros = 0;
      for (++k; k < e && text_[k] == '0'; ++k) ++zeros;
      exponent = -zeros - 1;
    }
    const auto mark = text_.find_first_of("eE", i);
    if (mark != std::string::npos && mark < e) {
      // The written exponent saturates at ±10^9, beyond any double's and any formula's digits:
      // one too long for a long (from_chars: out of range) keeps its sign, and the sum cannot
      // overflow.
      constexpr long kSaturated = 1000000000;
      const char* first = text_.data() + mark + 1 + (text_[mark + 1] == '+');
      long written = 0;
      if (std::from_chars(first, text_.data() + e, written).ec == std::errc::result_out_of_range)
        written = *first == '-' ? -kSaturated : kSaturated;
      exponent += std::clamp(written, -kSaturated, kSaturated);
    }
    return exponent > 0;
  }

  [[noreturn]] void bad_character(std::size_t i) const {
    // Decode the UTF-8 sequence at i (an invalid one shows as its first byte).
    const auto b = static_cast<unsigned char>(text_[i]);
    const int length = b < 0x80 ? 1 : (b >> 5) == 6 ? 2 : (b >> 4) == 14 ? 3 : (b >> 3) == 30 ? 4 : 1;
    char32_t code = length == 1 ? b : b & (0x3F >> (length - 1));
    bool valid = i + length <= text_.size();
    for (int k = 1; valid && k < length; ++k) {
      const auto cont = static_cast<unsigned char>(text_[i + k]);
      valid = (cont & 0xC0) == 0x80;
      code = (code << 6) | (cont & 0x3F);
    }
    char unicode[16];
    std::snprintf(unicode, sizeof unicode, "U+%04X", static_cast<unsigned>(valid ? code : b));
    const std::string shown = b < 0x20 || b == 0x7F ? std::string() : valid ? text_.substr(i, length) : "";
    std::string message = "unexpected character " + (shown.empty() ? std::string() : "'" + shown + "' ") +
                          "(" + unicode + ") at position " + std::to_string(position(i));
    for (const auto& hint : kCharacterHints)
      if (valid && hint.code == code) {
        message += "; write " + std::string(hint.replacement) + " instead";
        fail(FormulaError::Kind::syntax, i, message, std::string(hint.replacement));
      }
    fail(FormulaError::Kind::syntax, i, message + " (the operators are + - * / ^ < > <= >= == != && || ? :)");
  }

  // ---- grammar --------------------------------------------------------------------------------
  void ternary(int depth) {
    if (depth > kMaxNesting)
      fail(FormulaError::Kind::too_complex, pos_,
           "parentheses, calls and conditionals nested more than " + std::to_string(kMaxNesting) + " deep");
    chain(depth);
    const Token q = peek();
    if (q.kind != Tok::question) return;
    next();
    ternary(depth + 1);
    if (peek().kind != Tok::colon)
      fail(FormulaError::Kind::syntax, q.begin,
           "'?' at position " + at(q) + " has no ':' (a conditional is c ? a : b)");
    next();
    ternary(depth + 1);
  }

  void chain(int depth) {
    operand(depth);
    for (;;) {
      const Token t = peek();
      if (t.kind == Tok::op) {
        next();
        operand(depth);
      } else if (t.kind == Tok::number || t.kind == Tok::name || t.kind == Tok::open) {
        fail(FormulaError::Kind::syntax, t.begin,
             "an operator is missing before " + quoted(t) + " at position " + at(t) +
                 " (products are written a*b)");
      } else {
        return;
      }
    }
  }

  void operand(int depth) {
    const Token t = peek();
    if (t.kind == Tok::op && (text(t) == "+" || text(t) == "-")) {
      next();
      const Token u = peek();
      if (u.kind == Tok::op && (text(u) == "+" || text(u) == "-"))
        fail(FormulaError::Kind::syntax, u.begin,
             "a second sign " + quoted(u) + " at position " + at(u) + " (write -(-x), or one sign)");
    }
    primary(depth);
  }

  void primary(int depth) {
    const Token t = peek();
    switch (t.kind) {
      case Tok::number:
        next();
        return;
      case Tok::name:
        name(t, depth);
        return;
      case Tok::open: {
        next();
        const Token u = peek();
        if (u.kind == Tok::close)
          fail(FormulaError::Kind::syntax, u.begin, "nothing between '(' at position " + at(t) + " and ')'");
        ternary(depth + 1);
        const Token c = peek();
        if (c.kind == Tok::close) {
          next();
          return;
        }
        if (c.kind == Tok::end)
          fail(FormulaError::Kind::syntax, t.begin, "'(' at position " + at(t) + " is not closed");
        if (c.kind == Tok::comma)
          fail(FormulaError::Kind::syntax, c.begin,
               "',' at position " + at(c) + " inside parentheses that are no function's arguments");
        if (c.kind == Tok::colon) stray_colon(c);
        unexpected(c);
      }
      default:
        operand_expected(t);
    }
  }

  const FunctionSignature* function(std::string_view n) const {
    for (const auto& f : function_signatures())
      if (f.name == n) return &f;
    return nullptr;
  }

  bool is_value_name(std::string_view n) const {
    return n == "_pi" || n == "_e" || constants_.count(std::string(n)) > 0 ||
           std::find(variables_.begin(), variables_.end(), n) != variables_.end();
  }

  void name(const Token& t, int depth) {
    const std::string_view n = text(t);
    const std::size_t after = skip_space(t.end);
    const bool called = after < text_.size() && text_[after] == '(';
    if (const FunctionSignature* f = function(n)) {
      if (!called)
        fail(FormulaError::Kind::syntax, t.begin,
             std::string(n) + " at position " + at(t) + " is a function: write " + std::string(n) + "(x)");
      if (after > t.end) removed_.emplace_back(t.end, after);
      next();
      call(t, *f, depth);
      return;
    }
    if (is_value_name(n)) {
      next();
      return;
    }
    if (called) unknown_function(t, depth);
    unknown_name(t);
  }

  // The arguments of a call at the reader's position, '(' to ')': their spans; empty when they do
  // not parse.
  std::vector<std::pair<std::size_t, std::size_t>> arguments(int depth) {
    std::vector<std::pair<std::size_t, std::size_t>> spans;
    try {
      next();  // '('
      for (;;) {
        const std::size_t begin = skip_space(pos_);
        ternary(depth + 1);
        spans.emplace_back(begin, pos_);
        const Token t = next();
        if (t.kind == Tok::close) return spans;
        if (t.kind != Tok::comma) return {};
      }
    } catch (const FormulaError&) {
      return {};
    }
  }

  void call(const Token& name, const FunctionSignature& f, int depth) {
    const Token open = next();
    if (peek().kind == Tok::close)
      fail(FormulaError::Kind::syntax, name.begin,
           std::string(f.name) + " at position " + at(name) + " needs an argument: " + std::string(f.name) +
               "(x)");
    int count = 0;
    for (;;) {
      ternary(depth + 1);
      ++count;
      const Token t = peek();
      if (t.kind == Tok::comma) {
        next();
        continue;
      }
      if (t.kind == Tok::close) {
        next();
        break;
      }
      if (t.kind == Tok::end)
        fail(FormulaError::Kind::syntax, open.begin,
             "'(' at position " + at(open) + " (the call of " + std::string(f.name) + ") is not closed");
      if (t.kind == Tok::colon) stray_colon(t);
      unexpected(t);
    }
    if (f.arity > 0 && count != f.arity)
      fail(FormulaError::Kind::syntax, name.begin,
           std::string(f.name) + " at position " + at(name) + " takes " + std::to_string(f.arity) +
               " argument" + (f.arity == 1 ? "" : "s") + ", not " + std::to_string(count));
  }

  std::string function_list() const {
    std::string s;
    for (const auto& f : function_signatures()) (s += s.empty() ? "" : ", ") += f.name;
    return s;
  }

  // An argument as it reads inside a^b: a name, a number, a call or a parenthesized whole as it is,
  // anything else in parentheses.
  std::string operand_text(std::pair<std::size_t, std::size_t> span) const {
    std::string s = text_.substr(span.first, span.second - span.first);
    while (!s.empty() && is_space(s.back())) s.pop_back();
    const bool simple = std::all_of(s.begin(), s.end(), [](char c) { return is_name_char(c) || c == '.'; });
    bool enclosed = false;
    if (!simple && !s.empty() && s.back() == ')') {
      // the '(' matching the last ')' starts the text, or follows a name that does
      int level = 0;
      std::size_t k = s.size();
      while (k-- > 0) {
        level += s[k] == ')' ? 1 : s[k] == '(' ? -1 : 0;
        if (level == 0) break;
      }
      enclosed =
          k < s.size() && std::all_of(s.begin(), s.begin() + static_cast<std::ptrdiff_t>(k), is_name_char);
    }
    return simple || enclosed ? s : "(" + s + ")";
  }

  [[noreturn]] void unknown_function(const Token& t, int depth) {
    const std::string n(text(t));
    std::string suggestion;
    for (const auto& alias : kFunctionAliases)
      if (alias.name == n) suggestion = alias.replacement;
    if (suggestion.find('$') != std::string::npos) {
      // written with the arguments: the call's own when it has as many, else the letters a, b
      next();  // the name
      const auto spans = arguments(depth);
      const std::size_t wanted = suggestion.find("$b") != std::string::npos ? 2 : 1;
      std::string filled;
      for (std::size_t k = 0; k < suggestion.size(); ++k) {
        if (suggestion[k] != '$' || k + 1 == suggestion.size()) {
          filled += suggestion[k];
          continue;
        }
        const std::size_t arg = suggestion[++k] == 'a' ? 0 : 1;
        filled += spans.size() == wanted ? operand_text(spans[arg]) : std::string(1, suggestion[k]);
      }
      suggestion = filled;
    }
    if (suggestion.empty()) {
      std::vector<std::string_view> names;
      for (const auto& f : function_signatures()) names.push_back(f.name);
      suggestion = nearest(n, names);
    }
    fail(FormulaError::Kind::unknown_function, t.begin,
         "unknown function '" + n + "' at position " + at(t) +
             (suggestion.empty() ? "" : "; did you mean " + suggestion + "?") +
             " (the functions: " + function_list() + ")",
         suggestion);
  }

  [[noreturn]] void unknown_name(const Token& t) const {
    const std::string n(text(t));
    std::vector<std::string_view> names(variables_.begin(), variables_.end());
    for (const auto& [c, value] : constants_) names.push_back(c);
    names.push_back("_pi");
    names.push_back("_e");
    std::string suggestion = nearest(n, names);
    if (suggestion.empty())
      for (const auto& alias : kNameAliases)
        if (equal_ignoring_case(alias.name, n)) suggestion = alias.replacement;
    std::string known;
    for (const auto& v : variables_) (known += known.empty() ? "" : ", ") += v;
    std::string constants = "_pi, _e";
    for (const auto& [c, value] : constants_) constants += ", " + c;
    fail(FormulaError::Kind::unknown_variable, t.begin,
         "unknown name '" + n + "' at position " + at(t) +
             (suggestion.empty() ? "" : "; did you mean " + suggestion + "?") +
             " (the variables: " + (known.empty() ? "none" : known) + "; the constants: " + constants + ")",
         suggestion);
  }

  const NamedFormula& formula_;
  const std::string& text_;
  const std::vector<std::string>& variables_;
  const std::map<std::string, double>& constants_;
  std::size_t pos_ = 0;                                       // after the last token read
  std::optional<Token> last_;                                 // the last token read
  std::vector<std::pair<std::size_t, std::size_t>> removed_;  // whitespace between a function and '('
};

}  // namespace

std::string check_syntax(const NamedFormula& formula, const std::vector<std::string>& variables,
                         const std::map<std::string, double>& constants) {
  return Reader(formula, variables, constants).read();
}

}  // namespace footpoint::formula
