#include "evaluate_request.hpp"

#include <cmath>

#include "api_error.hpp"
#include "json_reader.hpp"
#include "json_writer.hpp"
#include "number_rows.hpp"
#include "request_object.hpp"

namespace footpoint::server {

namespace {

EvaluateRequest read_request(std::string_view body, std::size_t max_rows) {
  EvaluateRequest request;
  JsonReader r(body);
  bool has_one = false, has_many = false;
  read_object(r, "body", "body", "", [&](const std::string& key, const std::string&) {
    try {
      if (key == "parameter") {
        request.length = read_row(r, "parameter", request.values);
        request.count = 1;
        has_one = true;
      } else if (key == "parameters") {
        request.count = read_rows(r, "parameters", max_rows, request.values, request.length);
        has_many = true;
      } else if (key == "derivatives") {
        const double d = r.number();
        if (!(d == 0.0 || d == 1.0 || d == 2.0))
          throw ApiError(400, "invalid_option", "derivatives must be 0, 1 or 2", "derivatives");
        request.derivatives = static_cast<int>(d);
      } else if (key == "normals") {
        request.normals = r.boolean();
      } else {
        throw ApiError(400, "unknown_field",
                       "unknown field " + key + " (parameter, parameters, derivatives, normals)" +
                           (key == "point" || key == "points"
                                ? ": evaluate takes parameters; points are projected with POST "
                                  "/v1/geometries/{id}/project"
                                : ""),
                       key);
      }
    } catch (const JsonReadError& e) {
      throw request_error(e, key);
    }
    if (has_one && has_many)
      throw ApiError(400, "conflicting_fields", "give either parameter or parameters, not both",
                     "parameters");
  });
  try {
    r.finish();
  } catch (const JsonReadError& e) {
    throw request_error(e, "body");
  }
  if (!has_one && !has_many)
    throw ApiError(400, "missing_field", "parameter (one set) or parameters (a batch) is required",
                   "parameter");
  request.single = has_one;
  return request;
}

void vector(JsonAppender& o, const Vec3& v, int dim) {
  const double x[3] = {v.x, v.y, v.z};
  o.numbers(x, dim);
}

}  // namespace

EvaluateRequest read_evaluate_request(std::string_view body, std::size_t max_rows) {
  try {
    return read_request(body, max_rows);
  } catch (const ApiError& e) {
    throw unless_malformed(body, e);
  }
}

std::string evaluate_response(const CompiledGeometry& geometry, const EvaluateRequest& request) {
  const int params = geometry.num_params();
  const char* type = to_string(geometry.definition().type);
  if (params == 0)
    throw ApiError(400, "not_parametric",
                   with_article(type) +
                       " has no parameters to evaluate at: project points onto it with POST "
                       "/v1/geometries/{id}/project, or look at it with GET /v1/geometries/{id}/mesh",
                   "id");
  if (request.length != params)
    throw ApiError(400, "wrong_dimension",
                   std::string(request.single ? "parameter" : "parameters") + " must have " +
                       std::to_string(params) + " numbers for this " + type + " (" +
                       (params == 2 ? "[u, v]" : "[t]") + "), got " + std::to_string(request.length),
                   request.single ? "parameter" : "parameters[0]");
  const int dim = geometry.point_dim();
  static const char* const first_names[2][2] = {{",\"t\":", ""}, {",\"u\":", ",\"v\":"}};
  static const char* const second_names[2][3] = {{",\"tt\":", "", ""}, {",\"uu\":", ",\"uv\":", ",\"vv\":"}};
  const int kind = params - 1;
  std::string out;
  out.reserve(128 + request.count * (64 + 64 * request.derivatives * params + (request.normals ? 64 : 0)));
  JsonAppender o(out);
  o.literal("{\"geometry_id\":");
  o.string(geometry.id());
  o.literal(request.single ? ",\"result\":" : ",\"results\":[");
  std::size_t inside = 0;
  for (std::size_t i = 0; i < request.count; ++i) {
    const double* t = request.values.data() + i * static_cast<std::size_t>(params);
    Evaluation e;
    geometry.evaluate(t, e);
    inside += e.inside_domain;
    o.literal(i ? ",{\"parameters\":" : "{\"parameters\":");
    o.numbers(t, params);
    o.literal(",\"point\":");
    vector(o, e.point, dim);
    o.literal(e.inside_domain ? ",\"inside_domain\":true" : ",\"inside_domain\":false");
    if (request.derivatives >= 1) {
      o.literal(",\"derivatives\":{");
      for (int k = 0; k < params; ++k) {
        o.literal(std::string_view(first_names[kind][k]).substr(k == 0 ? 1 : 0));
        vector(o, e.first[k], dim);
      }
      o.literal("}");
    }
    if (request.derivatives >= 2) {
      o.literal(",\"second_derivatives\":{");
      for (int k = 0; k < 2 * params - 1; ++k) {
        o.literal(std::string_view(second_names[kind][k]).substr(k == 0 ? 1 : 0));
        vector(o, e.second[k], dim);
      }
      o.literal("}");
    }
    if (request.normals) {
      o.literal(",\"normal\":");
      if (e.normal_defined)
        vector(o, e.normal, dim);
      else
        o.literal("null");
    }
    o.literal("}");
  }
  o.literal(request.single ? ",\"stats\":{\"parameters\":" : "],\"stats\":{\"parameters\":");
  o.integer(static_cast<long long>(request.count));
  o.literal(",\"inside_domain\":");
  o.integer(static_cast<long long>(inside));
  o.literal("}}");
  o.flush();
  return out;
}

}  // namespace footpoint::server
