// The body of POST /v1/geometries/{id}/project and POST /v1/project:
//   {"point":[x,y,z]} or {"points":[[x,y,z],...]}, "method", "options":{tolerance, max_iterations,
//   initial, all_minima, trace, max_distance, certify}, "fields":[...] (the members of each
//   result), and for /v1/project the inline "geometry".
// Read in one pass with the pull reader; the points go straight into one flat array of doubles.
#pragma once
#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "compiled/compiled_geometry.hpp"
#include "result_json.hpp"

namespace footpoint::server {

struct ProjectRequest {
  std::optional<GeometryDefinition> geometry;  // the inline "geometry" (POST /v1/project)
  bool single = false;                         // "point" was given (answer "result"), else "points"
  std::vector<double> coords;                  // count * point_length coordinates, point after point
  std::size_t count = 0;
  int point_length = 0;  // coordinates per point (every point has the same)
  std::string method = "auto";
  Options options;                              // options.initial is set when one start serves all points
  std::vector<std::array<double, 3>> initials;  // one start per point (options.initial unset)
  int initial_length = 0;                       // numbers per start (0: no start given)
  // The members each result has: "fields", or all; minima and trace only when the options ask.
  ResultFields fields;
};

// Reads and checks the shape of a request body; throws ApiError (400 for shapes, 413 for more
// than `max_points` points). `inline_geometry` selects POST /v1/project, which requires
// "geometry"; the other route rejects it.
ProjectRequest read_project_request(std::string_view body, bool inline_geometry, std::size_t max_points);

// Checks the request against the geometry it targets (point dimension, method, starts) and returns
// the geometry's method it names.
GeometryMethod check_project_request(const ProjectRequest& request, const CompiledGeometry& geometry);

}  // namespace footpoint::server
