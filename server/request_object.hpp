// A JSON object of a request read member by member, with the field names its errors give.
#pragma once
#include <string>
#include <vector>

#include "api_error.hpp"
#include "json_reader.hpp"

namespace footpoint::server {

// Reads an object member by member: read_value(name, field) reads each value, field being the
// member's name after `prefix`. A JSON error in the object's structure names `object_field` (at
// its start) or `member_field` (between members); a member named twice is a duplicate_field error.
template <class ReadValue>
void read_object(JsonReader& r, const std::string& object_field, const std::string& member_field,
                 const std::string& prefix, ReadValue&& read_value) {
  at_field(object_field, [&] { r.begin_object(); });
  std::vector<std::string> seen;
  std::string name;
  for (;;) {
    if (!at_field(member_field, [&] { return r.next_member(name); })) break;
    const std::string field = prefix + name;
    for (const auto& s : seen)
      if (s == name) throw ApiError(400, "duplicate_field", field + " appears twice", field);
    seen.push_back(name);
    read_value(name, field);
  }
}

}  // namespace footpoint::server
