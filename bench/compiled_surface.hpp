// A parametric surface of the benchmarks compiled as the service compiles it (formulas in
// muparser syntax, the closed domain [u0,u1] x [v0,v1]).
#pragma once

#include <array>
#include <memory>
#include <string>

#include "compiled/compiled_geometry.hpp"
#include "compiled/parametric_surface_geometry.hpp"

namespace footpoint::bench {

inline std::shared_ptr<const ParametricSurface> compile_surface(const std::string& x, const std::string& y,
                                                                const std::string& z, std::array<double, 2> u,
                                                                std::array<double, 2> v) {
  GeometryDefinition def;
  def.type = GeometryType::parametric_surface;
  def.formulas = {{"x", x}, {"y", y}, {"z", z}};
  def.domain = {{"u", u}, {"v", v}};
  return std::dynamic_pointer_cast<const ParametricSurface>(compile_parametric_surface(def, {}));
}

}  // namespace footpoint::bench
