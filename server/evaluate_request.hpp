// POST /v1/geometries/{id}/evaluate: a parametric geometry at given parameters, to check a
// parametrisation and to sample it; an implicit one's equations at given points, to check them.
//   request  {"parameter": [u, v]} or {"parameters": [[u, v], ...]} ([t] for curves); for implicit
//            geometries {"point": [x, y(, z)]} or {"points": [...]};
//            "derivatives": 0 | 1 | 2 (default 0), "normals": true | false (default false)
//   response {"geometry_id", "result" | "results": [{"parameters", "point", "inside_domain",
//            "derivatives": {"u": [...], "v": [...]} | {"t": [...]},
//            "second_derivatives": {"uu", "uv", "vv"} | {"tt"}, "normal": [...] | null}], "stats"}
//            implicit: [{"point", "inside_box", "value" (f) | "values" ([f1, f2], space curves),
//            "gradient" | "gradients", "hessian" | "hessians" (rows), "normal": grad f / |grad f|
//            | null}], "stats": {"points", "inside_box"}
// Numbers as the projection writes them (shortest round trip; null when not finite).
#pragma once
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "compiled/compiled_geometry.hpp"

namespace footpoint::server {

struct EvaluateRequest {
  bool single = false;         // "parameter" or "point" was given (answer "result"), else a batch
  bool points = false;         // the rows are points ("point", "points"), not parameters
  std::vector<double> values;  // count * length numbers, one row after the other
  std::size_t count = 0;
  int length = 0;
  int derivatives = 0;  // 0, 1 or 2: which derivatives each result has
  bool normals = false;
};

// Reads and checks the shape of a body; throws ApiError (400; 413 beyond `max_rows` sets).
EvaluateRequest read_evaluate_request(std::string_view body, std::size_t max_rows);

// Evaluates the geometry at every set of parameters (its equations at every point) and writes the
// response body. Throws ApiError: 400 not_parametric (parameters for an implicit geometry),
// not_implicit (points for a parametric one), wrong_dimension for rows of the wrong length.
std::string evaluate_response(const CompiledGeometry& geometry, const EvaluateRequest& request);

}  // namespace footpoint::server
