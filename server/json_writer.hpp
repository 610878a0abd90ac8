// Writes JSON text directly into a string: numbers in the shortest form that reads back as the
// same double (std::to_chars), never NaN or infinity (a non-finite number is written as null),
// commas placed automatically. Used for every response; no DOM on the hot path.
#pragma once
#include <cstddef>
#include <cstring>
#include <string>
#include <string_view>

namespace footpoint::server {

class JsonWriter {
 public:
  explicit JsonWriter(std::size_t reserve = 256) { out_.reserve(reserve); }

  void begin_object() { open('{'); }
  void end_object() { close('}'); }
  void begin_array() { open('['); }
  void end_array() { close(']'); }
  // An object member's name; the next call writes its value.
  void key(std::string_view name);

  void string(std::string_view s);
  // Shortest round-trip form; null when x is NaN or infinite.
  void number(double x);
  void integer(long long x);
  void boolean(bool b);
  void null();
  // An already serialized JSON value, copied as it is.
  void raw(std::string_view json);

  const std::string& str() const { return out_; }
  std::string take() { return std::move(out_); }

 private:
  void before_value() {
    if (!first_ && !after_key_) out_ += ',';
    first_ = false;
    after_key_ = false;
  }
  void open(char c) {
    before_value();
    out_ += c;
    first_ = true;
  }
  // After a container closes, its parent holds at least one element: no stack is needed.
  void close(char c) {
    out_ += c;
    first_ = false;
  }

  std::string out_;
  bool first_ = true;       // nothing written yet in the current container (or at top level)
  bool after_key_ = false;  // a key was just written: the value follows without a comma
};

// The hot-path writer for large responses: the caller writes the punctuation and keys as
// literal fragments ("],\"distance\":"), numbers and strings; the text is gathered in a small
// buffer and appended to `out` in blocks, so a result costs a few appends instead of dozens.
// Numbers as in JsonWriter (shortest round trip, null when not finite).
class JsonAppender {
 public:
  explicit JsonAppender(std::string& out) : out_(out) {}
  ~JsonAppender() { flush(); }
  JsonAppender(const JsonAppender&) = delete;
  JsonAppender& operator=(const JsonAppender&) = delete;

  // JSON text written as it is (no escaping): punctuation, keys, names known to be plain ASCII.
  // Inline, so that a literal's copy is a few moves of a known length, not a call to memcpy.
  void literal(std::string_view text) {
    if (text.size() > sizeof buf_) return literal_large(text);
    room(text.size());
    std::memcpy(p_, text.data(), text.size());
    p_ += text.size();
  }
  void number(double x);
  void integer(long long x);
  void string(std::string_view s);
  // [x0,x1,...]
  void numbers(const double* x, int n);
  void flush() {
    out_.append(buf_, static_cast<std::size_t>(p_ - buf_));
    p_ = buf_;
  }

 private:
  void literal_large(std::string_view text);
  void room(std::size_t n) {
    if (static_cast<std::size_t>(buf_ + sizeof buf_ - p_) < n) flush();
  }
  std::string& out_;
  char buf_[2048];
  char* p_ = buf_;
};

// Appends the JSON string literal for s (quotes and escapes included). Bytes of s that are no
// well-formed UTF-8 are written as U+FFFD, so that the text is valid JSON whatever s holds.
void append_json_string(std::string& out, std::string_view s);
// Appends the shortest round-trip form of a finite x (caller checks finiteness).
void append_shortest(std::string& out, double x);

}  // namespace footpoint::server
