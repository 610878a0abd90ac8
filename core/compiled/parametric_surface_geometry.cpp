#include "compiled/parametric_surface_geometry.hpp"

#include <cmath>
#include <string>

#include "parametric/solvers/first_order.hpp"
#include "parametric/solvers/gsa.hpp"
#include "parametric/solvers/hybrid.hpp"
#include "parametric/solvers/newton.hpp"
#include "parametric/solvers/surface_auto.hpp"
#include "parametric/solvers/surface_certificate.hpp"

namespace footpoint {

namespace {

// The papers' methods take the formulas and the domain, and start from options.initial. With
// options.certify, an answer inside the domain gets its certificate (certified or refuted as it
// is: they search nothing beyond their own iteration).
template <ProjectionResult (*solve)(const SurfaceFormulas&, const ParamBox&, const Vec3&, const Options&)>
ProjectionResult from_start(const ParametricSurface& s, Vec3 p, const Options& o) {
  ProjectionResult r = solve(s.formulas(), s.domain(), p, o);
  if (o.certify.value_or(false) && std::isfinite(r.distance) && s.domain().contains(r.params[0], r.params[1]))
    r.summary.certificate =
        surface::certify_answer(s.cells(), s.formulas(), s.domain(), p, r.params[0], r.params[1]);
  return r;
}

// What the papers' iteration reports (parametric/solvers/surface_paper_iteration.hpp): it stops converged, on
// its budget, on a growing, non-finite or degenerate step, or converged outside the domain.
constexpr std::uint32_t kParametricSurfacePaperStatuses =
    statuses({Status::converged, Status::max_iterations, Status::diverged, Status::non_finite,
              Status::degenerate, Status::outside_domain, Status::deadline_exceeded});

// The method table of parametric surfaces.
constexpr Method<ParametricSurface> kParametricSurfaceMethods[] = {
    {{"auto",
      "global nearest point over the closed domain (edges and corners included): cached cell bounds, "
      "bound-constrained Newton from the surviving cells; options.initial is a warm start",
      "",
      {},
      kGlobalOptions | option_initial | option_max_minima,
      statuses({Status::converged, Status::max_iterations, Status::non_finite, Status::degenerate,
                Status::beyond_max_distance, Status::deadline_exceeded})},
     [](const ParametricSurface& s, Vec3 p, const Options& o) {
       return surface::project_auto(s.cells(), s.formulas(), s.domain(), s.closure(), p, o);
     }},
    {{"gsa",
      "Geometric Strategy Algorithm: normal-curvature sphere step, unclamped from a start",
      "gsa-parametric-surface (Algorithm 1, eqs. (3)-(20))",
      {kCitationGsa},
      kLocalOptions,
      kParametricSurfacePaperStatuses},
     from_start<surface::project_gsa>},
    {{"first_order",
      "tangent-plane (H-H-H) first-order iteration, unclamped from a start",
      "gsa-parametric-surface (eq. (2)); hybrid-second-order-surface (eq. (5))",
      {kCitationGsa, kCitationHybrid},
      kLocalOptions,
      kParametricSurfacePaperStatuses},
     from_start<surface::project_first_order>},
    {{"hybrid",
      "first-order steps until the Newton map contracts, then Newton, unclamped from a start",
      "hybrid-second-order-surface (Algorithm 1, eqs. (22)-(24))",
      {kCitationHybrid},
      kLocalOptions,
      kParametricSurfacePaperStatuses},
     from_start<surface::project_hybrid>},
    {{"newton",
      "Newton's method on <p - s, s_u> = <p - s, s_v> = 0, unclamped from a start",
      "hybrid-second-order-surface (eq. (22)); gsa-parametric-surface (Table 9)",
      {kCitationHybrid, kCitationGsa},
      kLocalOptions,
      kParametricSurfacePaperStatuses},
     from_start<surface::project_newton>},
};

const MethodTable<ParametricSurface>& parametric_surface_method_table() {
  static const MethodTable<ParametricSurface> t(kParametricSurfaceMethods, PointDims::spatial);
  return t;
}

// The directions (u, v) the definition declares periodic.
std::array<bool, 2> declared_uv(const GeometryDefinition& def) {
  const std::vector<bool> declared = declared_periodic(def, {"u", "v"});
  return {declared[0], declared[1]};
}

std::array<double, 2> domain_of(const GeometryDefinition& def, const std::string& name) {
  for (const auto& [n, range] : def.domain)
    if (n == name) return range;
  throw GeometryError("bad_domain", "domain." + name, -1, "domain." + name + " is missing");
}

}  // namespace

ParametricSurface::ParametricSurface(GeometryDefinition def, formula::Program program, const ParamBox& box,
                                     CompileBudget& budget, const SurfaceSeedingOptions& seeding)
    : CompiledGeometry(std::move(def)),
      formulas_(std::move(program)),
      box_(box),
      closure_(detect_surface_closure(formulas_, box_, declared_uv(definition()))),
      self_covering_(detect_self_covering(formulas_, box_)),
      cells_(formulas_, box_, budget, seeding, self_covering_) {}

const std::vector<MethodInfo>& ParametricSurface::methods() const {
  return parametric_surface_method_table().infos();
}

ProjectionResult ParametricSurface::project_with(std::size_t index, const double* p,
                                                 const Options& options) const {
  return parametric_surface_method_table().project(index, *this, {p[0], p[1], p[2]}, options);
}

bool ParametricSurface::evaluate(const double* t, Evaluation& out) const {
  out = evaluation_of(formulas_.jet(t[0], t[1]));
  out.inside_domain = box_.contains(t[0], t[1]);
  return true;
}

bool ParametricSurface::foot_normal(const ProjectionResult& r, std::array<double, 3>& n) const {
  if (r.summary.location == Location::pole) return false;
  Evaluation e;
  evaluate(r.params.data(), e);
  if (!e.normal_defined) return false;
  n = {e.normal.x, e.normal.y, e.normal.z};
  return true;
}

const std::vector<MethodInfo>& parametric_surface_methods() {
  return parametric_surface_method_table().infos();
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
  CompileBudget budget(limits.deadline, limits.max_geometry_bytes);
  return std::make_shared<ParametricSurface>(def, std::move(program), box, budget);
}

}  // namespace footpoint
