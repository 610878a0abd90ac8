// The binary form of projection results (Accept: application/octet-stream): one fixed-size record
// per point, in the order of the points, each the requested fields' numbers as little-endian
// IEEE-754 float64, in the result's own order:
//   foot_point (point_dim), parameters (num_params; none for implicit curves), distance,
//   normal (point_dim), signed_distance, status (the index in the Status list of openapi.yaml:
//   converged 0, max_iterations 1, diverged 2, non_finite 3, degenerate 4, outside_domain 5,
//   not_orthogonal 6, beyond_max_distance 7, deadline_exceeded 8), converged (1 or 0), iterations,
//   residual, step_norm, starts, location (interior 0, edge 1, corner 2, endpoint 3, box_face 4,
//   singular_point 5, pole 6, kink 7, unknown 8).
// NaN stands where the JSON form has null. Without "fields": foot_point, parameters, distance,
// normal, signed_distance and status. The response header X-Footpoint-Record names the columns
// ("foot_point:3,parameters:2,distance:1,...") so that a reader need not know these rules.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "projection/projection_result.hpp"
#include "result_json.hpp"

namespace footpoint::server {

struct BinaryLayout {
  std::vector<std::pair<ResultFields::Member, int>> columns;  // member, numbers
  std::size_t record_bytes() const;
  std::string describe() const;  // "foot_point:3,distance:1"
};

// The layout of `fields` (the defaults above when !fields_given) for a geometry with point_dim and
// num_params; 400 unsupported_field for a member that is no number (method, certificate,
// multiplicity, minima, trace).
BinaryLayout binary_layout(ResultFields fields, bool fields_given, int point_dim, int num_params);

// Appends r's record; returns its reported status.
Status append_record(std::string& out, const ProjectionResult& r, const BinaryLayout& layout);

}  // namespace footpoint::server
