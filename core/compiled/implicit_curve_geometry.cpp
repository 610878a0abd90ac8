#include "compiled/implicit_curve_geometry.hpp"

#include <cmath>
#include <string>

#include "implicit/solvers/accelerated_correction.hpp"
#include "implicit/solvers/complete_projection.hpp"
#include "implicit/solvers/foot_point_march.hpp"
#include "implicit/solvers/implicit_curve_auto.hpp"
#include "implicit/solvers/implicit_curve_certificate.hpp"
#include "implicit/solvers/simplified_projection.hpp"
#include "implicit/solvers/steepest_descent.hpp"
#include "implicit/solvers/tangent_foot.hpp"

namespace footpoint {

namespace {

// The solvers of the spatial-curve paper [Curve] take the curve's equations as written and its
// box; asked for a certificate (options.certify), their answer gets the one `auto`'s would (a
// local method's answer is certified or refuted, not improved).
template <ProjectionResult (*solve)(const ImplicitEquations&, const Box3&, Vec3, const Options&)>
ProjectionResult in_box(const ImplicitCurve& c, Vec3 p, const Options& o) {
  ProjectionResult r = solve(c.written_equations(), c.box(), p, o);
  if (o.certify.value_or(false) && std::isfinite(r.distance))
    r.summary.certificate = curve::certify_implicit_curve_answer(
        c.factors(), c.box(), p, {r.foot[0], r.foot[1], c.equations().planar() ? 0.0 : r.foot[2]},
        r.distance);
  return r;
}

// The method table of implicit curves: `auto` for both, the planar iteration of [Curve]'s
// introduction for planar curves, its Algorithms 1-5 for spatial ones.
// What the papers' iteration reports (implicit/solvers/paper_iteration.cpp); not_orthogonal only for
// Algorithm 1 alone, which lands on the curve without seeking the foot point.
constexpr std::uint32_t kImplicitCurvePaperStatuses = statuses(
    {Status::converged, Status::max_iterations, Status::diverged, Status::non_finite, Status::degenerate,
     Status::outside_domain, Status::beyond_max_distance, Status::deadline_exceeded});

constexpr Method<ImplicitCurve> kImplicitCurveMethods[] = {
    {{"auto",
      "global nearest point in the box: interval subdivision proves every piece of the curve, samples "
      "seed Newton on the Lagrange system; singular points and the crossings of the box's edges "
      "(planar) or faces (spatial) are candidates; a certificate bounds the distance from below",
      "",
      {},
      kGlobalOptions | option_max_minima,
      statuses({Status::converged, Status::non_finite, Status::degenerate, Status::beyond_max_distance,
                Status::deadline_exceeded})},
     [](const ImplicitCurve& c, Vec3 p, const Options& o) {
       return curve::implicit_curve_auto(c.factors(), c.box(), p, o);
     }},
    {{"tangent_foot",
      "Newton steps (2) onto the curve, then the tangent foot point (4), until they agree",
      "spatial-algebraic-curve (introduction, eqs. (2) and (4))",
      {kCitationCurve},
      kLocalOptions | option_max_distance,
      kImplicitCurvePaperStatuses},
     in_box<curve::tangent_foot>,
     PointDims::planar},
    {{"steepest_descent",
      "Newton steepest-descent steps alternately onto f1 = 0 and f2 = 0 (lands on the curve)",
      "spatial-algebraic-curve (Algorithm 1, eq. (9))",
      {kCitationCurve},
      kLocalOptions | option_max_distance,
      kImplicitCurvePaperStatuses | statuses({Status::not_orthogonal})},
     in_box<curve::steepest_descent>,
     PointDims::spatial},
    {{"foot_point_march",
      "Algorithm 1 and the tangent foot point Q alternated until the curve point stops moving",
      "spatial-algebraic-curve (Algorithms 1 + 2, eqs. (10)-(13))",
      {kCitationCurve},
      kLocalOptions | option_max_distance,
      kImplicitCurvePaperStatuses},
     in_box<curve::foot_point_march>,
     PointDims::spatial},
    {{"accelerated",
      "Algorithm 1, then the accelerating and correcting iteration",
      "spatial-algebraic-curve (Algorithm 3, eqs. (14)-(19))",
      {kCitationCurve},
      kLocalOptions | option_max_distance,
      kImplicitCurvePaperStatuses},
     in_box<curve::accelerated>,
     PointDims::spatial},
    {{"complete",
      "Algorithm 1, five rounds of Algorithms 2 + 1, then Algorithm 3",
      "spatial-algebraic-curve (Algorithm 4)",
      {kCitationCurve},
      kLocalOptions | option_max_distance,
      kImplicitCurvePaperStatuses},
     in_box<curve::complete_projection>,
     PointDims::spatial},
    {{"simplified",
      "Algorithm 1, then eq. (20) until the iterates stop moving",
      "spatial-algebraic-curve (Algorithm 5, eq. (20))",
      {kCitationCurve},
      kLocalOptions | option_max_distance,
      kImplicitCurvePaperStatuses},
     in_box<curve::simplified_projection>,
     PointDims::spatial},
};

const MethodTable<ImplicitCurve>& implicit_curve_method_table(PointDims dims) {
  static const MethodTable<ImplicitCurve> planar(kImplicitCurveMethods, PointDims::planar);
  static const MethodTable<ImplicitCurve> spatial(kImplicitCurveMethods, PointDims::spatial);
  static const MethodTable<ImplicitCurve> every(kImplicitCurveMethods, PointDims::any);
  return dims == PointDims::planar ? planar : dims == PointDims::spatial ? spatial : every;
}

}  // namespace

// At most this many factor curves (each costs a discovery at compile time and a search and a
// certificate per point); equations with more stay whole.
constexpr std::size_t kMaxFactorCurves = 8;

ImplicitCurve::ImplicitCurve(GeometryDefinition def, ImplicitEquations equations, Box3 box,
                             CompileBudget& budget)
    : CompiledGeometry(std::move(def)), written_(std::move(equations)), box_(box) {
  const bool planar = written_.planar();
  std::vector<formula::Program> systems = written_.program().factor_systems(kMaxFactorCurves);
  if (systems.size() == 1) {
    whole_ = std::make_unique<const DiscoveredCurve>(ImplicitEquations(std::move(systems.front()), planar),
                                                     box_, budget);
    factors_.push_back(whole_.get());
    return;
  }
  whole_ = std::make_unique<const DiscoveredCurve>(
      ImplicitEquations(written_.program().square_free(), planar), box_, budget);
  for (formula::Program& system : systems) {
    auto f =
        std::make_unique<const DiscoveredCurve>(ImplicitEquations(std::move(system), planar), box_, budget);
    if (f->discovery.samples.size() == 0) continue;  // no point of this factor in the box
    factors_.push_back(f.get());
    factor_curves_.push_back(std::move(f));
  }
  // No factor with a point in the box: nor has the whole curve (empty_curve below), which then
  // stands for itself.
  if (factors_.empty()) factors_.push_back(whole_.get());
}

PointDims ImplicitCurve::dims() const {
  return equations().planar() ? PointDims::planar : PointDims::spatial;
}

const std::vector<MethodInfo>& ImplicitCurve::methods() const {
  return implicit_curve_method_table(dims()).infos();
}

ProjectionResult ImplicitCurve::project_with(std::size_t index, const double* p,
                                             const Options& options) const {
  return implicit_curve_method_table(dims()).project(
      index, *this, {p[0], p[1], equations().planar() ? 0.0 : p[2]}, options);
}

bool ImplicitCurve::planar_normal(double x, double y, Vec3& n) const {
  const Vec3 g = equations().jet({x, y, 0.0}).grad[0];
  const double length = std::hypot(g.x, g.y);
  if (!(length > 0.0 && std::isfinite(length))) return false;
  n = {g.x / length, g.y / length, 0.0};
  return true;
}

bool ImplicitCurve::foot_normal(const ProjectionResult& r, std::array<double, 3>& n) const {
  if (!equations().planar() || r.summary.location == Location::singular_point) return false;
  Vec3 u;
  if (!planar_normal(r.foot[0], r.foot[1], u)) return false;
  n = {u.x, u.y, 0.0};
  return true;
}

bool ImplicitCurve::evaluate_equations(const double* x, EquationEvaluation& out) const {
  const bool planar = written_.planar();
  const Vec3 at{x[0], x[1], planar ? 0.0 : x[2]};
  const ImplicitJet j = written_.jet(at);
  out.equations = planar ? 1 : 2;
  for (int e = 0; e < out.equations; ++e) {
    const std::size_t k = static_cast<std::size_t>(e);
    out.value[k] = j.f[k];
    out.gradient[k] = j.grad[k];
    out.hessian[k] = j.hess[k];
    if (planar) {  // f(x, y): no z row or column
      out.gradient[k].z = 0.0;
      for (int r = 0; r < 3; ++r) out.hessian[k][static_cast<std::size_t>(r)].z = 0.0;
      out.hessian[k][2] = Vec3{};
    }
  }
  if (planar) out.normal_defined = planar_normal(at.x, at.y, out.normal);
  out.inside_box = planar ? (at.x >= box_.lo.x && at.x <= box_.hi.x && at.y >= box_.lo.y && at.y <= box_.hi.y)
                          : box_.contains(at);
  return true;
}

const std::vector<MethodInfo>& implicit_curve_methods() {
  return implicit_curve_method_table(PointDims::any).infos();
}

std::size_t ImplicitCurve::memory_bytes() const {
  const formula::Program& written = written_.program();
  std::size_t bytes = sizeof(*this) + whole_->memory_bytes() +
                      (written.same_tape(equations().program()) ? 0 : written.memory_bytes()) +
                      factors_.capacity() * sizeof(factors_[0]);
  for (const auto& f : factor_curves_) bytes += f->memory_bytes();
  return bytes;
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
  declared_periodic(def, {});  // an implicit curve has no parameters to declare
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
  CompileBudget budget(limits.deadline, limits.max_geometry_bytes);
  auto curve =
      std::make_shared<ImplicitCurve>(def, ImplicitEquations(std::move(program), planar), box, budget);
  // Nothing to project onto: a definition error, not a per-point failure.
  if (curve->discovery().samples.size() == 0)
    throw GeometryError("empty_curve", "domain", -1,
                        "no point of the curve lies in the box (the interval search excluded the whole box)");
  return curve;
}

}  // namespace footpoint
