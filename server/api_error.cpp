#include "api_error.hpp"

#include "json_writer.hpp"

namespace footpoint::server {

ApiError request_error(const JsonReadError& error, const std::string& field) {
  const auto position = static_cast<long>(error.position);
  switch (error.kind) {
    case JsonReadError::Kind::syntax:
      return ApiError(400, "malformed_json", std::string("malformed JSON: ") + error.what(), {}, position);
    case JsonReadError::Kind::type:
      return ApiError(400, "wrong_type", field + ": " + error.what(), field, position);
    case JsonReadError::Kind::range:
      return ApiError(400, "number_out_of_range", field + ": " + error.what(), field, position);
  }
  return ApiError(400, "malformed_json", error.what(), {}, position);
}

ApiError unless_malformed(std::string_view body, ApiError error) {
  if (error.code == "malformed_json") return error;
  try {
    JsonReader reader(body);
    reader.skip();
    reader.finish();
  } catch (const JsonReadError& e) {
    if (e.kind == JsonReadError::Kind::syntax) return request_error(e, {});
  }
  return error;
}

std::string error_body(const ApiError& error) {
  JsonWriter w;
  w.begin_object();
  w.key("error");
  w.begin_object();
  w.key("code");
  w.string(error.code);
  w.key("message");
  w.string(error.what());
  if (!error.field.empty()) {
    w.key("field");
    w.string(error.field);
  }
  if (error.position >= 0) {
    w.key("position");
    w.integer(error.position);
  }
  if (!error.suggestion.empty()) {
    w.key("suggestion");
    w.string(error.suggestion);
  }
  w.end_object();
  w.end_object();
  return w.take();
}

std::string with_article(std::string_view noun) {
  const bool vowel = !noun.empty() && std::string_view("aeiou").find(noun.front()) != std::string_view::npos;
  return (vowel ? "an " : "a ") + std::string(noun);
}

ApiError body_incomplete(std::size_t got, std::size_t length) {
  return ApiError(
      400, "body_incomplete",
      "the body ended after " + std::to_string(got) + " of its " + std::to_string(length) + " bytes", "body");
}

}  // namespace footpoint::server
