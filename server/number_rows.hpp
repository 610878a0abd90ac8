// Rows of numbers in a request body: one row ("point": [x, y, z], "parameter": [u, v]) or a
// batch ("points": [[x, y, z], ...], "parameters": [[u, v], ...]), read with the pull reader
// straight into one flat array of doubles, every row 1 to 3 numbers long and all of one length.
// Problems are ApiErrors naming the field ("points[17][2]"); more rows than the limit is 413
// too_many_points (--max-points bounds every batch).
#pragma once
#include <cstddef>
#include <string>
#include <vector>

#include "json_reader.hpp"

namespace footpoint::server {

// "name": [a, b(, c)] appended to `values`; returns its length.
int read_row(JsonReader& r, const std::string& name, std::vector<double>& values);

// "name": [[...], ...] appended to `values`, at most `max_rows` rows of one length, which goes
// to `length`; returns the number of rows (at least one).
std::size_t read_rows(JsonReader& r, const std::string& name, std::size_t max_rows,
                      std::vector<double>& values, int& length);

}  // namespace footpoint::server
