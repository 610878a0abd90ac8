#include "compiled/parametric_curve_geometry.hpp"

#include <cmath>
#include <string>

#include "parametric/seeding/curve_parametric_samples.hpp"
#include "parametric/solvers/curvature_circle.hpp"
#include "parametric/solvers/parametric_curve_auto.hpp"
#include "parametric/solvers/parametric_curve_certificate.hpp"
#include "parametric/solvers/parametric_newton.hpp"

namespace footpoint {
namespace {

// The local methods take the formulas, the domain and the samples' k-d tree (their default start);
// with options.certify an answer inside the domain gets its certificate, as it is.
template <ProjectionResult (*solve)(const CurveFormulas&, const ParamInterval&, const CurveSampleIndex&, Vec3,
                                    const Options&)>
ProjectionResult on_samples(const ParametricCurve& c, Vec3 p, const Options& o) {
  ProjectionResult r = solve(c.formulas(), c.domain(), c.sample_index(), p, o);
  if (o.certify.value_or(false) && std::isfinite(r.distance) && c.domain().contains(r.params[0]))
    r.summary.certificate = curve::certify_curve_answer(c.cells(), c.formulas(), c.domain(), p, r.params[0]);
  return r;
}

// What the local iteration reports (parametric/solvers/parametric_iteration.hpp and
// parametric_curve_summary.cpp).
constexpr std::uint32_t kParametricCurveLocalStatuses =
    statuses({Status::converged, Status::max_iterations, Status::non_finite, Status::degenerate,
              Status::outside_domain, Status::beyond_max_distance, Status::deadline_exceeded});

// The method table of parametric curves, planar and spatial alike.
constexpr Method<ParametricCurve> kParametricCurveMethods[] = {
    {{"auto",
      "global nearest point over [tmin, tmax], ends included: dense adaptive samples seed bracketed "
      "Newton at every candidate minimum",
      "",
      {},
      kGlobalOptions | option_max_minima,
      statuses({Status::converged, Status::non_finite, Status::degenerate, Status::beyond_max_distance,
                Status::deadline_exceeded})},
     [](const ParametricCurve& c, Vec3 p, const Options& o) {
       return curve::parametric_curve_auto(c.formulas(), c.domain(), c.sample_index(), c.cells(), c.closure(),
                                           p, o);
     }},
    {{"newton",
      "Newton's method on <c(t) - p, c'(t)> = 0 from options.initial or the nearest sample",
      "",
      {},
      kLocalOptions | option_max_distance,
      kParametricCurveLocalStatuses},
     on_samples<curve::parametric_newton>},
    {{"curvature_circle",
      "curvature circle iteration (Hu-Wallner) from options.initial or the nearest sample",
      "gsa-parametric-surface (Section 3, eqs. (21)-(22))",
      {kCitationHuWallner, kCitationGsa},
      kLocalOptions | option_max_distance,
      kParametricCurveLocalStatuses},
     on_samples<curve::curvature_circle>},
};

const MethodTable<ParametricCurve>& parametric_curve_method_table() {
  static const MethodTable<ParametricCurve> t(kParametricCurveMethods, PointDims::any);
  return t;
}

}  // namespace

// Each sample commits the curve to its place in samples_ (params included) and to a quarter of a
// cell and of a node of cells_ (a cell per four sample gaps, so n samples make at least (n-1)/4
// cells: the count is over by at most a quarter cell, less than sizeof(*this) and index_, which
// it leaves out).
ParametricSampling ParametricCurve::sampling() {
  ParametricSampling s;
  s.bytes_per_sample =
      ParametricSampling::kSampleBytes + (sizeof(ParametricCurveCell) + sizeof(ParametricCurveCellNode)) / 4;
  return s;
}

ParametricCurve::ParametricCurve(GeometryDefinition def, CurveFormulas formulas, ParamInterval domain,
                                 CompileBudget& budget)
    : CompiledGeometry(std::move(def)),
      formulas_(std::move(formulas)),
      domain_(domain),
      closure_(detect_curve_closure(formulas_, domain_, declared_periodic(definition(), {"t"})[0])),
      samples_(sample_parametric_curve(formulas_, domain_, budget, sampling())),
      index_(samples_),
      cells_(formulas_, domain_, samples_.params, budget) {}

const std::vector<MethodInfo>& ParametricCurve::methods() const {
  return parametric_curve_method_table().infos();
}

ProjectionResult ParametricCurve::project_with(std::size_t index, const double* p,
                                               const Options& options) const {
  return parametric_curve_method_table().project(index, *this,
                                                 {p[0], p[1], formulas_.dim() == 3 ? p[2] : 0.0}, options);
}

const std::vector<MethodInfo>& parametric_curve_methods() { return parametric_curve_method_table().infos(); }

bool ParametricCurve::evaluate(const double* t, Evaluation& out) const {
  out = evaluation_of(formulas_.jet(t[0]));
  out.inside_domain = domain_.contains(t[0]);
  return true;
}

bool ParametricCurve::foot_normal(const ProjectionResult& r, std::array<double, 3>& n) const {
  return formulas_.dim() == 2 && planar_curve_normal(formulas_.jet(r.params[0]).d1, n);
}

std::size_t ParametricCurve::memory_bytes() const {
  return sizeof(*this) + formulas_.program().memory_bytes() + samples_.memory_bytes() +
         index_.memory_bytes() + cells_.memory_bytes();
}

std::shared_ptr<const CompiledGeometry> compile_parametric_curve(const GeometryDefinition& def,
                                                                 const formula::CompileLimits& limits) {
  static const char* const names[] = {"x", "y", "z"};
  const std::size_t n = def.formulas.size();
  if (n != 2 && n != 3)
    throw GeometryError("wrong_shape", "formulas", -1,
                        "a parametric curve has formulas x, y (planar) or x, y, z");
  for (std::size_t i = 0; i < n; ++i)
    if (def.formulas[i].name != names[i])
      throw GeometryError("wrong_shape", def.formulas[i].name, -1,
                          "parametric curve formulas are x, y[, z] in order");
  validate_domain(def, {"t"});
  formula::Program program = compile_formulas(def, {"t"}, limits);
  const auto& range = def.domain.front().second;
  CompileBudget budget(limits.deadline, limits.max_geometry_bytes);
  return std::make_shared<ParametricCurve>(def, CurveFormulas(std::move(program)),
                                           ParamInterval{range[0], range[1]}, budget);
}

}  // namespace footpoint
