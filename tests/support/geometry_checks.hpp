// Checks shared by the tests of the compiled geometries (tests/core/compiled/): vectors against
// closed forms, the error a definition is refused with, the method table and the certify option.
#pragma once
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <doctest/doctest.h>

#include "compiled/compiled_geometry.hpp"

namespace footpoint::test {

// Each coordinate of got within `relative` of want's largest coordinate (at least 1): exact
// derivatives agree with their closed forms to rounding.
inline void check_vec_close(const Vec3& got, const Vec3& want, double relative = 1e-12) {
  const double scale = std::max({1.0, std::abs(want.x), std::abs(want.y), std::abs(want.z)});
  CHECK(std::abs(got.x - want.x) <= relative * scale);
  CHECK(std::abs(got.y - want.y) <= relative * scale);
  CHECK(std::abs(got.z - want.z) <= relative * scale);
}

// The code of the GeometryError that compiling def within `limits` throws (its field in *field),
// "" when it compiles.
inline std::string compile_error_code(const GeometryDefinition& def, std::string* field = nullptr,
                                      const formula::CompileLimits& limits = {}) {
  try {
    compile_geometry(def, limits);
  } catch (const GeometryError& e) {
    if (field) *field = e.field;
    return e.code;
  }
  return "";
}

// g offers the rows of its type's table (methods_of) in the table's order, and refuses the
// method `unknown` with `message`.
inline void check_method_table(const CompiledGeometry& g, GeometryType type, const char* unknown,
                               const std::string& message) {
  const std::vector<MethodInfo>& table = methods_of(type);
  REQUIRE(g.methods().size() == table.size());
  for (std::size_t k = 0; k < table.size(); ++k) CHECK(g.methods()[k].name == table[k].name);
  const auto refused = g.method(unknown);
  REQUIRE_FALSE(refused);
  CHECK(refused.error().message == message);
}

// Every method of g projecting p with `options`: `auto` certifies unasked, the others only with
// options.certify, and then their answer (here a global minimum) is certified.
inline void check_certify_option(const CompiledGeometry& g, const double* p, Options options) {
  for (const MethodInfo& info : g.methods()) {
    CAPTURE(info.name);
    options.certify.reset();
    CHECK(g.project(p, info.name, options).value().summary.certificate.computed == (info.name == "auto"));
    options.certify = true;
    const Certificate c = g.project(p, info.name, options).value().summary.certificate;
    CHECK(c.computed);
    CHECK(c.certified);
  }
}

// A definition that compiles is refused past the limits: a tape longer than max_nodes
// (formula_too_complex), a search structure larger than max_geometry_bytes (geometry_too_large).
inline void check_limits_refuse(const GeometryDefinition& def) {
  REQUIRE(compile_error_code(def).empty());
  formula::CompileLimits few_nodes;
  few_nodes.max_nodes = 1;
  CHECK(compile_error_code(def, nullptr, few_nodes) == "formula_too_complex");
  formula::CompileLimits few_bytes;
  few_bytes.max_geometry_bytes = 1024;
  CHECK(compile_error_code(def, nullptr, few_bytes) == "geometry_too_large");
}

}  // namespace footpoint::test
