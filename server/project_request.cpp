#include "project_request.hpp"

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
#include <system_error>

#include "api_error.hpp"
#include "geometry_json.hpp"
#include "json_reader.hpp"
#include "number_rows.hpp"
#include "query.hpp"
#include "request_object.hpp"

namespace footpoint::server {

namespace {

std::string indexed(const char* name, std::size_t i) {
  return std::string(name) + "[" + std::to_string(i) + "]";
}

// A start: [a(,b(,c))] (1 to 3 numbers).
int read_start(JsonReader& r, std::array<double, 3>& start, const std::string& field) {
  int n = 0;
  at_field(field, [&] {
    r.begin_array();
    while (r.next_element()) {
      if (n == 3) throw ApiError(400, "wrong_dimension", field + " has more than 3 numbers", field);
      start[n++] = r.number();
    }
  });
  if (n == 0) throw ApiError(400, "wrong_dimension", field + " is empty", field);
  return n;
}

void read_initial(JsonReader& r, ProjectRequest& request) {
  const std::string field = "options.initial";
  at_field(field, [&] {
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
  });
}

// An integer option in [lo, hi]; `meaning` follows the range in the message.
template <class Value>
int integer_option(Value& value, const std::string& field, int lo, int hi, const char* meaning = "") {
  const double n = value.number();
  if (!(n >= lo && n <= hi && n == std::floor(n)))
    throw ApiError(
        400, "invalid_option",
        field + " must be an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]" + meaning,
        field);
  return static_cast<int>(n);
}

// The options of a projection request, the JSON body's "options" and the query parameters of a
// binary request alike: each one's name and how its value is read, checked and stored. `Value`
// reads the value: number(), boolean(), numbers(start) (1 to 3 numbers into start, returns how
// many) and initial(request) (the start or starts, as the body or the query gives them).
template <class Value>
struct OptionMember {
  std::string_view name;
  void (*set)(ProjectRequest& request, const std::string& field, Value& value);
};

template <class Value>
constexpr OptionMember<Value> kOptionMembers[] = {
    {"tolerance",
     [](ProjectRequest& q, const std::string& field, Value& v) {
       const double t = v.number();
       if (!(t >= 0.0 && t < 1.0))
         throw ApiError(400, "invalid_option", field + " must be in [0, 1) (0: the method's default)", field);
       q.options.tolerance = t;
     }},
    {"max_iterations",
     [](ProjectRequest& q, const std::string& field, Value& v) {
       q.options.max_iterations = integer_option(v, field, 0, 10000, " (0: the method's default)");
     }},
    {"initial", [](ProjectRequest& q, const std::string&, Value& v) { v.initial(q); }},
    {"all_minima",
     [](ProjectRequest& q, const std::string&, Value& v) { q.options.all_minima = v.boolean(); }},
    {"max_minima", [](ProjectRequest& q, const std::string& field,
                      Value& v) { q.options.max_minima = integer_option(v, field, 1, 10000); }},
    {"trace", [](ProjectRequest& q, const std::string&, Value& v) { q.options.trace = v.boolean(); }},
    {"max_distance",
     [](ProjectRequest& q, const std::string& field, Value& v) {
       const double d = v.number();
       if (!(d > 0.0)) throw ApiError(400, "invalid_option", field + " must be positive", field);
       q.options.max_distance = d;
     }},
    {"certify", [](ProjectRequest& q, const std::string&, Value& v) { q.options.certify = v.boolean(); }},
    {"histogram_bins",
     [](ProjectRequest& q, const std::string& field, Value& v) {
       q.deviation.histogram_bins = integer_option(v, field, 1, DeviationOptions::kMaxBins);
     }},
    {"tolerance_band",
     [](ProjectRequest& q, const std::string& field, Value& v) {
       std::array<double, 3> band{};
       if (v.numbers(band) != 2)
         throw ApiError(400, "wrong_dimension", field + " must be two numbers [lo, hi]", field);
       if (!(std::isfinite(band[0]) && std::isfinite(band[1]) && band[0] <= band[1]))
         throw ApiError(400, "invalid_option", field + " must be [lo, hi] with finite lo <= hi", field);
       q.deviation.tolerance_band = std::array<double, 2>{band[0], band[1]};
     }},
};

// Sets the option `key` (named `field` in messages) from `value`. False for a key that is no option.
template <class Value>
bool set_option(ProjectRequest& request, const std::string& key, const std::string& field, Value& value) {
  for (const OptionMember<Value>& option : kOptionMembers<Value>)
    if (option.name == key) {
      option.set(request, field, value);
      return true;
    }
  return false;
}

// The options' names, for messages: "tolerance, max_iterations, ...".
template <class Value>
const std::string& option_names() {
  static const std::string names = [] {
    std::string out;
    for (const OptionMember<Value>& option : kOptionMembers<Value>)
      (out += out.empty() ? "" : ", ") += option.name;
    return out;
  }();
  return names;
}

// An option's value in the JSON body.
struct JsonOptionValue {
  JsonReader& r;
  const std::string& field;
  double number() { return r.number(); }
  bool boolean() { return r.boolean(); }
  int numbers(std::array<double, 3>& start) { return read_start(r, start, field); }
  void initial(ProjectRequest& request) { read_initial(r, request); }
};

void read_options(JsonReader& r, ProjectRequest& request) {
  read_object(r, "options", "options", "options.", [&](const std::string& key, const std::string& field) {
    at_field(field, [&] {
      JsonOptionValue value{r, field};
      if (!set_option(request, key, field, value))
        throw ApiError(400, "unknown_field",
                       "unknown option " + field + " (" + option_names<JsonOptionValue>() + ")", field);
    });
  });
}

// The members a field name selects; 400 unknown_field naming `item` for a name that is none.
std::uint32_t field_members(const std::string& name, const std::string& item) {
  const std::uint32_t members = ResultFields::parse(name);
  if (members == 0)
    throw ApiError(400, "unknown_field",
                   item + ": '" + name + "' is no member of a result (" + ResultFields::names() + ")", item);
  return members;
}

// "fields": ["distance", "foot_point", "diagnostics.status", ...], at least one.
ResultFields read_fields(JsonReader& r) {
  ResultFields fields{0};
  std::size_t i = 0;
  try {
    r.begin_array();
    for (; r.next_element(); ++i) {
      const std::string item = indexed("fields", i);
      const std::string name = at_field(item, [&] { return r.string(); });
      fields.members |= field_members(name, item);
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

void settle_request(ProjectRequest& request, bool fields_given);

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
      request.method = at_field("method", [&] { return r.string(); });
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
  at_field("body", [&] { r.finish(); });
  if (!has_point && !has_points)
    throw ApiError(400, "missing_field", "point (one point) or points (a batch) is required", "point");
  if (inline_geometry && !request.geometry)
    throw ApiError(400, "missing_field", "geometry (the definition) is required", "geometry");
  request.single = has_point;
  settle_request(request, fields_given);
  return request;
}

// minima and trace are computed on request only; "fields" cannot ask for them alone. One start
// per point, or none.
void settle_request(ProjectRequest& request, bool fields_given) {
  request.fields_given = fields_given;
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
}

}  // namespace

ProjectRequest read_project_request(std::string_view body, bool inline_geometry, std::size_t max_points) {
  try {
    return read_request(body, inline_geometry, max_points);
  } catch (const ApiError& e) {
    throw unless_malformed(body, e);
  }
}

namespace {

// A query parameter's value as an option: numbers written as in JSON, booleans true or false,
// several numbers separated by commas.
struct QueryOptionValue {
  const std::string& text;
  const std::string& name;
  static bool parse(std::string_view text, double& x) {
    const auto r = std::from_chars(text.data(), text.data() + text.size(), x);
    return r.ec == std::errc() && r.ptr == text.data() + text.size() && !text.empty();
  }
  double number() const {
    double x = 0.0;
    if (!parse(text, x))
      throw ApiError(400, "wrong_type", name + " must be a number, got '" + text + "'", name);
    return x;
  }
  bool boolean() const {
    if (text == "true") return true;
    if (text == "false") return false;
    throw ApiError(400, "wrong_type", name + " must be true or false, got '" + text + "'", name);
  }
  int numbers(std::array<double, 3>& out) const {
    int n = 0;
    std::string_view rest = text;
    while (true) {
      const auto comma = rest.find(',');
      if (n == 3) throw ApiError(400, "wrong_dimension", name + " has more than 3 numbers", name);
      if (!parse(rest.substr(0, comma), out[n++]))
        throw ApiError(400, "wrong_type", name + " must be numbers separated by commas, got '" + text + "'",
                       name);
      if (comma == std::string_view::npos) return n;
      rest = rest.substr(comma + 1);
    }
  }
  // One start for every point.
  void initial(ProjectRequest& request) const {
    std::array<double, 3> start{};
    request.initial_length = numbers(start);
    request.options.initial = start;
  }
};

// A binary request's query parameters: how its body is read, then the options.
const std::vector<std::string_view>& binary_query_names() {
  static const std::vector<std::string_view> names = [] {
    std::vector<std::string_view> out{"dtype", "method", "fields"};
    for (const auto& option : kOptionMembers<QueryOptionValue>) out.push_back(option.name);
    return out;
  }();
  return names;
}

}  // namespace

ProjectRequest read_binary_project_options(std::string_view query, int point_dim, std::size_t body_bytes,
                                           std::size_t max_points) {
  ProjectRequest request;
  bool fields_given = false;
  for (const auto& [name, value] : query_parameters(query, binary_query_names())) {
    QueryOptionValue v{value, name};
    if (name == "dtype") {
      if (value != "float64" && value != "float32")
        throw ApiError(400, "invalid_option", "dtype must be float64 or float32, got '" + value + "'", name);
      request.raw_float32 = value == "float32";
    } else if (name == "method") {
      request.method = value;
    } else if (name == "fields") {
      request.fields = ResultFields{0};
      std::string_view rest = value;
      for (std::size_t i = 0;; ++i) {
        const auto comma = rest.find(',');
        request.fields.members |= field_members(std::string(rest.substr(0, comma)), indexed("fields", i));
        if (comma == std::string_view::npos) break;
        rest = rest.substr(comma + 1);
      }
      fields_given = true;
    } else {
      set_option(request, name, name, v);
    }
  }
  const std::size_t record = binary_record_bytes(request, point_dim);
  if (body_bytes % record != 0)
    throw ApiError(400, "wrong_shape",
                   "the body has " + std::to_string(body_bytes) + " bytes, not a whole number of " +
                       std::to_string(record) + "-byte points (" + std::to_string(point_dim) +
                       " little-endian " + (request.raw_float32 ? "float32" : "float64") +
                       " numbers each); " + std::to_string(body_bytes % record) + " bytes are left over",
                   "body");
  request.count = body_bytes / record;
  if (request.count == 0) throw ApiError(400, "missing_field", "the body holds no point", "body");
  if (request.count > max_points)
    throw ApiError(413, "too_many_points",
                   "the body holds " + std::to_string(request.count) + " points, over the limit of " +
                       std::to_string(max_points) + " (--max-points): split the batch",
                   "body");
  request.point_length = point_dim;
  settle_request(request, fields_given);
  return request;
}

ProjectRequest read_binary_project_request(std::string_view body, std::string_view query, int point_dim,
                                           std::size_t max_points) {
  ProjectRequest request = read_binary_project_options(query, point_dim, body.size(), max_points);
  request.coords.resize(request.count * static_cast<std::size_t>(point_dim));
  decode_points(request, body.data(), request.count, request.coords.data());
  // Every coordinate finite, as JSON can only write them.
  check_finite(request, 0, request.coords.data(), request.count);
  return request;
}

std::size_t binary_record_bytes(const ProjectRequest& request, int point_dim) {
  return static_cast<std::size_t>(point_dim) * (request.raw_float32 ? 4 : 8);
}

void decode_points(const ProjectRequest& request, const char* raw, std::size_t points, double* out) {
  const std::size_t dim = static_cast<std::size_t>(request.point_length);
  const std::size_t width = request.raw_float32 ? 4 : 8;
  const char* p = raw;
  for (std::size_t i = 0; i < points * dim; ++i, p += width) {
    unsigned char bytes[8];
    std::memcpy(bytes, p, width);
    if constexpr (std::endian::native == std::endian::big) std::reverse(bytes, bytes + width);
    if (request.raw_float32) {
      float x;
      std::memcpy(&x, bytes, 4);
      out[i] = x;
    } else {
      std::memcpy(&out[i], bytes, 8);
    }
  }
}

std::size_t first_not_finite(const ProjectRequest& request, const double* coords, std::size_t points) {
  const std::size_t dim = static_cast<std::size_t>(request.point_length);
  for (std::size_t i = 0; i < points * dim; ++i)
    if (!std::isfinite(coords[i])) return i / dim;
  return points;
}

void check_finite(const ProjectRequest& request, std::size_t first_point, const double* coords,
                  std::size_t points) {
  const std::size_t dim = static_cast<std::size_t>(request.point_length);
  const std::size_t bad = first_not_finite(request, coords, points);
  if (bad == points) return;
  std::size_t i = bad * dim;
  while (std::isfinite(coords[i])) ++i;
  const std::size_t point = first_point + bad, coordinate = i % dim;
  const std::string field = indexed("points", point) + "[" + std::to_string(coordinate) + "]";
  throw ApiError(400, "number_out_of_range",
                 field + " is " + (std::isnan(coords[i]) ? "NaN" : "infinite") + " (body bytes from " +
                     std::to_string((point * dim + coordinate) * (request.raw_float32 ? 4 : 8)) +
                     "): every coordinate must be a finite number",
                 field);
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
