// The one JSON writer of the service: JSON text written straight into a string, no DOM. Numbers
// in the shortest form that reads back as the same double (std::to_chars), never NaN or infinity
// (a non-finite number is written as null); strings escaped (bytes that are no well-formed UTF-8
// become U+FFFD); commas placed automatically. The text goes through a small buffer appended to
// the string in blocks, so that a result of a large batch costs a few appends rather than one per
// token.
//   JsonWriter w;                              // into its own string: w.take()
//   JsonWriter w(out);                         // appended to `out` (flushed by the destructor)
//   w.begin_object(); w.key("distance"); w.number(0.5); w.end_object();
#pragma once
#include <concepts>
#include <cstddef>
#include <cstring>
#include <string>
#include <string_view>
#include <type_traits>

namespace footpoint::server {

// A member name written as a literal in the code, checked when it is compiled to need no escape
// (printable ASCII, no quote or backslash), so that the writer copies it as it is.
class JsonName {
 public:
  template <std::size_t N>
  consteval JsonName(const char (&name)[N])  // NOLINT(google-explicit-constructor): literals convert
      : text_(name, N - 1) {
    if (N > 256) throw "a JSON name literal must be short";  // (the writer's buffer holds it)
    for (const char c : text_)
      if (c < 0x20 || c > 0x7e || c == '"' || c == '\\') throw "a JSON name literal must need no escape";
  }
  std::string_view text() const { return text_; }

 private:
  std::string_view text_;
};

class JsonWriter {
 public:
  // Into a string of its own, `reserve` bytes reserved.
  explicit JsonWriter(std::size_t reserve = 256) : out_(&own_) { own_.reserve(reserve); }
  // Appended to `out`, which must outlive the writer; out holds the text after flush() or the
  // writer's end.
  explicit JsonWriter(std::string& out) : out_(&out) {}
  ~JsonWriter() { flush(); }
  JsonWriter(const JsonWriter&) = delete;
  JsonWriter& operator=(const JsonWriter&) = delete;

  void begin_object() { open('{'); }
  void end_object() { close('}'); }
  void begin_array() { open('['); }
  void end_array() { close(']'); }
  // An object member's name; the next call writes its value. A literal name is copied as it is
  // (JsonName); any other string is escaped as string() escapes it.
  void key(JsonName name) {
    const std::string_view s = name.text();
    room(s.size() + 4);
    if (!first_) *p_++ = ',';
    *p_++ = '"';
    std::memcpy(p_, s.data(), s.size());
    p_ += s.size();
    *p_++ = '"';
    *p_++ = ':';
    first_ = false;
    after_key_ = true;
  }
  template <class S>
  requires(std::convertible_to<const S&, std::string_view> && !std::is_array_v<S>) void key(const S& name) {
    if (!first_) put(',');
    first_ = false;
    quoted(std::string_view(name));
    put(':');
    after_key_ = true;
  }

  void string(std::string_view s) {
    before_value();
    quoted(s);
  }
  // Shortest round-trip form; null when x is NaN or infinite.
  void number(double x);
  void integer(long long x);
  void boolean(bool b) { literal(b ? std::string_view("true") : std::string_view("false")); }
  void null() { literal("null"); }
  // [x[0], ..., x[n-1]], each as number() writes it.
  void numbers(const double* x, int n);
  // An already serialized JSON value, copied as it is.
  void raw(std::string_view json) { literal(json); }

  // The text written so far, in the writer's own string (the first constructor).
  const std::string& str() {
    flush();
    return own_;
  }
  std::string take() {
    flush();
    return std::move(own_);
  }
  // Appends what the buffer holds to the string.
  void flush() {
    out_->append(buf_, static_cast<std::size_t>(p_ - buf_));
    p_ = buf_;
  }

 private:
  void before_value() {
    if (!first_ && !after_key_) put(',');
    first_ = false;
    after_key_ = false;
  }
  void open(char c) {
    before_value();
    put(c);
    first_ = true;
  }
  // After a container closes, its parent holds at least one element: no stack is needed.
  void close(char c) {
    put(c);
    first_ = false;
  }
  void literal(std::string_view text) {
    before_value();
    copy(text);
  }
  // The JSON string literal of s; names of plain characters (the keys, the status and method
  // names) are copied as they are, anything else escaped.
  void quoted(std::string_view s);
  void put(char c) {
    room(1);
    *p_++ = c;
  }
  void copy(std::string_view text) {
    if (text.size() > sizeof buf_) {
      flush();
      out_->append(text);
      return;
    }
    room(text.size());
    std::memcpy(p_, text.data(), text.size());
    p_ += text.size();
  }
  void room(std::size_t n) {
    if (static_cast<std::size_t>(buf_ + sizeof buf_ - p_) < n) flush();
  }

  std::string own_;
  std::string* out_;
  char buf_[2048];
  char* p_ = buf_;
  bool first_ = true;       // nothing written yet in the current container (or at top level)
  bool after_key_ = false;  // a key was just written: the value follows without a comma
};

// Appends the JSON string literal for s (quotes and escapes included). Bytes of s that are no
// well-formed UTF-8 are written as U+FFFD, so that the text is valid JSON whatever s holds.
void append_json_string(std::string& out, std::string_view s);
// Appends the shortest round-trip form of a finite x (caller checks finiteness).
void append_shortest(std::string& out, double x);

}  // namespace footpoint::server
