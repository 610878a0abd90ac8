// Geometry definitions (what a client posts) and compiled geometries (what the cache holds).
// A definition is validated and compiled once; the compiled object is immutable, shared by all
// threads, and answers projections by method name.
#pragma once
#include <array>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "formula/program.hpp"
#include "geometry/geometry_error.hpp"
#include "geometry/projection_result.hpp"

namespace footpoint {

enum class GeometryType { parametric_surface, parametric_curve, implicit_curve };
const char* to_string(GeometryType t);

struct GeometryDefinition {
  GeometryType type = GeometryType::parametric_surface;
  // parametric_surface: x, y, z (in u, v); parametric_curve: x, y[, z] (in t);
  // implicit_curve: equations[0][, equations[1]] (in x, y[, z]).
  std::vector<formula::NamedFormula> formulas;
  // Parameter domain (surfaces: u, v; curves: t) or box (implicit: x, y[, z]), in that order.
  std::vector<std::pair<std::string, std::array<double, 2>>> domain;
  std::map<std::string, double> constants;

  // Deterministic text form: same definition -> same text (formula whitespace removed, numbers
  // in shortest round-trip form). id() is a SHA-256 content hash of it (32 hex digits), so every
  // replica computes the same id for the same definition.
  std::string canonical() const;
  std::string id() const;
};

// The inverse of canonical(): the definition whose canonical text is `text`, with the formula
// names and domain variables a posted definition of its type has (a shared registry stores
// canonical texts; a replica compiles from them). canonical(parse_canonical(t)) == t for every
// text accepted; any other text throws GeometryError with code "bad_canonical".
GeometryDefinition parse_canonical(std::string_view text);

struct MethodInfo {
  std::string name;
  std::string description;  // one line
  std::string paper;        // e.g. "gsa-parametric-surface (Algorithm 1)" or "" for our own
};

class CompiledGeometry {
 public:
  explicit CompiledGeometry(GeometryDefinition def) : definition_(std::move(def)), id_(definition_.id()) {}
  virtual ~CompiledGeometry() = default;
  CompiledGeometry(const CompiledGeometry&) = delete;
  CompiledGeometry& operator=(const CompiledGeometry&) = delete;

  const GeometryDefinition& definition() const { return definition_; }
  const std::string& id() const { return id_; }

  virtual int point_dim() const = 0;   // 3, or 2 for planar curves
  virtual int num_params() const = 0;  // 2 surfaces, 1 parametric curves, 0 implicit curves
  virtual const std::vector<MethodInfo>& methods() const = 0;
  bool has_method(std::string_view name) const;
  // Projects the point p (point_dim() coordinates). `method` must be one of methods().
  // Never throws for numerical trouble: that is reported in the result's Summary.
  virtual ProjectionResult project(const double* p, std::string_view method,
                                   const Options& options) const = 0;
  virtual std::size_t memory_bytes() const = 0;

 private:
  GeometryDefinition definition_;
  std::string id_;
};

// Validates and compiles a definition (including what `auto` precomputes). Throws GeometryError.
std::shared_ptr<const CompiledGeometry> compile_geometry(const GeometryDefinition& def,
                                                         const formula::CompileLimits& limits = {});

// Per-type compilers (one per geometry file); compile_geometry dispatches to them.
std::shared_ptr<const CompiledGeometry> compile_parametric_surface(const GeometryDefinition& def,
                                                                   const formula::CompileLimits& limits);
std::shared_ptr<const CompiledGeometry> compile_parametric_curve(const GeometryDefinition& def,
                                                                 const formula::CompileLimits& limits);
std::shared_ptr<const CompiledGeometry> compile_implicit_curve(const GeometryDefinition& def,
                                                               const formula::CompileLimits& limits);

// Shared by the per-type compilers: compiles formulas over variables, turning FormulaError into
// GeometryError, and checks that each domain interval is finite with lo < hi.
formula::Program compile_formulas(const GeometryDefinition& def, const std::vector<std::string>& variables,
                                  const formula::CompileLimits& limits);
void validate_domain(const GeometryDefinition& def, const std::vector<std::string>& names);

}  // namespace footpoint
