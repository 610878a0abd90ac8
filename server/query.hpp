// The query of a GET (the target after '?', application/x-www-form-urlencoded): its parameters
// decoded, each allowed name at most once, and integers read with their bounds. Problems are 400
// ApiErrors naming the parameter: unknown_field, duplicate_field, wrong_type, number_out_of_range.
#pragma once
#include <initializer_list>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace footpoint::server {

// The name=value pairs of `query`, in order; a name not in `allowed` is unknown_field, a name
// given twice duplicate_field.
std::vector<std::pair<std::string, std::string>> query_parameters(std::string_view query,
                                                                  std::span<const std::string_view> allowed);
inline std::vector<std::pair<std::string, std::string>> query_parameters(
    std::string_view query, std::initializer_list<std::string_view> allowed) {
  return query_parameters(query, std::span<const std::string_view>(allowed.begin(), allowed.size()));
}

// The integer `value` of parameter `name`, in [min, max].
long long query_integer(const std::string& name, const std::string& value, long long min, long long max);

}  // namespace footpoint::server
