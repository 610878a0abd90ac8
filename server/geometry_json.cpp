#include "geometry_json.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <vector>

#include "api_error.hpp"
#include "compiled/parametric_curve_geometry.hpp"
#include "compiled/parametric_surface_geometry.hpp"
#include "request_object.hpp"

namespace footpoint::server {

namespace {

struct NumberTree {
  bool is_array = false;
  double number = 0.0;
  std::vector<NumberTree> items;
};

// A bound as posted: a number, or a constant expression in the formula syntax ("2*_pi"), which
// is evaluated once the definition's constants are known.
struct Bound {
  double value = 0.0;
  std::optional<std::string> expression;
};
using Interval = std::array<Bound, 2>;

std::string join(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}

// The members of a definition object as read, before the type decides which are allowed.
struct RawDefinition {
  std::optional<std::string> type, x, y, z, equation;
  std::optional<std::vector<std::string>> equations;
  std::optional<std::vector<std::pair<std::string, Interval>>> domain;
  std::map<std::string, double> constants;
  std::optional<std::vector<std::string>> periodic;
  // bspline_curve, bspline_surface: as posted, shapes checked once the type is known
  std::optional<NumberTree> degree, knots, control_points, weights;
  std::optional<std::pair<NumberTree, NumberTree>> knots_uv;  // a surface's {"u": [...], "v": [...]}
};

// A number, or an array of number trees: what the B-spline members are made of.
NumberTree read_number_tree(JsonReader& r, const std::string& field) {
  NumberTree t;
  const bool number = at_field(field, [&] {
    if (r.peek() == JsonReader::Type::number) {
      t.number = r.number();
      return true;
    }
    r.begin_array();
    return false;
  });
  if (number) return t;
  t.is_array = true;
  for (;;) {
    const std::string item = field + "[" + std::to_string(t.items.size()) + "]";
    if (!at_field(item, [&] { return r.next_element(); })) break;
    t.items.push_back(read_number_tree(r, item));
  }
  return t;
}

// The tree as nested vectors of `depth` levels of arrays (0: a number), or 400 wrong_shape naming
// the element at fault.
void shape_error(const std::string& field, int depth) {
  static const char* const kinds[] = {"a number", "an array of numbers", "an array of arrays of numbers",
                                      "an array of arrays of arrays of numbers"};
  throw ApiError(400, "wrong_shape", field + " must be " + kinds[depth], field);
}
double tree_number(const NumberTree& t, const std::string& field) {
  if (t.is_array) shape_error(field, 0);
  return t.number;
}
std::vector<double> tree_numbers(const NumberTree& t, const std::string& field) {
  if (!t.is_array) shape_error(field, 1);
  std::vector<double> out;
  for (std::size_t i = 0; i < t.items.size(); ++i)
    out.push_back(tree_number(t.items[i], field + "[" + std::to_string(i) + "]"));
  return out;
}
std::vector<std::vector<double>> tree_rows(const NumberTree& t, const std::string& field) {
  if (!t.is_array) shape_error(field, 2);
  std::vector<std::vector<double>> out;
  for (std::size_t i = 0; i < t.items.size(); ++i)
    out.push_back(tree_numbers(t.items[i], field + "[" + std::to_string(i) + "]"));
  return out;
}
int tree_degree(const NumberTree& t, const std::string& field) {
  const double d = tree_number(t, field);
  if (d != std::floor(d) || d < 0 || d > 1000)
    throw ApiError(400, "wrong_type", field + " must be a whole number", field);
  return static_cast<int>(d);
}

// [lo, hi], each a number or a constant expression string.
Interval read_interval(JsonReader& r, const std::string& field) {
  Interval v{};
  int n = 0;
  at_field(field, [&] { r.begin_array(); });
  for (;;) {
    const std::string item = field + "[" + std::to_string(n) + "]";
    if (!at_field(item, [&] { return r.next_element(); })) break;
    at_field(item, [&] {
      if (n == 2) throw ApiError(400, "wrong_shape", field + " must be [lo, hi]", field);
      const JsonReader::Type type = r.peek();
      if (type == JsonReader::Type::string)
        v[n].expression = r.string();
      else if (type == JsonReader::Type::number)
        v[n].value = r.number();
      else
        throw ApiError(400, "wrong_type",
                       item + ": expected a number or a constant expression such as \"2*_pi\", got " +
                           JsonReader::name(type),
                       item);
      ++n;
    });
  }
  if (n != 2) throw ApiError(400, "wrong_shape", field + " must be [lo, hi]", field);
  return v;
}

RawDefinition read_members(JsonReader& r, const std::string& prefix) {
  RawDefinition raw;
  auto read_string = [&](const std::string& field) { return at_field(field, [&] { return r.string(); }); };
  // An array of at most `most` strings.
  auto read_strings = [&](const std::string& field, std::size_t most, const char* too_many) {
    std::vector<std::string> items;
    at_field(field, [&] { r.begin_array(); });
    for (;;) {
      const std::string item = field + "[" + std::to_string(items.size()) + "]";
      if (!at_field(item, [&] { return r.next_element(); })) break;
      if (items.size() == most) throw ApiError(400, "wrong_shape", field + too_many, field);
      items.push_back(read_string(item));
    }
    return items;
  };
  const std::string object_field = prefix.empty() ? "body" : prefix.substr(0, prefix.size() - 1);
  read_object(r, object_field, prefix, prefix, [&](const std::string& key, const std::string& field) {
    if (key == "type") {
      raw.type = read_string(field);
    } else if (key == "x") {
      raw.x = read_string(field);
    } else if (key == "y") {
      raw.y = read_string(field);
    } else if (key == "z") {
      raw.z = read_string(field);
    } else if (key == "equation") {
      raw.equation = read_string(field);
    } else if (key == "equations") {
      raw.equations = read_strings(field, 2, " holds one equation (planar) or two (spatial)");
    } else if (key == "periodic") {
      raw.periodic = read_strings(field, 2, " names each parameter at most once");
    } else if (key == "domain") {
      std::vector<std::pair<std::string, Interval>> domain;
      read_object(r, field, field, field + ".", [&](const std::string& name, const std::string& item) {
        domain.emplace_back(name, read_interval(r, item));
      });
      raw.domain = std::move(domain);
    } else if (key == "degree") {
      raw.degree = read_number_tree(r, field);
    } else if (key == "knots") {
      const JsonReader::Type type = at_field(field, [&] { return r.peek(); });
      if (type == JsonReader::Type::object) {
        std::optional<NumberTree> u, v;
        read_object(r, field, field, field + ".", [&](const std::string& name, const std::string& item) {
          if (name == "u")
            u = read_number_tree(r, item);
          else if (name == "v")
            v = read_number_tree(r, item);
          else
            throw ApiError(400, "unknown_field", "unknown field " + item + " (u, v)", item);
        });
        if (!u || !v)
          throw ApiError(400, "missing_field", field + " needs u and v", field + (u ? ".v" : ".u"));
        raw.knots_uv = std::make_pair(std::move(*u), std::move(*v));
      } else {
        raw.knots = read_number_tree(r, field);
      }
    } else if (key == "control_points") {
      raw.control_points = read_number_tree(r, field);
    } else if (key == "weights") {
      raw.weights = read_number_tree(r, field);
    } else if (key == "constants") {
      read_object(r, field, field, field + ".", [&](const std::string& name, const std::string& item) {
        raw.constants[name] = at_field(item, [&] { return r.number(); });
      });
    } else if (prefix.empty() && (key == "geometry" || key == "point" || key == "points")) {
      // a projection request sent to POST /v1/geometries
      throw ApiError(400, "unknown_field",
                     "unknown field " + key +
                         ": POST /v1/geometries takes a definition alone ({\"type\": ..., \"domain\": ...}); "
                         "a body with geometry and point or points is for POST /v1/project, which projects "
                         "with the definition inline",
                     field);
    } else {
      throw ApiError(
          400, "unknown_field",
          "unknown field " + field +
              " (type, x, y, z, equation, equations, domain, constants, periodic; B-splines: degree, "
              "knots, control_points, weights)",
          field);
    }
  });
  return raw;
}

}  // namespace

namespace {

// A bspline_curve or bspline_surface: its net in the shapes the type has (400 wrong_shape naming
// the element); the values are checked when it compiles (422 bad_bspline).
GeometryDefinition read_bspline(RawDefinition& raw, const std::string& prefix, bool surface) {
  const std::string& type = *raw.type;
  auto forbid = [&](bool present, const char* name) {
    if (present)
      throw ApiError(400, "unknown_field", prefix + name + " is not a field of " + type, prefix + name);
  };
  forbid(raw.x.has_value(), "x");
  forbid(raw.y.has_value(), "y");
  forbid(raw.z.has_value(), "z");
  forbid(raw.equation.has_value(), "equation");
  forbid(raw.equations.has_value(), "equations");
  forbid(raw.domain.has_value(), "domain");
  forbid(!raw.constants.empty(), "constants");
  forbid(raw.periodic.has_value(), "periodic");
  auto require = [&](bool present, const char* name) {
    if (!present)
      throw ApiError(400, "missing_field", prefix + name + " is required for " + type, prefix + name);
  };
  require(raw.degree.has_value(), "degree");
  require(raw.control_points.has_value(), "control_points");
  require(raw.knots.has_value() || raw.knots_uv.has_value(), "knots");
  GeometryDefinition def;
  BSplineNet& net = def.bspline;
  if (surface) {
    def.type = GeometryType::bspline_surface;
    const std::vector<double> degree = tree_numbers(*raw.degree, prefix + "degree");
    if (degree.size() != 2)
      throw ApiError(400, "wrong_shape", prefix + "degree must be [p, q]", prefix + "degree");
    net.degree = {tree_degree(raw.degree->items[0], prefix + "degree[0]"),
                  tree_degree(raw.degree->items[1], prefix + "degree[1]")};
    if (!raw.knots_uv)
      throw ApiError(400, "wrong_shape", prefix + "knots must be {\"u\": [...], \"v\": [...]} for a surface",
                     prefix + "knots");
    net.knots = {tree_numbers(raw.knots_uv->first, prefix + "knots.u"),
                 tree_numbers(raw.knots_uv->second, prefix + "knots.v")};
    const NumberTree& rows = *raw.control_points;
    if (!rows.is_array) shape_error(prefix + "control_points", 3);
    for (std::size_t i = 0; i < rows.items.size(); ++i)
      net.control_points.push_back(
          tree_rows(rows.items[i], prefix + "control_points[" + std::to_string(i) + "]"));
    if (raw.weights) net.weights = tree_rows(*raw.weights, prefix + "weights");
  } else {
    def.type = GeometryType::bspline_curve;
    net.degree = {tree_degree(*raw.degree, prefix + "degree")};
    if (!raw.knots)
      throw ApiError(400, "wrong_shape", prefix + "knots must be an array of numbers for a curve",
                     prefix + "knots");
    net.knots = {tree_numbers(*raw.knots, prefix + "knots")};
    net.control_points = {tree_rows(*raw.control_points, prefix + "control_points")};
    if (raw.weights) net.weights = {tree_numbers(*raw.weights, prefix + "weights")};
  }
  return def;
}

}  // namespace

GeometryDefinition read_geometry(JsonReader& r, const std::string& prefix) {
  RawDefinition raw = read_members(r, prefix);
  GeometryDefinition def;
  if (!raw.type) throw ApiError(400, "missing_field", prefix + "type is required", prefix + "type");
  const std::string& type = *raw.type;
  if (type == "bspline_surface" || type == "bspline_curve")
    return read_bspline(raw, prefix, type == "bspline_surface");
  for (const auto& [present, name] : {std::pair{raw.degree.has_value(), "degree"},
                                      std::pair{raw.knots.has_value() || raw.knots_uv.has_value(), "knots"},
                                      std::pair{raw.control_points.has_value(), "control_points"},
                                      std::pair{raw.weights.has_value(), "weights"}})
    if (present)
      throw ApiError(400, "unknown_field", prefix + name + " is not a field of " + type, prefix + name);
  std::vector<std::string> names;  // the domain's variables, in order
  auto forbid = [&](bool present, const char* name) {
    if (present)
      throw ApiError(400, "unknown_field", prefix + name + " is not a field of " + type, prefix + name);
  };
  auto require = [&](const std::optional<std::string>& formula, const char* name) {
    if (!formula)
      throw ApiError(400, "missing_field", prefix + name + " is required for " + type, prefix + name);
    def.formulas.push_back({name, *formula});
  };
  if (type == "parametric_surface") {
    def.type = GeometryType::parametric_surface;
    forbid(raw.equations.has_value(), "equations");
    forbid(raw.equation.has_value(), "equation");
    require(raw.x, "x");
    require(raw.y, "y");
    require(raw.z, "z");
    names = {"u", "v"};
  } else if (type == "parametric_curve") {
    def.type = GeometryType::parametric_curve;
    forbid(raw.equations.has_value(), "equations");
    forbid(raw.equation.has_value(), "equation");
    require(raw.x, "x");
    require(raw.y, "y");
    if (raw.z) def.formulas.push_back({"z", *raw.z});
    names = {"t"};
  } else if (type == "implicit_curve") {
    def.type = GeometryType::implicit_curve;
    forbid(raw.x.has_value(), "x");
    forbid(raw.y.has_value(), "y");
    forbid(raw.z.has_value(), "z");
    forbid(raw.equation.has_value(), "equation");
    if (!raw.equations)
      throw ApiError(400, "missing_field", prefix + "equations is required for implicit_curve",
                     prefix + "equations");
    if (raw.equations->empty())
      throw ApiError(400, "wrong_shape", prefix + "equations holds one equation (planar) or two (spatial)",
                     prefix + "equations");
    for (std::size_t i = 0; i < raw.equations->size(); ++i)
      def.formulas.push_back({"equations[" + std::to_string(i) + "]", (*raw.equations)[i]});
    names = raw.equations->size() == 1 ? std::vector<std::string>{"x", "y"}
                                       : std::vector<std::string>{"x", "y", "z"};
  } else if (type == "implicit_surface") {
    def.type = GeometryType::implicit_surface;
    forbid(raw.x.has_value(), "x");
    forbid(raw.y.has_value(), "y");
    forbid(raw.z.has_value(), "z");
    forbid(raw.equations.has_value(), "equations");
    require(raw.equation, "equation");
    names = {"x", "y", "z"};
  } else {
    throw ApiError(400, "unknown_geometry_type",
                   "unknown geometry type '" + type +
                       "' (parametric_surface, parametric_curve, implicit_curve, implicit_surface, "
                       "bspline_surface, bspline_curve)",
                   prefix + "type");
  }

  if (!raw.domain) throw ApiError(400, "missing_field", prefix + "domain is required", prefix + "domain");
  // The domain in canonical order (u, v / t / x, y, z) whatever the order of the members.
  for (const auto& [name, interval] : *raw.domain) {
    bool known = false;
    for (const auto& n : names) known = known || n == name;
    if (!known)
      throw ApiError(400, "unknown_field",
                     prefix + "domain." + name + ": the domain of this " + type + " has " + join(names),
                     prefix + "domain." + name);
  }
  for (const auto& n : names) {
    const std::pair<std::string, Interval>* found = nullptr;
    for (const auto& d : *raw.domain)
      if (d.first == n) found = &d;
    if (!found)
      throw ApiError(400, "missing_field", prefix + "domain." + n + " is required", prefix + "domain." + n);
    std::array<double, 2> range{};
    for (std::size_t k = 0; k < 2; ++k) {
      const Bound& bound = found->second[k];
      if (!bound.expression) {
        range[k] = bound.value;
        continue;
      }
      const auto value =
          evaluate_bound("domain." + n + "[" + std::to_string(k) + "]", *bound.expression, raw.constants);
      if (!value) {
        const GeometryError& e = value.error();
        throw ApiError(422, e.code, e.what(), prefix + e.field, e.position, e.suggestion);
      }
      range[k] = *value;
    }
    def.domain.emplace_back(n, range);
  }
  def.constants = std::move(raw.constants);
  if (raw.periodic) {
    // Parameters only (an implicit curve has none), each once; kept in the parameters' order.
    const std::vector<std::string> parameters =
        def.type == GeometryType::parametric_surface ? std::vector<std::string>{"u", "v"}
        : def.type == GeometryType::parametric_curve ? std::vector<std::string>{"t"}
                                                     : std::vector<std::string>{};
    forbid(parameters.empty(), "periodic");
    for (std::size_t i = 0; i < raw.periodic->size(); ++i) {
      const std::string& name = (*raw.periodic)[i];
      const std::string field = prefix + "periodic[" + std::to_string(i) + "]";
      if (std::find(parameters.begin(), parameters.end(), name) == parameters.end())
        throw ApiError(400, "unknown_parameter",
                       field + ": '" + name + "' is not a parameter of " + with_article(type) + " (" +
                           join(parameters) + ")",
                       field);
      for (std::size_t j = 0; j < i; ++j)
        if ((*raw.periodic)[j] == name)
          throw ApiError(400, "duplicate_parameter", field + ": '" + name + "' is named twice", field);
    }
    for (const std::string& p : parameters)
      if (std::find(raw.periodic->begin(), raw.periodic->end(), p) != raw.periodic->end())
        def.periodic.push_back(p);
  }
  return def;
}

namespace {

void write_numbers(JsonWriter& w, const std::vector<double>& xs) {
  w.begin_array();
  for (const double x : xs) w.number(x);
  w.end_array();
}

// A B-spline's net as posted: degree, knots, control_points, weights (when rational).
void write_bspline(JsonWriter& w, const BSplineNet& net, bool surface) {
  w.key("degree");
  if (surface) {
    w.begin_array();
    for (const int d : net.degree) w.number(d);
    w.end_array();
  } else {
    w.number(net.degree[0]);
  }
  w.key("knots");
  if (surface) {
    w.begin_object();
    w.key("u");
    write_numbers(w, net.knots[0]);
    w.key("v");
    write_numbers(w, net.knots[1]);
    w.end_object();
  } else {
    write_numbers(w, net.knots[0]);
  }
  auto rows = [&](const auto& each) {
    if (surface) w.begin_array();
    for (const auto& row : each) {
      w.begin_array();
      for (const auto& point : row) write_numbers(w, point);
      w.end_array();
    }
    if (surface) w.end_array();
  };
  w.key("control_points");
  rows(net.control_points);
  if (!net.weights.empty()) {
    w.key("weights");
    if (surface) {
      w.begin_array();
      for (const auto& row : net.weights) write_numbers(w, row);
      w.end_array();
    } else {
      write_numbers(w, net.weights[0]);
    }
  }
}

}  // namespace

void write_geometry(JsonWriter& w, const GeometryDefinition& def) {
  w.begin_object();
  w.key("type");
  w.string(to_string(def.type));
  if (def.type == GeometryType::bspline_surface || def.type == GeometryType::bspline_curve) {
    write_bspline(w, def.bspline, def.type == GeometryType::bspline_surface);
    w.end_object();
    return;
  }
  if (def.type == GeometryType::implicit_curve) {
    w.key("equations");
    w.begin_array();
    for (const auto& f : def.formulas) w.string(f.expression);
    w.end_array();
  } else {
    for (const auto& f : def.formulas) {
      w.key(f.name);
      w.string(f.expression);
    }
  }
  w.key("domain");
  w.begin_object();
  for (const auto& [name, interval] : def.domain) {
    w.key(name);
    w.begin_array();
    w.number(interval[0]);
    w.number(interval[1]);
    w.end_array();
  }
  w.end_object();
  if (!def.constants.empty()) {
    w.key("constants");
    w.begin_object();
    for (const auto& [name, value] : def.constants) {
      w.key(name);
      w.number(value);
    }
    w.end_object();
  }
  if (!def.periodic.empty()) {
    w.key("periodic");
    w.begin_array();
    for (const std::string& name : def.periodic_parameters()) w.string(name);
    w.end_array();
  }
  w.end_object();
}

namespace {

void write_point(JsonWriter& w, Vec3 p, int dim) {
  w.begin_array();
  for (int c = 0; c < dim; ++c) w.number(p[c]);
  w.end_array();
}

void write_names(JsonWriter& w, const std::vector<std::string>& names) {
  w.begin_array();
  for (const std::string& name : names) w.string(name);
  w.end_array();
}

// A closed direction: {"direction", "reversed", "smooth", "max_gap", "gap_bound"} (null: no bound).
void write_seam(JsonWriter& w, const char* direction, bool reversed, bool smooth, double max_gap,
                double gap_bound) {
  w.begin_object();
  w.key("direction");
  w.string(direction);
  w.key("reversed");
  w.boolean(reversed);
  w.key("smooth");
  w.boolean(smooth);
  w.key("max_gap");
  w.number(max_gap);
  w.key("gap_bound");
  w.number(gap_bound);
  w.end_object();
}

}  // namespace

void write_closure(JsonWriter& w, const CompiledGeometry& geometry) {
  const auto* surface = dynamic_cast<const ParametricSurface*>(&geometry);
  const auto* curve = dynamic_cast<const ParametricCurve*>(&geometry);
  if (!surface && !curve) return;
  static const char* const kDirections[2] = {"u", "v"};
  w.key("closure");
  w.begin_object();
  w.key("periodic");
  std::vector<std::string> periodic;
  if (surface) {
    for (int i = 0; i < 2; ++i)
      if (surface->closure().periodic(i)) periodic.push_back(kDirections[i]);
  } else if (curve->closure().closed) {
    periodic.push_back("t");
  }
  write_names(w, periodic);
  w.key("declared");
  write_names(w, geometry.definition().periodic_parameters());
  w.key("seams");
  w.begin_array();
  if (surface) {
    for (int i = 0; i < 2; ++i) {
      const SurfaceSeam& seam = surface->closure().seams[static_cast<std::size_t>(i)];
      if (seam.closed)
        write_seam(w, kDirections[i], seam.reversed, seam.smooth, seam.max_gap, seam.gap_bound);
    }
  } else if (const CurveClosure& c = curve->closure(); c.closed) {
    write_seam(w, "t", false, c.smooth, c.gap, c.gap_bound);
  }
  w.end_array();
  w.key("poles");
  w.begin_array();
  if (surface)
    for (const BoxEdge edge : {BoxEdge::umin, BoxEdge::umax, BoxEdge::vmin, BoxEdge::vmax}) {
      const SurfacePole& pole = surface->closure().poles[static_cast<std::size_t>(edge)];
      if (!pole.collapsed) continue;
      w.begin_object();
      w.key("edge");
      w.string(to_string(edge));
      w.key("point");
      write_point(w, pole.point, 3);
      w.key("radius_bound");
      w.number(pole.radius_bound);
      w.end_object();
    }
  w.end_array();
  w.key("tolerance");
  w.number(surface ? surface->closure().tolerance : curve->closure().tolerance);
  if (surface) {
    w.key("translations");
    w.begin_array();
    for (const auto& d : surface->self_covering().translations) write_point(w, {d[0], d[1], 0.0}, 2);
    w.end_array();
  }
  w.end_object();
}

}  // namespace footpoint::server
