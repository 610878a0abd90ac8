// A value, or the error that stands in its place: std::expected of C++23, in the part this code
// needs. A caller's mistake that it must handle (a method name the geometry does not have) is such
// an error value, not an exception.
#pragma once
#include <stdexcept>
#include <utility>
#include <variant>

namespace footpoint {

template <class T, class E>
class [[nodiscard]] Expected {
 public:
  Expected(T value) : state_(std::in_place_index<0>, std::move(value)) {}
  Expected(E error) : state_(std::in_place_index<1>, std::move(error)) {}

  bool has_value() const { return state_.index() == 0; }
  explicit operator bool() const { return has_value(); }

  // The value. Asking an error for its value is a programming error: std::logic_error.
  const T& value() const& {
    if (!has_value()) throw std::logic_error("Expected: the value of an error");
    return std::get<0>(state_);
  }
  T&& value() && {
    if (!has_value()) throw std::logic_error("Expected: the value of an error");
    return std::get<0>(std::move(state_));
  }
  const T& operator*() const& { return value(); }
  T&& operator*() && { return std::move(*this).value(); }
  const T* operator->() const { return &value(); }

  // The error; only when !has_value().
  const E& error() const { return std::get<1>(state_); }

 private:
  std::variant<T, E> state_;
};

}  // namespace footpoint
