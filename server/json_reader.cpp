#include "json_reader.hpp"

#include <charconv>
#include <cmath>
#include <cstdlib>

namespace footpoint::server {

namespace {

bool is_digit(char c) { return c >= '0' && c <= '9'; }

int hex_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

void append_utf8(std::string& out, unsigned cp) {
  if (cp < 0x80) {
    out += static_cast<char>(cp);
  } else if (cp < 0x800) {
    out += static_cast<char>(0xC0 | (cp >> 6));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  } else if (cp < 0x10000) {
    out += static_cast<char>(0xE0 | (cp >> 12));
    out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  } else {
    out += static_cast<char>(0xF0 | (cp >> 18));
    out += static_cast<char>(0x80 | ((cp >> 12) & 0x3F));
    out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  }
}

}  // namespace

JsonReader::JsonReader(std::string_view text, int max_depth) : text_(text), max_depth_(max_depth) {
  first_.reserve(8);
}

const char* JsonReader::name(Type type) {
  switch (type) {
    case Type::object:
      return "an object";
    case Type::array:
      return "an array";
    case Type::string:
      return "a string";
    case Type::number:
      return "a number";
    case Type::boolean:
      return "a boolean";
    case Type::null:
      return "null";
  }
  return "a value";
}

void JsonReader::syntax_error(const std::string& message) const {
  throw JsonReadError(JsonReadError::Kind::syntax, pos_, message);
}

void JsonReader::type_error(Type expected) {
  const Type found = peek();
  throw JsonReadError(JsonReadError::Kind::type, pos_,
                      std::string("expected ") + name(expected) + ", found " + name(found));
}

void JsonReader::skip_whitespace() {
  while (pos_ < text_.size()) {
    const char c = text_[pos_];
    if (c != ' ' && c != '\n' && c != '\r' && c != '\t') return;
    ++pos_;
  }
}

JsonReader::Type JsonReader::peek() {
  skip_whitespace();
  if (pos_ >= text_.size()) syntax_error("unexpected end of input");
  const char c = text_[pos_];
  switch (c) {
    case '{':
      return Type::object;
    case '[':
      return Type::array;
    case '"':
      return Type::string;
    case 't':
    case 'f':
      return Type::boolean;
    case 'n':
      return Type::null;
    default:
      if (c == '-' || is_digit(c)) return Type::number;
  }
  if (c == 'N' || c == 'I' || c == '+')
    syntax_error("invalid number: NaN, Infinity and a leading '+' are not JSON");
  if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7F)
    syntax_error("unexpected character");
  syntax_error(std::string("unexpected character '") + c + "'");
}

void JsonReader::open() {
  if (static_cast<int>(first_.size()) >= max_depth_)
    syntax_error("nesting deeper than " + std::to_string(max_depth_) + " levels");
  ++pos_;  // the '{' or '['
  first_.push_back(1);
}

void JsonReader::begin_object() {
  if (peek() != Type::object) type_error(Type::object);
  open();
}

void JsonReader::begin_array() {
  if (peek() != Type::array) type_error(Type::array);
  open();
}

// After an opening bracket or an item: the closing bracket (false) or, from the second item on,
// the comma before the next item (true).
bool JsonReader::next_item(char close, const char* end_message, const char* separator_message) {
  skip_whitespace();
  if (pos_ >= text_.size()) syntax_error(end_message);
  if (text_[pos_] == close) {
    ++pos_;
    first_.pop_back();
    return false;
  }
  if (first_.back()) {
    first_.back() = 0;
  } else {
    if (text_[pos_] != ',') syntax_error(separator_message);
    ++pos_;
  }
  return true;
}

bool JsonReader::next_member(std::string& key) {
  if (!next_item('}', "unexpected end of input in an object", "expected ',' or '}'")) return false;
  skip_whitespace();
  if (pos_ >= text_.size() || text_[pos_] != '"') syntax_error("expected a member name (a string)");
  key.clear();
  parse_string_into(&key);
  skip_whitespace();
  if (pos_ >= text_.size() || text_[pos_] != ':') syntax_error("expected ':'");
  ++pos_;
  return true;
}

bool JsonReader::next_element() {
  return next_item(']', "unexpected end of input in an array", "expected ',' or ']'");
}

std::string_view JsonReader::scan_number() {
  // number = [ "-" ] ( "0" / digit1-9 *digit ) [ "." 1*digit ] [ ( "e" / "E" ) [ "-" / "+" ] 1*digit ]
  const std::size_t start = pos_;
  const std::size_t n = text_.size();
  if (pos_ < n && text_[pos_] == '-') ++pos_;
  if (pos_ >= n || !is_digit(text_[pos_])) syntax_error("invalid number");
  if (text_[pos_] == '0') {
    ++pos_;
    if (pos_ < n && is_digit(text_[pos_])) syntax_error("invalid number: leading zero");
  } else {
    while (pos_ < n && is_digit(text_[pos_])) ++pos_;
  }
  if (pos_ < n && text_[pos_] == '.') {
    ++pos_;
    if (pos_ >= n || !is_digit(text_[pos_])) syntax_error("invalid number: digit expected after '.'");
    while (pos_ < n && is_digit(text_[pos_])) ++pos_;
  }
  if (pos_ < n && (text_[pos_] == 'e' || text_[pos_] == 'E')) {
    ++pos_;
    if (pos_ < n && (text_[pos_] == '+' || text_[pos_] == '-')) ++pos_;
    if (pos_ >= n || !is_digit(text_[pos_])) syntax_error("invalid number: digit expected in the exponent");
    while (pos_ < n && is_digit(text_[pos_])) ++pos_;
  }
  return text_.substr(start, pos_ - start);
}

double JsonReader::number() {
  if (peek() != Type::number) type_error(Type::number);
  const std::size_t start = pos_;
  const std::string_view s = scan_number();
  double value = 0.0;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), value);
  if (r.ec == std::errc::result_out_of_range) {
    // Overflow or underflow: strtod tells them apart (HUGE_VAL vs. zero / subnormal).
    const std::string copy(s);
    value = std::strtod(copy.c_str(), nullptr);
    if (!std::isfinite(value))
      throw JsonReadError(JsonReadError::Kind::range, start,
                          "number " + copy + " is outside the range of a double");
  } else if (r.ec != std::errc() || r.ptr != s.data() + s.size()) {
    pos_ = start;
    syntax_error("invalid number");
  }
  return value;
}

void JsonReader::parse_string_into(std::string* out) {
  ++pos_;  // opening quote
  const std::size_t n = text_.size();
  for (;;) {
    // Copy the run of plain ASCII characters in one go.
    std::size_t run = pos_;
    while (pos_ < n) {
      const auto c = static_cast<unsigned char>(text_[pos_]);
      if (c == '"' || c == '\\' || c < 0x20 || c >= 0x80) break;
      ++pos_;
    }
    if (out) out->append(text_.data() + run, pos_ - run);
    if (pos_ >= n) syntax_error("unterminated string");
    const auto c = static_cast<unsigned char>(text_[pos_]);
    if (c == '"') {
      ++pos_;
      return;
    }
    if (c < 0x20) syntax_error("control character in a string (escape it)");
    if (c == '\\') {
      if (pos_ + 1 >= n) syntax_error("unterminated string");
      const char e = text_[pos_ + 1];
      char plain = 0;
      switch (e) {
        case '"':
          plain = '"';
          break;
        case '\\':
          plain = '\\';
          break;
        case '/':
          plain = '/';
          break;
        case 'b':
          plain = '\b';
          break;
        case 'f':
          plain = '\f';
          break;
        case 'n':
          plain = '\n';
          break;
        case 'r':
          plain = '\r';
          break;
        case 't':
          plain = '\t';
          break;
        case 'u':
          break;
        default:
          syntax_error("invalid escape in a string");
      }
      if (plain) {
        if (out) *out += plain;
        pos_ += 2;
        continue;
      }
      auto read_hex4 = [&](std::size_t at) -> unsigned {
        if (at + 4 > n) syntax_error("invalid \\u escape");
        unsigned v = 0;
        for (std::size_t k = 0; k < 4; ++k) {
          const int h = hex_value(text_[at + k]);
          if (h < 0) syntax_error("invalid \\u escape");
          v = v * 16 + static_cast<unsigned>(h);
        }
        return v;
      };
      unsigned cp = read_hex4(pos_ + 2);
      pos_ += 6;
      if (cp >= 0xDC00 && cp <= 0xDFFF) syntax_error("lone low surrogate in a \\u escape");
      if (cp >= 0xD800 && cp <= 0xDBFF) {
        if (pos_ + 1 >= n || text_[pos_] != '\\' || text_[pos_ + 1] != 'u')
          syntax_error("high surrogate without its low surrogate");
        const unsigned low = read_hex4(pos_ + 2);
        if (low < 0xDC00 || low > 0xDFFF) syntax_error("high surrogate without its low surrogate");
        cp = 0x10000 + ((cp - 0xD800) << 10) + (low - 0xDC00);
        pos_ += 6;
      }
      if (out) append_utf8(*out, cp);
      continue;
    }
    // A multi-byte UTF-8 sequence: check its length, continuation bytes, overlong forms,
    // surrogates and the U+10FFFF ceiling.
    std::size_t len = 0;
    unsigned cp = 0;
    if (c >= 0xC2 && c <= 0xDF) {
      len = 2;
      cp = c & 0x1F;
    } else if (c >= 0xE0 && c <= 0xEF) {
      len = 3;
      cp = c & 0x0F;
    } else if (c >= 0xF0 && c <= 0xF4) {
      len = 4;
      cp = c & 0x07;
    } else {
      syntax_error("invalid UTF-8 in a string");
    }
    if (pos_ + len > n) syntax_error("invalid UTF-8 in a string");
    for (std::size_t k = 1; k < len; ++k) {
      const auto b = static_cast<unsigned char>(text_[pos_ + k]);
      if ((b & 0xC0) != 0x80) syntax_error("invalid UTF-8 in a string");
      cp = (cp << 6) | (b & 0x3F);
    }
    if ((len == 3 && cp < 0x800) || (len == 4 && (cp < 0x10000 || cp > 0x10FFFF)) ||
        (cp >= 0xD800 && cp <= 0xDFFF))
      syntax_error("invalid UTF-8 in a string");
    if (out) out->append(text_.data() + pos_, len);
    pos_ += len;
  }
}

std::string JsonReader::string() {
  if (peek() != Type::string) type_error(Type::string);
  std::string s;
  parse_string_into(&s);
  return s;
}

void JsonReader::literal(std::string_view word) {
  if (text_.substr(pos_, word.size()) != word) syntax_error("invalid literal");
  pos_ += word.size();
}

bool JsonReader::boolean() {
  if (peek() != Type::boolean) type_error(Type::boolean);
  if (text_[pos_] == 't') {
    literal("true");
    return true;
  }
  literal("false");
  return false;
}

void JsonReader::null() {
  if (peek() != Type::null) type_error(Type::null);
  literal("null");
}

void JsonReader::skip() {
  switch (peek()) {
    case Type::object: {
      begin_object();
      std::string key;
      while (next_member(key)) skip();
      return;
    }
    case Type::array:
      begin_array();
      while (next_element()) skip();
      return;
    case Type::string:
      parse_string_into(nullptr);
      return;
    case Type::number:
      scan_number();
      return;
    case Type::boolean:
      boolean();
      return;
    case Type::null:
      literal("null");
      return;
  }
}

void JsonReader::finish() {
  skip_whitespace();
  if (pos_ != text_.size()) syntax_error("unexpected data after the JSON value");
}

}  // namespace footpoint::server
