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
    at_field(key, [&] {
      if (key == "parameter" || key == "point") {
        if (has_one || has_many)
          throw ApiError(400, "conflicting_fields", "give one of parameter, parameters, point, points", key);
        request.length = read_row(r, key, request.values);
        request.count = 1;
        request.points = key == "point";
        has_one = true;
      } else if (key == "parameters" || key == "points") {
        if (has_one || has_many)
          throw ApiError(400, "conflicting_fields", "give one of parameter, parameters, point, points", key);
        request.count = read_rows(r, key, max_rows, request.values, request.length);
        request.points = key == "points";
        has_many = true;
      } else if (key == "derivatives") {
        const double d = r.number();
        if (!(d == 0.0 || d == 1.0 || d == 2.0))
          throw ApiError(400, "invalid_option", "derivatives must be 0, 1 or 2", "derivatives");
        request.derivatives = static_cast<int>(d);
      } else if (key == "normals") {
        request.normals = r.boolean();
      } else {
        throw ApiError(
            400, "unknown_field",
            "unknown field " + key + " (parameter, parameters, point, points, derivatives, normals)", key);
      }
    });
  });
  at_field("body", [&] { r.finish(); });
  if (!has_one && !has_many)
    throw ApiError(400, "missing_field",
                   "parameter or parameters (a parametric geometry), point or points (an implicit one) is "
                   "required",
                   "parameter");
  request.single = has_one;
  return request;
}

void vector(JsonWriter& o, const Vec3& v, int dim) {
  const double x[3] = {v.x, v.y, v.z};
  o.numbers(x, dim);
}

// {"geometry_id": ..., "result": or "results": [
void begin(JsonWriter& o, const CompiledGeometry& geometry, const EvaluateRequest& request) {
  o.begin_object();
  o.key("geometry_id");
  o.string(geometry.id());
  o.key(request.single ? "result" : "results");
  if (!request.single) o.begin_array();
}

// "normal": [...] or null
void normal(JsonWriter& o, bool defined, const Vec3& n, int dim) {
  o.key("normal");
  if (defined)
    vector(o, n, dim);
  else
    o.null();
}

// The end of the results and the counts: {"<rows>": n, "<inside>": k}.
void stats(JsonWriter& o, const EvaluateRequest& request, std::string_view rows, std::string_view inside_name,
           std::size_t inside) {
  if (!request.single) o.end_array();
  o.key("stats");
  o.begin_object();
  o.key(rows);
  o.integer(static_cast<long long>(request.count));
  o.key(inside_name);
  o.integer(static_cast<long long>(inside));
  o.end_object();
  o.end_object();
  o.flush();
}

}  // namespace

EvaluateRequest read_evaluate_request(std::string_view body, std::size_t max_rows) {
  try {
    return read_request(body, max_rows);
  } catch (const ApiError& e) {
    throw unless_malformed(body, e);
  }
}

namespace {

// An implicit geometry's equations at each point.
std::string equations_response(const CompiledGeometry& geometry, const EvaluateRequest& request) {
  const int dim = geometry.point_dim();
  const char* type = to_string(geometry.definition().type);
  const char* field = request.single ? "point" : "points";
  if (request.length != dim)
    throw ApiError(400, "wrong_dimension",
                   std::string(field) + " must have " + std::to_string(dim) + " coordinates for this " +
                       type + ", got " + std::to_string(request.length),
                   request.single ? "point" : "points[0]");
  std::string out;
  out.reserve(128 + request.count * (96 + 64 * request.derivatives * dim + (request.normals ? 64 : 0)));
  JsonWriter o(out);
  begin(o, geometry, request);
  std::size_t inside = 0;
  for (std::size_t i = 0; i < request.count; ++i) {
    const double* x = request.values.data() + i * static_cast<std::size_t>(dim);
    EquationEvaluation e;
    geometry.evaluate_equations(x, e);
    inside += e.inside_box;
    const bool two = e.equations == 2;  // a space curve: f1, f2
    o.begin_object();
    o.key("point");
    o.numbers(x, dim);
    o.key("inside_box");
    o.boolean(e.inside_box);
    if (two) {
      o.key("values");
      o.numbers(e.value.data(), 2);
    } else {
      o.key("value");
      o.number(e.value[0]);
    }
    if (request.derivatives >= 1) {
      o.key(two ? "gradients" : "gradient");
      if (two) o.begin_array();
      for (int k = 0; k < e.equations; ++k) vector(o, e.gradient[static_cast<std::size_t>(k)], dim);
      if (two) o.end_array();
    }
    if (request.derivatives >= 2) {
      o.key(two ? "hessians" : "hessian");
      if (two) o.begin_array();
      for (int k = 0; k < e.equations; ++k) {
        o.begin_array();
        for (int row = 0; row < dim; ++row)
          vector(o, e.hessian[static_cast<std::size_t>(k)][static_cast<std::size_t>(row)], dim);
        o.end_array();
      }
      if (two) o.end_array();
    }
    if (request.normals) normal(o, e.normal_defined, e.normal, dim);
    o.end_object();
  }
  stats(o, request, "points", "inside_box", inside);
  return out;
}

}  // namespace

std::string evaluate_response(const CompiledGeometry& geometry, const EvaluateRequest& request) {
  const int params = geometry.num_params();
  const char* type = to_string(geometry.definition().type);
  if (params == 0) {
    if (!request.points)
      throw ApiError(400, "not_parametric",
                     with_article(type) +
                         " has no parameters to evaluate at: evaluate its equations at points with "
                         "{\"points\": [[x, y, z], ...]}, project points with POST "
                         "/v1/geometries/{id}/project, or look at it with GET /v1/geometries/{id}/mesh",
                     request.single ? "parameter" : "parameters");
    return equations_response(geometry, request);
  }
  if (request.points)
    throw ApiError(
        400, "not_implicit",
        with_article(type) +
            " is evaluated at parameters ({\"parameters\": [[u, v], ...]}, [t] for curves); points "
            "are projected with POST /v1/geometries/{id}/project",
        request.single ? "point" : "points");
  if (request.length != params)
    throw ApiError(400, "wrong_dimension",
                   std::string(request.single ? "parameter" : "parameters") + " must have " +
                       std::to_string(params) + " numbers for this " + type + " (" +
                       (params == 2 ? "[u, v]" : "[t]") + "), got " + std::to_string(request.length),
                   request.single ? "parameter" : "parameters[0]");
  const int dim = geometry.point_dim();
  static const char* const first_names[2][2] = {{"t", ""}, {"u", "v"}};
  static const char* const second_names[2][3] = {{"tt", "", ""}, {"uu", "uv", "vv"}};
  const int kind = params - 1;
  std::string out;
  out.reserve(128 + request.count * (64 + 64 * request.derivatives * params + (request.normals ? 64 : 0)));
  JsonWriter o(out);
  begin(o, geometry, request);
  std::size_t inside = 0;
  for (std::size_t i = 0; i < request.count; ++i) {
    const double* t = request.values.data() + i * static_cast<std::size_t>(params);
    Evaluation e;
    geometry.evaluate(t, e);
    inside += e.inside_domain;
    o.begin_object();
    o.key("parameters");
    o.numbers(t, params);
    o.key("point");
    vector(o, e.point, dim);
    o.key("inside_domain");
    o.boolean(e.inside_domain);
    if (request.derivatives >= 1) {
      o.key("derivatives");
      o.begin_object();
      for (int k = 0; k < params; ++k) {
        o.key(first_names[kind][k]);
        vector(o, e.first[k], dim);
      }
      o.end_object();
    }
    if (request.derivatives >= 2) {
      o.key("second_derivatives");
      o.begin_object();
      for (int k = 0; k < 2 * params - 1; ++k) {
        o.key(second_names[kind][k]);
        vector(o, e.second[k], dim);
      }
      o.end_object();
    }
    if (request.normals) normal(o, e.normal_defined, e.normal, dim);
    o.end_object();
  }
  stats(o, request, "parameters", "inside_domain", inside);
  return out;
}

}  // namespace footpoint::server
