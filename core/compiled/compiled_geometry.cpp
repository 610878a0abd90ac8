#include "compiled/compiled_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <string_view>
#include <system_error>
#include <vector>

#include "compiled/bspline_geometry.hpp"

namespace footpoint {

Expected<GeometryMethod, UnknownMethod> CompiledGeometry::method(std::string_view name) const {
  const std::vector<MethodInfo>& m = methods();
  for (std::size_t i = 0; i < m.size(); ++i)
    if (m[i].name == name) return GeometryMethod(*this, i);
  std::string names;
  for (const MethodInfo& info : m) (names += names.empty() ? "" : ", ") += info.name;
  return UnknownMethod{"unknown method '" + std::string(name) + "' for a " + to_string(definition_.type) +
                       " (" + names + ")"};
}

Expected<ProjectionResult, UnknownMethod> CompiledGeometry::project(const double* p, std::string_view name,
                                                                    const Options& options) const {
  const auto m = method(name);
  if (!m) return m.error();
  return m->project(p, options);
}

Evaluation evaluation_of(const SurfaceJet& j) {
  Evaluation out;
  out.point = j.s;
  out.first = {j.su, j.sv};
  out.second = {j.suu, j.suv, j.svv};
  const Vec3 n = cross(j.su, j.sv);
  const double length = norm(n);
  out.normal_defined = length > 0.0 && std::isfinite(length);
  out.normal = out.normal_defined ? n / length : Vec3{};
  return out;
}

Evaluation evaluation_of(const CurveJet& j) {
  Evaluation out;
  out.point = j.c;
  out.first = {j.d1, Vec3{}};
  out.second = {j.d2, Vec3{}, Vec3{}};
  // The principal normal: c'' less its part along the tangent, normalized.
  const double speed2 = norm2(j.d1);
  const Vec3 bend = speed2 > 0.0 ? j.d2 - (dot(j.d2, j.d1) / speed2) * j.d1 : Vec3{};
  const double length = norm(bend);
  out.normal_defined = length > 0.0 && std::isfinite(length);
  out.normal = out.normal_defined ? bend / length : Vec3{};
  return out;
}

bool planar_curve_normal(const Vec3& d, std::array<double, 3>& n) {
  const double speed = std::hypot(d.x, d.y);
  if (!(speed > 0.0 && std::isfinite(speed))) return false;
  n = {-d.y / speed, d.x / speed, 0.0};
  return true;
}

const char* option_name(std::uint32_t bit_index) {
  static const char* const names[kMethodOptionCount] = {"tolerance",  "max_iterations", "initial",
                                                        "all_minima", "trace",          "max_distance",
                                                        "certify",    "max_minima"};
  return bit_index < kMethodOptionCount ? names[bit_index] : "unknown";
}

const std::vector<MethodInfo>& methods_of(GeometryType type) {
  switch (type) {
    case GeometryType::parametric_surface:
      return parametric_surface_methods();
    case GeometryType::parametric_curve:
      return parametric_curve_methods();
    case GeometryType::implicit_curve:
      break;
    case GeometryType::implicit_surface:
      return implicit_surface_methods();
    case GeometryType::bspline_surface:
      return bspline_surface_methods();
    case GeometryType::bspline_curve:
      return bspline_curve_methods();
  }
  return implicit_curve_methods();
}

formula::Program compile_formulas(const GeometryDefinition& def, const std::vector<std::string>& variables,
                                  const formula::CompileLimits& limits) {
  try {
    return formula::Program::compile(def.formulas, variables, def.constants, limits);
  } catch (const formula::FormulaError& e) {
    throw GeometryError(formula::to_string(e.kind), e.formula, e.position, e.what(), e.suggestion);
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

std::vector<bool> declared_periodic(const GeometryDefinition& def,
                                    const std::vector<std::string>& parameters) {
  std::vector<bool> declared(parameters.size(), false);
  for (const std::string& name : def.periodic) {
    const auto it = std::find(parameters.begin(), parameters.end(), name);
    if (it == parameters.end()) {
      std::string names;
      for (const std::string& p : parameters) (names += names.empty() ? "" : ", ") += p;
      throw GeometryError("unknown_parameter", "periodic", -1,
                          "periodic: '" + name + "' is not a parameter of a " + to_string(def.type) +
                              (names.empty() ? " (it has none)" : " (" + names + ")"));
    }
    declared[static_cast<std::size_t>(it - parameters.begin())] = true;
  }
  return declared;
}

std::shared_ptr<const CompiledGeometry> compile_geometry(const GeometryDefinition& def,
                                                         const formula::CompileLimits& limits) {
  switch (def.type) {
    case GeometryType::parametric_surface:
      return compile_parametric_surface(def, limits);
    case GeometryType::parametric_curve:
      return compile_parametric_curve(def, limits);
    case GeometryType::implicit_curve:
      return compile_implicit_curve(def, limits);
    case GeometryType::implicit_surface:
      return compile_implicit_surface(def, limits);
    case GeometryType::bspline_surface:
      return compile_bspline_surface(def, limits);
    case GeometryType::bspline_curve:
      return compile_bspline_curve(def, limits);
  }
  throw GeometryError("bad_type", "type", -1, "unknown geometry type");
}

}  // namespace footpoint
