// Compiled geometries (what the cache holds): a definition is validated and compiled once; the
// compiled object is immutable, shared by all threads, and answers projections by method name.
#pragma once
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "compiled/geometry_definition.hpp"
#include "formula/program.hpp"
#include "geometry/geometry_error.hpp"
#include "geometry/projection_result.hpp"

namespace footpoint {

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
