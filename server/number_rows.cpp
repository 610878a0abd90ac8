#include "number_rows.hpp"

#include "api_error.hpp"

namespace footpoint::server {

namespace {

std::string indexed(const std::string& name, std::size_t i) { return name + "[" + std::to_string(i) + "]"; }

}  // namespace

int read_row(JsonReader& r, const std::string& name, std::vector<double>& values) {
  int n = 0;
  bool started = false;
  try {
    r.begin_array();
    started = true;
    while (r.next_element()) {
      if (n == 3) throw ApiError(400, "wrong_dimension", name + " has more than 3 numbers", name);
      values.push_back(r.number());
      ++n;
    }
  } catch (const JsonReadError& e) {
    throw request_error(e, started ? indexed(name, static_cast<std::size_t>(n)) : name);
  }
  if (n == 0) throw ApiError(400, "wrong_dimension", name + " is empty", name);
  return n;
}

std::size_t read_rows(JsonReader& r, const std::string& name, std::size_t max_rows,
                      std::vector<double>& values, int& length) {
  std::size_t i = 0;
  int j = 0;
  bool started = false, in_row = false;  // where a reading error happened, to name the field
  try {
    r.begin_array();
    started = true;
    while (r.next_element()) {
      if (i == max_rows)
        throw ApiError(
            413, "too_many_points",
            "more than " + std::to_string(max_rows) + " " + name +
                " in one request, the limit (--max-points): split the batch into requests of at most " +
                std::to_string(max_rows) + " " + name,
            name);
      j = 0;
      r.begin_array();
      in_row = true;
      while (r.next_element()) {
        if (j == 3)
          throw ApiError(400, "wrong_dimension", indexed(name, i) + " has more than 3 numbers",
                         indexed(name, i));
        values.push_back(r.number());
        ++j;
      }
      in_row = false;
      if (j == 0) throw ApiError(400, "wrong_dimension", indexed(name, i) + " is empty", indexed(name, i));
      if (i == 0) {
        length = j;
      } else if (j != length) {
        throw ApiError(400, "wrong_dimension",
                       indexed(name, i) + " has " + std::to_string(j) + " numbers, " + name + "[0] has " +
                           std::to_string(length),
                       indexed(name, i));
      }
      ++i;
    }
  } catch (const JsonReadError& e) {
    throw request_error(e, !started ? name
                           : in_row ? indexed(name, i) + "[" + std::to_string(j) + "]"
                                    : indexed(name, i));
  }
  if (i == 0) throw ApiError(400, "empty_batch", name + " is empty", name);
  return i;
}

}  // namespace footpoint::server
