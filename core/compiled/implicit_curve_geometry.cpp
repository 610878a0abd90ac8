#include "compiled/implicit_curve_geometry.hpp"

#include <stdexcept>
#include <string>

#include "solvers/curve/accelerated_correction.hpp"
#include "solvers/curve/complete_projection.hpp"
#include "solvers/curve/foot_point_march.hpp"
#include "solvers/curve/implicit_curve_auto.hpp"
#include "solvers/curve/simplified_projection.hpp"
#include "solvers/curve/steepest_descent.hpp"
#include "solvers/curve/tangent_foot.hpp"

namespace footpoint {

namespace {

const std::vector<MethodInfo>& spatial_methods() {
  static const std::vector<MethodInfo> methods{
      {"auto",
       "global nearest point in the box: interval subdivision finds every piece of the curve, samples "
       "seed Newton on the Lagrange system; singular points and box-face crossings are candidates",
       ""},
      {"steepest_descent",
       "Newton steepest-descent steps alternately onto f1 = 0 and f2 = 0 (lands on the curve)",
       "spatial-algebraic-curve (Algorithm 1, eq. (9))"},
      {"foot_point_march",
       "Algorithm 1 and the tangent foot point Q alternated until the curve point stops moving",
       "spatial-algebraic-curve (Algorithms 1 + 2, eqs. (10)-(13))"},
      {"accelerated", "Algorithm 1, then the accelerating and correcting iteration",
       "spatial-algebraic-curve (Algorithm 3, eqs. (14)-(19))"},
      {"complete", "Algorithm 1, five rounds of Algorithms 2 + 1, then Algorithm 3",
       "spatial-algebraic-curve (Algorithm 4)"},
      {"simplified", "Algorithm 1, then eq. (20) until the iterates stop moving",
       "spatial-algebraic-curve (Algorithm 5, eq. (20))"},
  };
  return methods;
}

const std::vector<MethodInfo>& planar_methods() {
  static const std::vector<MethodInfo> methods{
      {"auto",
       "global nearest point in the box: interval subdivision finds every piece of the curve, samples "
       "seed Newton on the Lagrange system; singular points and box-edge crossings are candidates",
       ""},
      {"tangent_foot", "Newton steps (2) onto the curve, then the tangent foot point (4), until they agree",
       "spatial-algebraic-curve (introduction, eqs. (2) and (4))"},
  };
  return methods;
}

}  // namespace

ImplicitCurve::ImplicitCurve(GeometryDefinition def, ImplicitEquations equations, Box3 box)
    : CompiledGeometry(std::move(def)),
      equations_(std::move(equations)),
      box_(box),
      discovery_(discover_implicit_curve(equations_, box_)),
      index_(discovery_.samples) {}

const std::vector<MethodInfo>& ImplicitCurve::methods() const {
  return equations_.planar() ? planar_methods() : spatial_methods();
}

ProjectionResult ImplicitCurve::project(const double* p, std::string_view method,
                                        const Options& options) const {
  const bool planar = equations_.planar();
  const Vec3 q{p[0], p[1], planar ? 0.0 : p[2]};
  if (method == "auto") return curve::implicit_curve_auto(equations_, box_, discovery_, index_, q, options);
  if (planar) {
    if (method == "tangent_foot") return curve::tangent_foot(equations_, box_, q, options);
  } else {
    if (method == "steepest_descent") return curve::steepest_descent(equations_, box_, q, options);
    if (method == "foot_point_march") return curve::foot_point_march(equations_, box_, q, options);
    if (method == "accelerated") return curve::accelerated(equations_, box_, q, options);
    if (method == "complete") return curve::complete_projection(equations_, box_, q, options);
    if (method == "simplified") return curve::simplified_projection(equations_, box_, q, options);
  }
  throw std::invalid_argument("implicit_curve has no method '" + std::string(method) + "'");
}

std::size_t ImplicitCurve::memory_bytes() const {
  return sizeof(*this) + equations_.program().memory_bytes() + discovery_.samples.memory_bytes() +
         index_.memory_bytes();
}

std::shared_ptr<const CompiledGeometry> compile_implicit_curve(const GeometryDefinition& def,
                                                               const formula::CompileLimits& limits) {
  const std::size_t n = def.formulas.size();
  if (n != 1 && n != 2)
    throw GeometryError("wrong_shape", "equations", -1,
                        "an implicit curve has one equation in x, y (planar) or two in x, y, z (spatial)");
  for (std::size_t i = 0; i < n; ++i)
    if (def.formulas[i].name != "equations[" + std::to_string(i) + "]")
      throw GeometryError("wrong_shape", def.formulas[i].name, -1,
                          "implicit curve formulas are named equations[0], equations[1]");
  const bool planar = n == 1;
  const std::vector<std::string> names =
      planar ? std::vector<std::string>{"x", "y"} : std::vector<std::string>{"x", "y", "z"};
  validate_domain(def, names);
  formula::Program program = compile_formulas(def, names, limits);
  Box3 box;  // planar curves keep lo.z = hi.z = 0
  for (std::size_t k = 0; k < names.size(); ++k)
    for (const auto& [name, range] : def.domain)
      if (name == names[k]) {
        box.lo[static_cast<int>(k)] = range[0];
        box.hi[static_cast<int>(k)] = range[1];
      }
  auto curve = std::make_shared<ImplicitCurve>(def, ImplicitEquations(std::move(program), planar), box);
  // Nothing to project onto: a definition error, not a per-point failure.
  if (curve->discovery().samples.size() == 0)
    throw GeometryError("empty_curve", "domain", -1,
                        "no point of the curve lies in the box (the interval search excluded the whole box)");
  return curve;
}

}  // namespace footpoint
