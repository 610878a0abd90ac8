#include "json_writer.hpp"

#include <charconv>
#include <cmath>
#include <cstring>

namespace footpoint::server {

namespace {

// The length of the well-formed UTF-8 sequence starting at s[i] (a byte >= 0x80), or 0 where
// there is none: a continuation byte without its lead, an overlong form, a surrogate, a code point
// past U+10FFFF, or a sequence cut short (RFC 3629 section 4; the Unicode Standard's table 3-7 of
// well-formed byte sequences).
std::size_t utf8_sequence(std::string_view s, std::size_t i) {
  const auto c = static_cast<unsigned char>(s[i]);
  std::size_t n = 0;
  unsigned char low = 0x80, high = 0xBF;  // the second byte's range
  if (c >= 0xC2 && c <= 0xDF) {
    n = 2;
  } else if (c >= 0xE0 && c <= 0xEF) {
    n = 3;
    if (c == 0xE0) low = 0xA0;   // no overlong form
    if (c == 0xED) high = 0x9F;  // no surrogate
  } else if (c >= 0xF0 && c <= 0xF4) {
    n = 4;
    if (c == 0xF0) low = 0x90;   // no overlong form
    if (c == 0xF4) high = 0x8F;  // at most U+10FFFF
  } else {
    return 0;
  }
  if (s.size() - i < n) return 0;
  for (std::size_t k = 1; k < n; ++k) {
    const auto b = static_cast<unsigned char>(s[i + k]);
    if (b < (k == 1 ? low : 0x80) || b > (k == 1 ? high : 0xBF)) return 0;
  }
  return n;
}

}  // namespace

void append_json_string(std::string& out, std::string_view s) {
  static constexpr char hex[] = "0123456789abcdef";
  out += '"';
  std::size_t run = 0;  // start of the pending run of characters that need no escape
  for (std::size_t i = 0; i < s.size(); ++i) {
    const auto c = static_cast<unsigned char>(s[i]);
    if (c >= 0x20 && c < 0x80 && c != '"' && c != '\\') continue;
    if (c >= 0x80) {
      // JSON text is UTF-8 (RFC 8259 section 8.1): a well-formed sequence is copied, any other
      // byte (a path or header of raw bytes, echoed in an error or a log line) becomes U+FFFD
      if (const std::size_t n = utf8_sequence(s, i); n > 0) {
        i += n - 1;
        continue;
      }
      out.append(s.data() + run, i - run);
      run = i + 1;
      out += "\\ufffd";
      continue;
    }
    out.append(s.data() + run, i - run);
    run = i + 1;
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\r':
        out += "\\r";
        break;
      case '\t':
        out += "\\t";
        break;
      case '\b':
        out += "\\b";
        break;
      case '\f':
        out += "\\f";
        break;
      default:
        out += "\\u00";
        out += hex[c >> 4];
        out += hex[c & 15];
    }
  }
  out.append(s.data() + run, s.size() - run);
  out += '"';
}

void append_shortest(std::string& out, double x) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  out.append(buf, r.ptr);
}

void JsonWriter::quoted(std::string_view s) {
  // Whether any byte needs an escape or a UTF-8 check (no early exit: the loop vectorises).
  bool special = s.size() + 2 > sizeof buf_;
  for (const char ch : s) {
    const auto c = static_cast<unsigned char>(ch);
    special |= (c < 0x20) | (c >= 0x80) | (c == '"') | (c == '\\');
  }
  if (special) {
    flush();
    append_json_string(*out_, s);
    return;
  }
  room(s.size() + 2);
  *p_++ = '"';
  std::memcpy(p_, s.data(), s.size());
  p_ += s.size();
  *p_++ = '"';
}

void JsonWriter::number(double x) {
  before_value();
  room(32);
  if (std::isfinite(x)) {
    p_ = std::to_chars(p_, p_ + 32, x).ptr;
  } else {
    std::memcpy(p_, "null", 4);
    p_ += 4;
  }
}

void JsonWriter::integer(long long x) {
  before_value();
  room(24);
  p_ = std::to_chars(p_, p_ + 24, x).ptr;
}

void JsonWriter::numbers(const double* x, int n) {
  begin_array();
  for (int k = 0; k < n; ++k) number(x[k]);
  end_array();
}

}  // namespace footpoint::server
