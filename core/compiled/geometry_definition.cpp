#include "compiled/geometry_definition.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <string_view>
#include <system_error>
#include <vector>

#include "compiled/sha256.hpp"
#include "geometry/geometry_error.hpp"

namespace footpoint {

const char* to_string(GeometryType t) {
  switch (t) {
    case GeometryType::parametric_surface:
      return "parametric_surface";
    case GeometryType::parametric_curve:
      return "parametric_curve";
    case GeometryType::implicit_curve:
      return "implicit_curve";
    case GeometryType::implicit_surface:
      return "implicit_surface";
    case GeometryType::bspline_surface:
      return "bspline_surface";
    case GeometryType::bspline_curve:
      return "bspline_curve";
  }
  return "unknown";
}

namespace {

// Shortest text that reads back as the same double.
std::string shortest(double x) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  return std::string(buf, r.ptr);
}

// A list of numbers as [a,b,...] in shortest form. (Strings are appended piece by piece: GCC 12
// warns falsely about operator+ on a literal and a temporary string, -Wrestrict.)
std::string number_list(const std::vector<double>& xs) {
  std::string s = "[";
  for (std::size_t i = 0; i < xs.size(); ++i) {
    if (i) s += ',';
    s += shortest(xs[i]);
  }
  s += ']';
  return s;
}

bool is_bspline(GeometryType t) {
  return t == GeometryType::bspline_surface || t == GeometryType::bspline_curve;
}

// The net's members: degree=p[,q];knots.u=[...][;knots.v=[...]];control_points=[...][;weights=[...]],
// a curve's points and weights as one list, a surface's as a list of rows.
std::string canonical_net(const BSplineNet& net, bool surface) {
  std::string s = ";degree=";
  for (std::size_t i = 0; i < net.degree.size(); ++i) {
    if (i) s += ',';
    s += std::to_string(net.degree[i]);
  }
  static const char* const names[2] = {"u", "v"};
  for (std::size_t i = 0; i < net.knots.size() && i < 2; ++i) {
    s += ";knots.";
    s += names[i];
    s += '=';
    s += number_list(net.knots[i]);
  }
  // A curve's one row as it is, a surface's rows in a list.
  auto rows = [&](std::string& out, std::size_t count, const auto& append_row) {
    if (surface) out += '[';
    for (std::size_t r = 0; r < count; ++r) {
      if (r) out += ',';
      append_row(out, r);
    }
    if (surface) out += ']';
  };
  s += ";control_points=";
  rows(s, net.control_points.size(), [&](std::string& out, std::size_t r) {
    out += '[';
    for (std::size_t j = 0; j < net.control_points[r].size(); ++j) {
      if (j) out += ',';
      out += number_list(net.control_points[r][j]);
    }
    out += ']';
  });
  if (!net.weights.empty()) {
    s += ";weights=";
    rows(s, net.weights.size(), [&](std::string& out, std::size_t r) { out += number_list(net.weights[r]); });
  }
  return s;
}

}  // namespace

std::string GeometryDefinition::canonical() const {
  std::string s = "footpoint/1;type=";
  s += to_string(type);
  if (is_bspline(type)) return s + canonical_net(bspline, type == GeometryType::bspline_surface);
  for (const auto& f : formulas) {
    s += ';' + f.name + '=';
    for (char ch : f.expression)
      if (!std::isspace(static_cast<unsigned char>(ch))) s += ch;
  }
  for (const auto& [name, range] : domain)
    s += ";domain." + name + "=[" + shortest(range[0]) + ',' + shortest(range[1]) + ']';
  for (const auto& [name, value] : constants) s += ";constants." + name + '=' + shortest(value);
  const std::vector<std::string> names = periodic_parameters();
  for (std::size_t i = 0; i < names.size(); ++i) s += (i == 0 ? ";periodic=" : ",") + names[i];
  return s;
}

std::vector<std::string> GeometryDefinition::periodic_parameters() const {
  std::vector<std::string> names = periodic;
  std::sort(names.begin(), names.end());
  names.erase(std::unique(names.begin(), names.end()), names.end());
  return names;
}

std::string GeometryDefinition::id() const { return sha256_hex(canonical()).substr(0, 32); }

Expected<double, GeometryError> evaluate_bound(const std::string& field, const std::string& expression,
                                               const std::map<std::string, double>& constants) {
  double value = 0.0;
  try {
    value = formula::Program::constant_value({field, expression}, constants);
  } catch (const formula::FormulaError& e) {
    return GeometryError(formula::to_string(e.kind), e.formula, e.position, e.what(), e.suggestion);
  }
  if (!std::isfinite(value))
    return GeometryError("bad_domain", field, -1, field + ": '" + expression + "' is not a finite number");
  return value;
}

namespace {

[[noreturn]] void bad_canonical(const std::string& why) {
  throw GeometryError("bad_canonical", "", -1, "not a canonical geometry definition: " + why);
}

double read_number(std::string_view text) {
  double x = 0.0;
  const auto r = std::from_chars(text.data(), text.data() + text.size(), x);
  if (r.ec != std::errc() || r.ptr != text.data() + text.size())
    bad_canonical("bad number '" + std::string(text) + "'");
  return x;
}

// The formula names and domain variables of each type, in canonical order, as read_geometry
// (server/geometry_json.cpp) builds them from a posted definition.
struct TypeLayout {
  GeometryType type;
  std::vector<std::string> required, optional, domain, parameters;
};

const TypeLayout* layout_of(std::string_view type, std::size_t formulas) {
  static const TypeLayout layouts[] = {
      {GeometryType::parametric_surface, {"x", "y", "z"}, {}, {"u", "v"}, {"u", "v"}},
      {GeometryType::parametric_curve, {"x", "y"}, {"z"}, {"t"}, {"t"}},
      {GeometryType::implicit_curve, {"equations[0]"}, {}, {"x", "y"}, {}},
      {GeometryType::implicit_curve, {"equations[0]", "equations[1]"}, {}, {"x", "y", "z"}, {}},
      {GeometryType::implicit_surface, {"equation"}, {}, {"x", "y", "z"}, {}},
  };
  for (const auto& l : layouts)
    if (type == to_string(l.type) && formulas >= l.required.size() &&
        formulas <= l.required.size() + l.optional.size())
      return &l;
  return nullptr;
}

// A nested list of numbers, [[1,2],[3]]: its depth must be `depth` (1: a list of numbers) and
// every entry at the same depth; read into nested vectors by the caller.
struct NestedList {
  double number = 0.0;
  std::vector<NestedList> items;
  bool is_list = false;
};

NestedList read_nested(std::string_view& text, int depth) {
  NestedList out;
  if (depth == 0) {
    const std::size_t end = text.find_first_of(",]");
    out.number = read_number(text.substr(0, end));
    text.remove_prefix(end == std::string_view::npos ? text.size() : end);
    return out;
  }
  if (text.empty() || text.front() != '[') bad_canonical("a list does not start with [");
  text.remove_prefix(1);
  out.is_list = true;
  while (true) {
    out.items.push_back(read_nested(text, depth - 1));
    if (text.empty()) bad_canonical("a list is not closed");
    const char c = text.front();
    text.remove_prefix(1);
    if (c == ']') break;
    if (c != ',') bad_canonical("a list's entries are not separated by commas");
  }
  return out;
}

NestedList read_whole(std::string_view text, int depth) {
  NestedList out = read_nested(text, depth);
  if (!text.empty()) bad_canonical("text after a list");
  return out;
}

std::vector<double> numbers_of(const NestedList& list) {
  std::vector<double> out;
  for (const NestedList& x : list.items) out.push_back(x.number);
  return out;
}

// The members after type= of a bspline_curve or bspline_surface.
BSplineNet parse_net(const std::vector<std::string_view>& members, bool surface) {
  BSplineNet net;
  for (const std::string_view member : members) {
    const auto eq = member.find('=');
    if (eq == std::string_view::npos) bad_canonical("member '" + std::string(member) + "' has no name=");
    const std::string_view name = member.substr(0, eq), value = member.substr(eq + 1);
    if (name == "degree") {
      for (std::size_t start = 0;;) {
        const auto comma = value.find(',', start);
        const std::string_view part =
            value.substr(start, comma == std::string_view::npos ? comma : comma - start);
        int d = 0;
        const auto r = std::from_chars(part.data(), part.data() + part.size(), d);
        if (r.ec != std::errc() || r.ptr != part.data() + part.size()) bad_canonical("bad degree");
        net.degree.push_back(d);
        if (comma == std::string_view::npos) break;
        start = comma + 1;
      }
    } else if (name == "knots.u" || name == "knots.v") {
      net.knots.push_back(numbers_of(read_whole(value, 1)));
    } else if (name == "control_points") {
      const NestedList list = read_whole(value, surface ? 3 : 2);
      if (surface)
        for (const NestedList& row : list.items) {
          net.control_points.emplace_back();
          for (const NestedList& point : row.items) net.control_points.back().push_back(numbers_of(point));
        }
      else {
        net.control_points.emplace_back();
        for (const NestedList& point : list.items) net.control_points.back().push_back(numbers_of(point));
      }
    } else if (name == "weights") {
      const NestedList list = read_whole(value, surface ? 2 : 1);
      if (surface)
        for (const NestedList& row : list.items) net.weights.push_back(numbers_of(row));
      else
        net.weights.push_back(numbers_of(list));
    } else {
      bad_canonical("member '" + std::string(name) + "' is not one of a B-spline's");
    }
  }
  return net;
}

}  // namespace

GeometryDefinition parse_canonical(std::string_view text) {
  std::vector<std::string_view> parts;
  for (std::size_t start = 0;;) {
    const auto end = text.find(';', start);
    parts.push_back(text.substr(start, end == std::string_view::npos ? std::string_view::npos : end - start));
    if (end == std::string_view::npos) break;
    start = end + 1;
  }
  constexpr std::string_view kType = "type=", kDomain = "domain.", kConstants = "constants.",
                             kPeriodic = "periodic";
  if (parts.size() < 2 || parts[0] != "footpoint/1" || parts[1].substr(0, kType.size()) != kType)
    bad_canonical("it does not start with footpoint/1;type=");
  const std::string_view type = parts[1].substr(kType.size());
  for (const GeometryType t : {GeometryType::bspline_surface, GeometryType::bspline_curve})
    if (type == to_string(t)) {
      GeometryDefinition def;
      def.type = t;
      def.bspline = parse_net({parts.begin() + 2, parts.end()}, t == GeometryType::bspline_surface);
      if (def.canonical() != text) bad_canonical("it is not in canonical form");
      return def;
    }

  // name=value members: the formulas first, then the domain, then the constants, then the
  // periodic parameters (a comma-separated list).
  std::vector<std::pair<std::string_view, std::string_view>> formulas, domain, constants;
  std::vector<std::string> periodic;
  for (std::size_t i = 2; i < parts.size(); ++i) {
    const auto eq = parts[i].find('=');
    if (eq == std::string_view::npos || eq == 0)
      bad_canonical("member '" + std::string(parts[i]) + "' has no name=");
    std::string_view name = parts[i].substr(0, eq), value = parts[i].substr(eq + 1);
    if (name.substr(0, kDomain.size()) == kDomain)
      domain.emplace_back(name.substr(kDomain.size()), value);
    else if (name.substr(0, kConstants.size()) == kConstants)
      constants.emplace_back(name.substr(kConstants.size()), value);
    else if (name == kPeriodic)
      for (std::size_t start = 0;;) {
        const auto comma = value.find(',', start);
        periodic.emplace_back(value.substr(start, comma == std::string_view::npos ? comma : comma - start));
        if (comma == std::string_view::npos) break;
        start = comma + 1;
      }
    else
      formulas.emplace_back(name, value);
  }
  const TypeLayout* layout = layout_of(type, formulas.size());
  if (!layout)
    bad_canonical("type '" + std::string(type) + "' with " + std::to_string(formulas.size()) + " formulas");

  GeometryDefinition def;
  def.type = layout->type;
  for (std::size_t i = 0; i < formulas.size(); ++i) {
    const std::string& expected =
        i < layout->required.size() ? layout->required[i] : layout->optional[i - layout->required.size()];
    if (formulas[i].first != expected)
      bad_canonical("formula " + std::to_string(i) + " is named '" + std::string(formulas[i].first) +
                    "', not " + expected);
    def.formulas.push_back({expected, std::string(formulas[i].second)});
  }
  if (domain.size() != layout->domain.size()) bad_canonical("the domain does not have the type's variables");
  for (std::size_t i = 0; i < domain.size(); ++i) {
    const auto [name, value] = domain[i];
    const auto comma = value.find(',');
    if (name != layout->domain[i] || value.size() < 5 || value.front() != '[' || value.back() != ']' ||
        comma == std::string_view::npos)
      bad_canonical("bad domain member '" + std::string(name) + "=" + std::string(value) + "'");
    def.domain.push_back({std::string(name),
                          {read_number(value.substr(1, comma - 1)),
                           read_number(value.substr(comma + 1, value.size() - comma - 2))}});
  }
  for (const auto& [name, value] : constants)
    if (!def.constants.emplace(std::string(name), read_number(value)).second)
      bad_canonical("constant '" + std::string(name) + "' appears twice");
  for (const std::string& name : periodic)
    if (std::find(layout->parameters.begin(), layout->parameters.end(), name) == layout->parameters.end())
      bad_canonical("'" + name + "' is no parameter of a " + std::string(type));
  def.periodic = std::move(periodic);
  // Whatever the members parsed to must print back to these very bytes (order, number forms,
  // no whitespace), so that the text and the definition have one id.
  if (def.canonical() != text) bad_canonical("it is not in canonical form");
  return def;
}

}  // namespace footpoint
