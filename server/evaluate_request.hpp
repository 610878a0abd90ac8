// POST /v1/geometries/{id}/evaluate: a parametric geometry at given parameters, to check a
// parametrisation and to sample it.
//   request  {"parameter": [u, v]} or {"parameters": [[u, v], ...]} ([t] for curves),
//            "derivatives": 0 | 1 | 2 (default 0), "normals": true | false (default false)
//   response {"geometry_id", "result" | "results": [{"parameters", "point", "inside_domain",
//            "derivatives": {"u": [...], "v": [...]} | {"t": [...]},
//            "second_derivatives": {"uu", "uv", "vv"} | {"tt"}, "normal": [...] | null}], "stats"}
// Numbers as the projection writes them (shortest round trip; null when not finite).
#pragma once
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "compiled/compiled_geometry.hpp"

namespace footpoint::server {

struct EvaluateRequest {
  bool single = false;         // "parameter" was given (answer "result"), else "parameters"
  std::vector<double> values;  // count * length parameters, one set after the other
  std::size_t count = 0;
  int length = 0;
  int derivatives = 0;  // 0, 1 or 2: which derivatives each result has
  bool normals = false;
};

// Reads and checks the shape of a body; throws ApiError (400; 413 beyond `max_rows` sets).
EvaluateRequest read_evaluate_request(std::string_view body, std::size_t max_rows);

// Evaluates the geometry at every set of parameters and writes the response body. Throws
// ApiError: 400 not_parametric for an implicit curve, wrong_dimension for sets of the wrong length.
std::string evaluate_response(const CompiledGeometry& geometry, const EvaluateRequest& request);

}  // namespace footpoint::server
