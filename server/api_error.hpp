// The one error a request can end with: an HTTP status and the JSON body
//   {"error":{"code":"...","message":"...","field":"...","position":n,"suggestion":"..."}}
// `code` is stable and machine-readable, `field` names the offending request field when there is
// one ("points[17][2]", "geometry.x", "options.tolerance"), `position` is a character position
// (in the body for malformed JSON, in the formula for a formula that does not compile),
// `suggestion` what to write at that position instead, when something near is known.
#pragma once
#include <stdexcept>
#include <string>
#include <string_view>

#include "json_reader.hpp"

namespace footpoint::server {

struct ApiError : std::runtime_error {
  ApiError(int status, std::string code, const std::string& message, std::string field = {},
           long position = -1, std::string suggestion = {})
      : std::runtime_error(message),
        status(status),
        code(std::move(code)),
        field(std::move(field)),
        position(position),
        suggestion(std::move(suggestion)) {}
  int status;
  std::string code;
  std::string field;       // empty when the error is not about one field
  long position;           // -1 when there is no position
  std::string suggestion;  // empty when there is none
  int retry_after_s = 0;   // the Retry-After header's seconds (429, 503), 0: none
};

// A JSON reading problem at `field` as a 400: malformed_json (syntax; no field), wrong_type or
// number_out_of_range (naming the field).
ApiError request_error(const JsonReadError& error, const std::string& field);

// read() with the reader's errors named at `field`: its value, or request_error(e, field) thrown
// for the JsonReadError e it throws. Every request parser reads its values through this.
template <class Read>
auto at_field(const std::string& field, Read&& read) -> decltype(read()) {
  try {
    return read();
  } catch (const JsonReadError& e) {
    throw request_error(e, field);
  }
}

// A body that is not acceptable JSON (syntax, nesting deeper than the reader's limit) gets
// malformed_json whatever else is wrong with it: the request parsers stop at the first problem
// in document order, so before reporting a shape problem, `error`, they let this check the
// whole body. Returns the malformed_json error, or `error` when the body is well-formed.
ApiError unless_malformed(std::string_view body, ApiError error);

// `noun` with its indefinite article, as error messages name a geometry's type: "an
// implicit_curve", "a parametric_surface".
std::string with_article(std::string_view noun);

// The JSON body of an error response.
std::string error_body(const ApiError& error);

// 400 body_incomplete: a body that ended after `got` of its Content-Length `length` bytes (the
// client closed, or sent nothing for the read timeout).
ApiError body_incomplete(std::size_t got, std::size_t length);

}  // namespace footpoint::server
