#include "query.hpp"

#include <charconv>
#include <system_error>

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

std::vector<std::pair<std::string, std::string>> query_parameters(std::string_view query,
                                                                  std::span<const std::string_view> allowed) {
  std::vector<std::pair<std::string, std::string>> out;
  while (!query.empty()) {
    const auto amp = query.find('&');
    const std::string_view pair = query.substr(0, amp);
    query = amp == std::string_view::npos ? std::string_view() : query.substr(amp + 1);
    if (pair.empty()) continue;
    const auto eq = pair.find('=');
    std::string name = decoded(pair.substr(0, eq));
    std::string value = eq == std::string_view::npos ? std::string() : decoded(pair.substr(eq + 1));
    bool known = false;
    std::string names;
    for (const auto a : allowed) {
      known = known || a == name;
      (names += names.empty() ? "" : ", ") += a;
    }
    if (!known)
      throw ApiError(400, "unknown_field", "unknown query parameter '" + name + "' (" + names + ")", name);
    for (const auto& [seen, v] : out)
      if (seen == name) throw ApiError(400, "duplicate_field", name + " is given twice", name);
    out.emplace_back(std::move(name), std::move(value));
  }
  return out;
}

long long query_integer(const std::string& name, const std::string& value, long long min, long long max) {
  long long n = 0;
  const auto r = std::from_chars(value.data(), value.data() + value.size(), n);
  const bool whole = r.ptr == value.data() + value.size();
  if (r.ec == std::errc::result_out_of_range || (r.ec == std::errc() && whole && (n < min || n > max)))
    throw ApiError(400, "number_out_of_range",
                   name + " must be an integer in [" + std::to_string(min) + ", " + std::to_string(max) +
                       "], got " + value,
                   name);
  if (r.ec != std::errc() || !whole)
    throw ApiError(400, "wrong_type", name + " must be an integer, got '" + value + "'", name);
  return n;
}

}  // namespace footpoint::server
