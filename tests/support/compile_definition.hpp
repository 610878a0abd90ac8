// Shared by the tests that compile a geometry from its definition's parts.
#pragma once
#include <array>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "compiled/compiled_geometry.hpp"

namespace footpoint::test {

inline std::shared_ptr<const CompiledGeometry> compile_definition(
    GeometryType type, std::vector<formula::NamedFormula> formulas,
    std::vector<std::pair<std::string, std::array<double, 2>>> domain) {
  GeometryDefinition def;
  def.type = type;
  def.formulas = std::move(formulas);
  def.domain = std::move(domain);
  return compile_geometry(def);
}

}  // namespace footpoint::test
