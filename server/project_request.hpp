// The body of POST /v1/geometries/{id}/project and POST /v1/project:
//   {"point":[x,y,z]} or {"points":[[x,y,z],...]}, "method", "options":{tolerance, max_iterations,
//   initial, all_minima, trace, max_distance, certify, histogram_bins, tolerance_band}, "fields":[...] (the
//   members of each result), and for /v1/project the inline "geometry".
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
  bool fields_given = false;   // "fields" was given (else fields holds the defaults)
  DeviationOptions deviation;  // options.histogram_bins, options.tolerance_band (stats.deviation)
  // A binary body (read_binary_project_options): little-endian float32 (else float64) numbers.
  bool raw_float32 = false;
};

// Reads and checks the shape of a request body; throws ApiError (400 for shapes, 413 for more
// than `max_points` points). `inline_geometry` selects POST /v1/project, which requires
// "geometry"; the other route rejects it.
ProjectRequest read_project_request(std::string_view body, bool inline_geometry, std::size_t max_points);

// A body of points in binary (Content-Type application/octet-stream): count records of point_dim
// little-endian float64 numbers (float32 with ?dtype=float32), the options as query parameters
// (method, fields=a,b,..., tolerance, max_iterations, initial=a,b, all_minima, max_minima, trace,
// max_distance, certify, histogram_bins, tolerance_band=lo,hi). Reads the query and checks the
// body's length: one that is no whole number of records is 400 wrong_shape with the byte counts.
// The points are not read (coords stays empty): a stream reads them as they arrive.
ProjectRequest read_binary_project_options(std::string_view query, int point_dim, std::size_t body_bytes,
                                           std::size_t max_points);
// The same with the whole body at hand: its points decoded into coords and checked finite.
ProjectRequest read_binary_project_request(std::string_view body, std::string_view query, int point_dim,
                                           std::size_t max_points);
// The bytes of one point of a binary request.
std::size_t binary_record_bytes(const ProjectRequest& request, int point_dim);
// `points` records of a binary request at `raw`, decoded to doubles (point_length each) into out.
void decode_points(const ProjectRequest& request, const char* raw, std::size_t points, double* out);
// The index of the first of `points` decoded points with a coordinate that is NaN or infinite
// (JSON cannot write them), or `points` when there is none.
std::size_t first_not_finite(const ProjectRequest& request, const double* coords, std::size_t points);
// Throws 400 number_out_of_range naming the first such coordinate (its point counted from
// `first_point`, and its byte offset in the body).
void check_finite(const ProjectRequest& request, std::size_t first_point, const double* coords,
                  std::size_t points);

// Checks the request against the geometry it targets (point dimension, method, starts) and returns
// the geometry's method it names.
GeometryMethod check_project_request(const ProjectRequest& request, const CompiledGeometry& geometry);

}  // namespace footpoint::server
