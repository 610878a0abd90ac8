#include "project_request.hpp"

#include <cmath>

#include "api_error.hpp"
#include "geometry_json.hpp"
#include "json_reader.hpp"
#include "number_rows.hpp"
#include "request_object.hpp"

namespace footpoint::server {

namespace {

std::string indexed(const char* name, std::size_t i) {
  return std::string(name) + "[" + std::to_string(i) + "]";
}

// A start: [a(,b(,c))] (1 to 3 numbers).
int read_start(JsonReader& r, std::array<double, 3>& start, const std::string& field) {
  int n = 0;
  try {
    r.begin_array();
    while (r.next_element()) {
      if (n == 3) throw ApiError(400, "wrong_dimension", field + " has more than 3 numbers", field);
      start[n++] = r.number();
    }
  } catch (const JsonReadError& e) {
    throw request_error(e, field);
  }
  if (n == 0) throw ApiError(400, "wrong_dimension", field + " is empty", field);
  return n;
}

void read_initial(JsonReader& r, ProjectRequest& request) {
  const std::string field = "options.initial";
  try {
    r.begin_array();
    const bool per_point = r.peek() == JsonReader::Type::array;
    if (!per_point) {
      // One start for every point: [a, b].
      std::array<double, 3> start{};
      int n = 0;
      while (r.next_element()) {
        if (n == 3) throw ApiError(400, "wrong_dimension", field + " has more than 3 numbers", field);
        start[n++] = r.number();
      }
      if (n == 0) throw ApiError(400, "wrong_dimension", field + " is empty", field);
      request.options.initial = start;
      request.initial_length = n;
      return;
    }
    // One start per point: [[a, b], ...].
    while (r.next_element()) {
      const std::string item = indexed("options.initial", request.initials.size());
      std::array<double, 3> start{};
      const int n = read_start(r, start, item);
      if (request.initial_length == 0) request.initial_length = n;
      if (n != request.initial_length)
        throw ApiError(400, "wrong_dimension",
                       item + " has " + std::to_string(n) + " numbers, " + field + "[0] has " +
                           std::to_string(request.initial_length),
                       item);
      request.initials.push_back(start);
    }
  } catch (const JsonReadError& e) {
    throw request_error(e, field);
  }
}

void read_options(JsonReader& r, ProjectRequest& request) {
  Options& o = request.options;
  read_object(r, "options", "options", "options.", [&](const std::string& key, const std::string& field) {
    try {
      if (key == "tolerance") {
        const double t = r.number();
        if (!(t >= 0.0 && t < 1.0))
          throw ApiError(400, "invalid_option", field + " must be in [0, 1) (0: the method's default)",
                         field);
        o.tolerance = t;
      } else if (key == "max_iterations") {
        const double n = r.number();
        if (!(n >= 0.0 && n <= 10000.0 && n == std::floor(n)))
          throw ApiError(400, "invalid_option",
                         field + " must be an integer in [0, 10000] (0: the method's default)", field);
        o.max_iterations = static_cast<int>(n);
      } else if (key == "max_distance") {
        const double d = r.number();
        if (!(d > 0.0)) throw ApiError(400, "invalid_option", field + " must be positive", field);
        o.max_distance = d;
      } else if (key == "all_minima") {
        o.all_minima = r.boolean();
      } else if (key == "max_minima") {
        const double n = r.number();
        if (!(n >= 1.0 && n <= 10000.0 && n == std::floor(n)))
          throw ApiError(400, "invalid_option", field + " must be an integer in [1, 10000]", field);
        o.max_minima = static_cast<int>(n);
      } else if (key == "trace") {
        o.trace = r.boolean();
      } else if (key == "certify") {
        o.certify = r.boolean();
      } else if (key == "initial") {
        read_initial(r, request);
      } else {
        throw ApiError(
            400, "unknown_field",
            "unknown option " + field +
                " (tolerance, max_iterations, initial, all_minima, max_minima, trace, max_distance, certify)",
            field);
      }
    } catch (const JsonReadError& e) {
      throw request_error(e, field);
    }
  });
}

// "fields": ["distance", "foot_point", "diagnostics.status", ...], at least one.
ResultFields read_fields(JsonReader& r) {
  ResultFields fields{0};
  std::size_t i = 0;
  try {
    r.begin_array();
    for (; r.next_element(); ++i) {
      const std::string item = indexed("fields", i);
      std::string name;
      try {
        name = r.string();
      } catch (const JsonReadError& e) {
        throw request_error(e, item);
      }
      const std::uint32_t members = ResultFields::parse(name);
      if (members == 0)
        throw ApiError(400, "unknown_field",
                       item + ": '" + name + "' is no member of a result (" + ResultFields::names() + ")",
                       item);
      fields.members |= members;
    }
  } catch (const JsonReadError& e) {
    throw request_error(e, i == 0 ? std::string("fields") : indexed("fields", i));
  }
  if (i == 0)
    throw ApiError(400, "wrong_shape", "fields is empty: name the members each result should have", "fields");
  return fields;
}

}  // namespace

namespace {

ProjectRequest read_request(std::string_view body, bool inline_geometry, std::size_t max_points) {
  ProjectRequest request;
  JsonReader r(body);
  bool has_point = false, has_points = false, fields_given = false;
  read_object(r, "body", "body", "", [&](const std::string& key, const std::string&) {
    if (key == "point") {
      request.point_length = read_row(r, "point", request.coords);
      request.count = 1;
      has_point = true;
    } else if (key == "points") {
      request.count = read_rows(r, "points", max_points, request.coords, request.point_length);
      has_points = true;
    } else if (key == "method") {
      try {
        request.method = r.string();
      } catch (const JsonReadError& e) {
        throw request_error(e, "method");
      }
    } else if (key == "options") {
      read_options(r, request);
    } else if (key == "fields") {
      request.fields = read_fields(r);
      fields_given = true;
    } else if (key == "geometry" && inline_geometry) {
      request.geometry = read_geometry(r, "geometry.");
    } else if (key == "type" || key == "x" || key == "equations" || key == "domain" || key == "constants") {
      // a definition's member where a projection request is expected
      throw ApiError(
          400, "unknown_field",
          "unknown field " + key +
              (inline_geometry ? ": POST /v1/project takes the definition under \"geometry\": "
                                 "{\"geometry\": {\"type\": ...}, \"point\": [...]}"
                               : ": this route projects onto the geometry its id names; post a definition to "
                                 "POST /v1/geometries, or send it under \"geometry\" to POST /v1/project"),
          key);
    } else {
      throw ApiError(400, "unknown_field",
                     "unknown field " + key +
                         (inline_geometry ? " (geometry, point, points, method, options, fields)"
                                          : " (point, points, method, options, fields)"),
                     key);
    }
    if (has_point && has_points)
      throw ApiError(400, "conflicting_fields", "give either point or points, not both", "points");
  });
  try {
    r.finish();
  } catch (const JsonReadError& e) {
    throw request_error(e, "body");
  }
  if (!has_point && !has_points)
    throw ApiError(400, "missing_field", "point (one point) or points (a batch) is required", "point");
  if (inline_geometry && !request.geometry)
    throw ApiError(400, "missing_field", "geometry (the definition) is required", "geometry");
  request.single = has_point;
  // minima and trace are computed on request only; "fields" cannot ask for them alone.
  for (const auto& [member, option] :
       {std::pair{ResultFields::minima, "all_minima"}, std::pair{ResultFields::trace, "trace"}}) {
    const bool asked = member == ResultFields::minima ? request.options.all_minima : request.options.trace;
    if (asked) continue;
    if (fields_given && request.fields.has(member))
      throw ApiError(400, "conflicting_fields",
                     std::string("fields names ") + (member == ResultFields::minima ? "minima" : "trace") +
                         ", which only options." + option + ": true computes",
                     "fields");
    request.fields.members &= ~member;
  }
  if (!request.initials.empty() && request.initials.size() != request.count)
    throw ApiError(400, "wrong_shape",
                   "options.initial has " + std::to_string(request.initials.size()) + " starts for " +
                       std::to_string(request.count) + " points",
                   "options.initial");
  return request;
}

}  // namespace

ProjectRequest read_project_request(std::string_view body, bool inline_geometry, std::size_t max_points) {
  try {
    return read_request(body, inline_geometry, max_points);
  } catch (const ApiError& e) {
    throw unless_malformed(body, e);
  }
}

GeometryMethod check_project_request(const ProjectRequest& request, const CompiledGeometry& geometry) {
  const int dim = geometry.point_dim();
  const char* type = to_string(geometry.definition().type);
  if (request.point_length != dim)
    throw ApiError(400, "wrong_dimension",
                   std::string(request.single ? "point" : "points") + " must have " + std::to_string(dim) +
                       " coordinates for this " + type + ", got " + std::to_string(request.point_length),
                   request.single ? "point" : "points[0]");
  const auto method = geometry.method(request.method);
  if (!method) throw ApiError(400, "unknown_method", method.error().message, "method");
  if (request.initial_length != 0) {
    const int expected = geometry.num_params() > 0 ? geometry.num_params() : dim;
    if (request.initial_length != expected)
      throw ApiError(400, "wrong_dimension",
                     "options.initial: a start has " + std::to_string(expected) + " numbers for " +
                         with_article(type) + " (" +
                         (geometry.num_params() == 2   ? "[u, v]"
                          : geometry.num_params() == 1 ? "[t]"
                                                       : "a point") +
                         ")",
                     "options.initial");
  }
  return *method;
}

}  // namespace footpoint::server
