// A pull reader over JSON text (RFC 8259, strict): the request parsers walk the document and
// take exactly the values they expect, so a 10,000-point body is read straight into doubles
// (std::from_chars, exact round trip) with no DOM. Whole-document validity is checked as it
// goes: syntax, UTF-8 in strings, a nesting limit. Errors carry the byte position.
#pragma once
#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace footpoint::server {

struct JsonReadError : std::runtime_error {
  enum class Kind {
    syntax,  // not JSON (or nested deeper than the limit)
    type,    // valid JSON, but not the kind of value the reader was asked for
    range,   // a number too large for a double (e.g. 1e400)
  };
  JsonReadError(Kind kind, std::size_t position, const std::string& message)
      : std::runtime_error(message), kind(kind), position(position) {}
  Kind kind;
  std::size_t position;  // byte offset in the text
};

class JsonReader {
 public:
  enum class Type { object, array, string, number, boolean, null };

  // `max_depth` bounds the nesting of arrays and objects.
  explicit JsonReader(std::string_view text, int max_depth = 64);

  // The type of the next value (whitespace skipped). Syntax error when no value starts here.
  Type peek();
  std::size_t position() const { return pos_; }

  // Objects: begin_object(), then while (next_member(key)) { read the value }.
  void begin_object();
  bool next_member(std::string& key);
  // Arrays: begin_array(), then while (next_element()) { read the value }.
  void begin_array();
  bool next_element();

  double number();  // a finite double (numbers below the subnormal range read as zero)
  std::string string();
  bool boolean();
  void null();
  void skip();  // any one value, fully validated
  // Only whitespace may remain.
  void finish();

  static const char* name(Type type);

 private:
  bool next_item(char close, const char* end_message, const char* separator_message);
  [[noreturn]] void syntax_error(const std::string& message) const;
  [[noreturn]] void type_error(Type expected);
  void skip_whitespace();
  void open();
  void parse_string_into(std::string* out);  // out == nullptr: validate only
  std::string_view scan_number();
  void literal(std::string_view word);

  std::string_view text_;
  std::size_t pos_ = 0;
  int max_depth_;
  // One entry per open container: true while it has no element yet.
  std::vector<char> first_;
};

}  // namespace footpoint::server
