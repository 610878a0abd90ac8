// Shared by the curve tests: a reference case of tests/data/curve_*_cases.json ("kind":
// paramcurve, implicit2d or curve3d; "formulas" and "domain" as tests/data/README.md says)
// compiled as the service compiles its definition.
#pragma once
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "compiled/compiled_geometry.hpp"

namespace footpoint::test {

inline std::shared_ptr<const CompiledGeometry> compile_curve_case(const nlohmann::json& c) {
  GeometryDefinition def;
  const std::string kind = c["kind"];
  const nlohmann::json& f = c["formulas"];
  const nlohmann::json& d = c["domain"];
  if (kind == "paramcurve") {
    def.type = GeometryType::parametric_curve;
    def.formulas = {{"x", f["x"]}, {"y", f["y"]}};
    if (f.contains("z")) def.formulas.push_back({"z", f["z"]});
    def.domain = {{"t", {d["t"][0], d["t"][1]}}};
    return compile_parametric_curve(def, {});
  }
  def.type = GeometryType::implicit_curve;
  if (kind == "implicit2d") {
    def.formulas = {{"equations[0]", f["f"]}};
    def.domain = {{"x", {d["x"][0], d["x"][1]}}, {"y", {d["y"][0], d["y"][1]}}};
  } else {
    def.formulas = {{"equations[0]", f["f1"]}, {"equations[1]", f["f2"]}};
    def.domain = {
        {"x", {d["x"][0], d["x"][1]}}, {"y", {d["y"][0], d["y"][1]}}, {"z", {d["z"][0], d["z"][1]}}};
  }
  return compile_implicit_curve(def, {});
}

}  // namespace footpoint::test
