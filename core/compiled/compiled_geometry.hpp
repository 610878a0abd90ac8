// Compiled geometries (what the cache holds): a definition is validated and compiled once; the
// compiled object is immutable, shared by all threads, and answers projections by method name.
#pragma once
#include <array>
#include <cmath>
#include <cstddef>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "compiled/expected.hpp"
#include "compiled/geometry_definition.hpp"
#include "compiled/method_table.hpp"
#include "formula/program.hpp"
#include "geometry/geometry_error.hpp"
#include "geometry/vec.hpp"
#include "parametric/geometry/parametric_curve.hpp"
#include "parametric/geometry/parametric_surface.hpp"
#include "projection/projection_result.hpp"

namespace footpoint {

// A method name the geometry does not have.
struct UnknownMethod {
  std::string message;  // names the geometry type and the methods it has
};

class CompiledGeometry;

// What a parametric geometry is at given parameters (CompiledGeometry::evaluate): its point, the
// exact first and second derivatives of the formulas, and the unit normal. Planar curves have
// z = 0 throughout.
struct Evaluation {
  Vec3 point;
  std::array<Vec3, 2> first{};   // surfaces s_u, s_v; curves c' (first[0])
  std::array<Vec3, 3> second{};  // surfaces s_uu, s_uv, s_vv; curves c'' (second[0])
  // Surfaces: s_u x s_v / |s_u x s_v|. Curves: the principal normal, the unit part of c''
  // orthogonal to c' (towards the centre of curvature). Undefined (normal_defined false) where
  // s_u x s_v = 0 (a pole, a degenerate edge) or, on a curve, where c' = 0 or the curvature is 0.
  Vec3 normal;
  bool normal_defined = false;
  bool inside_domain = false;  // the parameters lie in the closed domain (formulas extend beyond it)
};

// The Evaluation of a surface's jet (the normal s_u x s_v / |s_u x s_v|) and of a curve's (the
// principal normal); inside_domain is left to the caller.
Evaluation evaluation_of(const SurfaceJet& j);
Evaluation evaluation_of(const CurveJet& j);
// A planar curve's unit normal at a point with tangent d: d turned by +90 degrees in the plane,
// (-d_y, d_x) / |d|; false where d = 0.
bool planar_curve_normal(const Vec3& d, std::array<double, 3>& n);

// What an implicit geometry's equations are at a point (CompiledGeometry::evaluate_equations):
// the value of each equation as written in the definition (one for a surface f(x, y, z) = 0 or a
// planar curve f(x, y) = 0, two for a space curve f1 = f2 = 0), its exact gradient and Hessian
// (rows). Planar curves: the third coordinate, row and column are 0.
struct EquationEvaluation {
  int equations = 0;
  std::array<double, 2> value{};
  std::array<Vec3, 2> gradient{};
  std::array<std::array<Vec3, 3>, 2> hessian{};
  // grad f / |grad f| of the square-free equation (formula::Program::square_free: the normal of
  // (x^2 + y^2 + z^2 - 1)^2 = 0 is the sphere's, where the written gradient vanishes); undefined
  // (normal_defined false) where that gradient is 0 and for space curves (a plane of normals).
  Vec3 normal;
  bool normal_defined = false;
  bool inside_box = false;  // the point lies in the closed box (the equations extend beyond it)
};

// A method of one compiled geometry, found by name (CompiledGeometry::method): projects the
// geometry's points with it.
class GeometryMethod {
 public:
  const CompiledGeometry& geometry() const { return *geometry_; }
  const MethodInfo& info() const;
  // Projects the point p (geometry().point_dim() coordinates). Never throws for numerical trouble:
  // that is reported in the result's Summary.
  ProjectionResult project(const double* p, const Options& options) const;

 private:
  friend class CompiledGeometry;
  GeometryMethod(const CompiledGeometry& geometry, std::size_t index) : geometry_(&geometry), index_(index) {}
  const CompiledGeometry* geometry_;
  std::size_t index_;  // in geometry().methods()
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
  // The rows of its type's method table that apply to this geometry (planar or spatial curves
  // have methods of their own), in the table's order.
  virtual const std::vector<MethodInfo>& methods() const = 0;
  // The method called `name`, or UnknownMethod naming the methods there are.
  Expected<GeometryMethod, UnknownMethod> method(std::string_view name) const;
  // Projects the point p (point_dim() coordinates) with the method called `name`.
  Expected<ProjectionResult, UnknownMethod> project(const double* p, std::string_view name,
                                                    const Options& options) const;
  virtual std::size_t memory_bytes() const = 0;
  // The geometry at the parameters t (num_params() of them), from its formulas' exact jets.
  // False for a geometry without parameters (an implicit curve).
  virtual bool evaluate(const double* t, Evaluation& out) const {
    (void)t;
    (void)out;
    return false;
  }
  // The equations at the point x (point_dim() coordinates). False for a geometry without
  // equations (a parametric one).
  virtual bool evaluate_equations(const double* x, EquationEvaluation& out) const {
    (void)x;
    (void)out;
    return false;
  }
  // The unit normal at r's foot point (first point_dim() coordinates of n), or false where the
  // geometry has none there: parametric surfaces s_u x s_v / |s_u x s_v| (none at a pole or where
  // s_u x s_v = 0); planar parametric curves the tangent c' turned by +90 degrees in the plane,
  // (-y', x') / |c'|; implicit surfaces and planar implicit curves grad f / |grad f| of the
  // square-free equation (none at a singular point); space curves none (their normals form a plane). r has a
  // finite answer.
  virtual bool foot_normal(const ProjectionResult& r, std::array<double, 3>& n) const {
    (void)r;
    (void)n;
    return false;
  }

 private:
  friend class GeometryMethod;
  // Projects p with methods()[index].
  virtual ProjectionResult project_with(std::size_t index, const double* p, const Options& options) const = 0;

  GeometryDefinition definition_;
  std::string id_;
};

inline const MethodInfo& GeometryMethod::info() const { return geometry_->methods()[index_]; }
inline ProjectionResult GeometryMethod::project(const double* p, const Options& options) const {
  ProjectionResult r = geometry_->project_with(index_, p, options);
  std::array<double, 3> n{};
  if (std::isfinite(r.distance) && geometry_->foot_normal(r, n)) set_foot_normal(r, p, n);
  return r;
}

// Every method of a geometry type (planar and spatial curves' together), in its table's order.
const std::vector<MethodInfo>& methods_of(GeometryType type);

// Validates and compiles a definition (including what `auto` precomputes). Throws GeometryError.
std::shared_ptr<const CompiledGeometry> compile_geometry(const GeometryDefinition& def,
                                                         const formula::CompileLimits& limits = {});

// Per-type compilers and method tables (one per geometry file); compile_geometry and methods_of
// dispatch to them. Each compiler builds its search structures within one CompileBudget made from
// `limits` (its deadline and max_geometry_bytes; geometry/compile_budget.hpp), handed to every
// loop that builds them.
std::shared_ptr<const CompiledGeometry> compile_parametric_surface(const GeometryDefinition& def,
                                                                   const formula::CompileLimits& limits);
std::shared_ptr<const CompiledGeometry> compile_parametric_curve(const GeometryDefinition& def,
                                                                 const formula::CompileLimits& limits);
std::shared_ptr<const CompiledGeometry> compile_implicit_curve(const GeometryDefinition& def,
                                                               const formula::CompileLimits& limits);
std::shared_ptr<const CompiledGeometry> compile_implicit_surface(const GeometryDefinition& def,
                                                                 const formula::CompileLimits& limits);
const std::vector<MethodInfo>& parametric_surface_methods();
const std::vector<MethodInfo>& parametric_curve_methods();
const std::vector<MethodInfo>& implicit_curve_methods();
const std::vector<MethodInfo>& implicit_surface_methods();

// Shared by the per-type compilers: compiles formulas over variables, turning FormulaError into
// GeometryError, and checks that each domain interval is finite with lo < hi.
formula::Program compile_formulas(const GeometryDefinition& def, const std::vector<std::string>& variables,
                                  const formula::CompileLimits& limits);
void validate_domain(const GeometryDefinition& def, const std::vector<std::string>& names);
// Which of `parameters` the definition declares periodic, in their order; a name that is none of
// them throws GeometryError unknown_parameter (field "periodic").
std::vector<bool> declared_periodic(const GeometryDefinition& def,
                                    const std::vector<std::string>& parameters);

}  // namespace footpoint
