#include <algorithm>
#include <stdexcept>
#include <string>

#include "compiled/parametric_surface_geometry.hpp"
#include "solvers/surface/first_order.hpp"
#include "solvers/surface/gsa.hpp"
#include "solvers/surface/hybrid.hpp"
#include "solvers/surface/newton.hpp"
#include "solvers/surface/surface_auto.hpp"

namespace footpoint {

namespace {

const std::vector<MethodInfo>& surface_methods() {
  static const std::vector<MethodInfo> methods = {
      {"auto",
       "global nearest point over the closed domain (edges and corners included): cached cell bounds, "
       "bound-constrained Newton from the surviving cells",
       ""},
      {"gsa", "Geometric Strategy Algorithm: normal-curvature sphere step, unclamped from a start",
       "gsa-parametric-surface (Algorithm 1, eqs. (3)-(20))"},
      {"first_order", "tangent-plane (H-H-H) first-order iteration, unclamped from a start",
       "gsa-parametric-surface (eq. (2)); hybrid-second-order-surface (eq. (5))"},
      {"hybrid", "first-order steps until the Newton map contracts, then Newton, unclamped from a start",
       "hybrid-second-order-surface (Algorithm 1, eqs. (22)-(24))"},
      {"newton", "Newton's method on <p - s, s_u> = <p - s, s_v> = 0, unclamped from a start",
       "hybrid-second-order-surface (eq. (22)); gsa-parametric-surface (Table 9)"},
  };
  return methods;
}

std::array<double, 2> domain_of(const GeometryDefinition& def, const std::string& name) {
  for (const auto& [n, range] : def.domain)
    if (n == name) return range;
  throw GeometryError("bad_domain", "domain." + name, -1, "domain." + name + " is missing");
}

}  // namespace

ParametricSurface::ParametricSurface(GeometryDefinition def, formula::Program program, const ParamBox& box,
                                     const SurfaceSeedingOptions& seeding)
    : CompiledGeometry(std::move(def)),
      formulas_(std::move(program)),
      box_(box),
      cells_(formulas_, box_, seeding) {}

const std::vector<MethodInfo>& ParametricSurface::methods() const { return surface_methods(); }

ProjectionResult ParametricSurface::project(const double* p, std::string_view method,
                                            const Options& options) const {
  const Vec3 point{p[0], p[1], p[2]};
  if (method == "auto") return surface::project_auto(cells_, formulas_, box_, point, options);
  if (method == "gsa") return surface::project_gsa(formulas_, box_, point, options);
  if (method == "first_order") return surface::project_first_order(formulas_, box_, point, options);
  if (method == "hybrid") return surface::project_hybrid(formulas_, box_, point, options);
  if (method == "newton") return surface::project_newton(formulas_, box_, point, options);
  throw std::invalid_argument("parametric_surface has no method '" + std::string(method) + "'");
}

std::size_t ParametricSurface::memory_bytes() const {
  return sizeof(*this) + formulas_.program().memory_bytes() + cells_.memory_bytes();
}

std::shared_ptr<const CompiledGeometry> compile_parametric_surface(const GeometryDefinition& def,
                                                                   const formula::CompileLimits& limits) {
  validate_domain(def, {"u", "v"});
  static const char* const names[3] = {"x", "y", "z"};
  if (def.formulas.size() != 3)
    throw GeometryError("bad_formulas", "formulas", -1, "a parametric surface needs the formulas x, y and z");
  for (int i = 0; i < 3; ++i)
    if (def.formulas[static_cast<std::size_t>(i)].name != names[i])
      throw GeometryError("bad_formulas", names[i], -1,
                          std::string("formula ") + std::to_string(i) + " must be '" + names[i] + "'");
  formula::Program program = compile_formulas(def, {"u", "v"}, limits);
  const auto u = domain_of(def, "u"), v = domain_of(def, "v");
  const ParamBox box{u[0], u[1], v[0], v[1]};
  return std::make_shared<ParametricSurface>(def, std::move(program), box);
}

}  // namespace footpoint
