#include "mesh_request.hpp"

#include <charconv>
#include <string>

#include "api_error.hpp"

namespace footpoint::server {

namespace {

int hex_digit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

// application/x-www-form-urlencoded: '+' is a space, %XX a byte.
std::string decoded(std::string_view text) {
  std::string out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '+') {
      out += ' ';
    } else if (c == '%' && i + 2 < text.size() && hex_digit(text[i + 1]) >= 0 &&
               hex_digit(text[i + 2]) >= 0) {
      out += static_cast<char>(hex_digit(text[i + 1]) * 16 + hex_digit(text[i + 2]));
      i += 2;
    } else {
      out += c;
    }
  }
  return out;
}

}  // namespace

MeshRequest read_mesh_request(std::string_view query, int max_resolution) {
  MeshRequest request;
  bool have_resolution = false, have_format = false;
  while (!query.empty()) {
    const auto amp = query.find('&');
    const std::string_view pair = query.substr(0, amp);
    query = amp == std::string_view::npos ? std::string_view() : query.substr(amp + 1);
    if (pair.empty()) continue;
    const auto eq = pair.find('=');
    const std::string name = decoded(pair.substr(0, eq));
    const std::string value = eq == std::string_view::npos ? std::string() : decoded(pair.substr(eq + 1));
    if (name == "resolution") {
      if (have_resolution) throw ApiError(400, "duplicate_field", "resolution is given twice", name);
      have_resolution = true;
      long long n = 0;
      const auto r = std::from_chars(value.data(), value.data() + value.size(), n);
      if (r.ec == std::errc::result_out_of_range ||
          (r.ec == std::errc() && r.ptr == value.data() + value.size() && (n < 2 || n > max_resolution)))
        throw ApiError(
            400, "number_out_of_range",
            "resolution must be an integer in [2, " + std::to_string(max_resolution) + "], got " + value,
            name);
      if (r.ec != std::errc() || r.ptr != value.data() + value.size())
        throw ApiError(400, "wrong_type", "resolution must be an integer, got '" + value + "'", name);
      request.resolution = static_cast<int>(n);
    } else if (name == "format") {
      if (have_format) throw ApiError(400, "duplicate_field", "format is given twice", name);
      have_format = true;
      if (value == "json")
        request.format = MeshFormat::json;
      else if (value == "obj")
        request.format = MeshFormat::obj;
      else
        throw ApiError(400, "unknown_format", "format must be json or obj, got '" + value + "'", name);
    } else {
      throw ApiError(400, "unknown_field", "unknown query parameter '" + name + "' (resolution, format)",
                     name);
    }
  }
  return request;
}

}  // namespace footpoint::server
