#include "geometry/geometry.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>

#include "geometry/sha256.hpp"

namespace footpoint {

const char* to_string(GeometryType t) {
  switch (t) {
    case GeometryType::parametric_surface:
      return "parametric_surface";
    case GeometryType::parametric_curve:
      return "parametric_curve";
    case GeometryType::implicit_curve:
      return "implicit_curve";
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

}  // namespace

std::string GeometryDefinition::canonical() const {
  std::string s = "footpoint/1;type=";
  s += to_string(type);
  for (const auto& f : formulas) {
    s += ';' + f.name + '=';
    for (char ch : f.expression)
      if (!std::isspace(static_cast<unsigned char>(ch))) s += ch;
  }
  for (const auto& [name, range] : domain)
    s += ";domain." + name + "=[" + shortest(range[0]) + ',' + shortest(range[1]) + ']';
  for (const auto& [name, value] : constants) s += ";constants." + name + '=' + shortest(value);
  return s;
}

std::string GeometryDefinition::id() const { return sha256_hex(canonical()).substr(0, 32); }

bool CompiledGeometry::has_method(std::string_view name) const {
  const auto& m = methods();
  return std::any_of(m.begin(), m.end(), [&](const MethodInfo& info) { return info.name == name; });
}

formula::Program compile_formulas(const GeometryDefinition& def, const std::vector<std::string>& variables,
                                  const formula::CompileLimits& limits) {
  try {
    return formula::Program::compile(def.formulas, variables, def.constants, limits);
  } catch (const formula::FormulaError& e) {
    throw GeometryError(formula::to_string(e.kind), e.formula, e.position, e.what());
  }
}

void validate_domain(const GeometryDefinition& def, const std::vector<std::string>& names) {
  for (const auto& name : names) {
    auto it =
        std::find_if(def.domain.begin(), def.domain.end(), [&](const auto& d) { return d.first == name; });
    if (it == def.domain.end())
      throw GeometryError("bad_domain", "domain." + name, -1, "domain." + name + " is missing");
    const auto [lo, hi] = it->second;
    if (!std::isfinite(lo) || !std::isfinite(hi))
      throw GeometryError("bad_domain", "domain." + name, -1, "domain." + name + " must be finite");
    if (!(lo < hi))
      throw GeometryError("bad_domain", "domain." + name, -1,
                          "domain." + name + " must be an interval [lo, hi] with lo < hi");
  }
  if (def.domain.size() != names.size())
    throw GeometryError("bad_domain", "domain", -1, "domain has unexpected entries");
}

}  // namespace footpoint
