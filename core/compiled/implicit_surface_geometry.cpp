#include "compiled/implicit_surface_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "implicit/solvers/implicit_surface_certificate.hpp"
#include "implicit/solvers/implicit_surface_methods.hpp"

namespace footpoint {

namespace {

// A local method's answer, asked for a certificate (options.certify), gets it from the same
// bounds `auto` uses (certified or refuted, not improved).
template <ProjectionResult (*solve)(const ImplicitSurfaceEquation&, const Box3&, Vec3, const Options&)>
ProjectionResult local(const ImplicitSurface& s, Vec3 p, const Options& o) {
  ProjectionResult r = solve(s.equation(), s.box(), p, o);
  const Vec3 foot{r.foot[0], r.foot[1], r.foot[2]};
  if (o.certify.value_or(false) && std::isfinite(r.distance) && s.box().contains(foot))
    r.summary.certificate = surface_implicit::certify_union_answer(s.pieces(), p, foot, r.distance);
  return r;
}

constexpr std::uint32_t kImplicitSurfaceLocalStatuses = statuses(
    {Status::converged, Status::max_iterations, Status::diverged, Status::non_finite, Status::degenerate,
     Status::outside_domain, Status::beyond_max_distance, Status::deadline_exceeded});

constexpr Method<ImplicitSurface> kImplicitSurfaceMethods[] = {
    {{"auto",
      "global nearest point in the box: interval subdivision of the box, Newton on the Lagrange system "
      "from the nearest samples, the curves on the box's faces, its edges' points and the singular "
      "points are candidates; a branch-and-bound certificate bounds the distance from below",
      "",
      {},
      kGlobalOptions | option_max_minima,
      statuses(
          {Status::converged, Status::degenerate, Status::beyond_max_distance, Status::deadline_exceeded})},
     [](const ImplicitSurface& s, Vec3 p, const Options& o) {
       return surface_implicit::implicit_surface_union_auto(s.pieces(), p, o);
     }},
    {{"lagrange_newton",
      "Newton's method on the Lagrange system p - x = l grad f(x), f(x) = 0 from the start",
      "Nocedal and Wright, Numerical Optimization (Sec. 18.1)",
      {kCitationNocedalWright},
      kLocalOptions | option_max_distance,
      kImplicitSurfaceLocalStatuses},
     local<surface_implicit::lagrange_newton_method>},
    {{"first_order",
      "Hartmann's first-order foot-point iteration: Newton onto the surface, then the foot of p on the "
      "tangent plane, until the surface points stop moving",
      "Hartmann, On the curvature of curves and surfaces defined by normalforms (Sec. 5)",
      {kCitationHartmann},
      kLocalOptions | option_max_distance,
      kImplicitSurfaceLocalStatuses},
     local<surface_implicit::first_order_method>},
    {{"hu_wallner",
      "Hu and Wallner's second-order iteration: the foot of p on the curvature circle of the normal "
      "section toward p, moved onto the surface, until the surface points stop moving",
      "Hu and Wallner, A second order algorithm for orthogonal projection onto curves and surfaces",
      {kCitationHuWallner, kCitationGsa},
      kLocalOptions | option_max_distance,
      kImplicitSurfaceLocalStatuses},
     local<surface_implicit::hu_wallner_method>},
};

const MethodTable<ImplicitSurface>& implicit_surface_method_table() {
  static const MethodTable<ImplicitSurface> every(kImplicitSurfaceMethods, PointDims::any);
  return every;
}

}  // namespace

// At most this many factor surfaces (each costs a subdivision at compile time and a search and a
// certificate per point); equations with more stay whole.
constexpr std::size_t kMaxFactorSurfaces = 8;

ImplicitSurface::ImplicitSurface(GeometryDefinition def, formula::Program program, Box3 box,
                                 CompileBudget& budget)
    : CompiledGeometry(std::move(def)),
      written_(std::move(program)),
      equation_(written_.program().square_free()),
      box_(box) {
  std::vector<formula::Program> systems = written_.program().factor_systems(kMaxFactorSurfaces);
  if (systems.size() > 1)
    for (formula::Program& system : systems) {
      ImplicitSurfaceEquation factor(std::move(system));
      ImplicitSurfaceCells cells = subdivide_surface(factor, box_, budget);
      if (!cells.empty()) pieces_.push_back({std::move(factor), std::move(cells)});  // else none in the box
    }
  // Not split, or no factor surface in the box (nor then the whole, empty_surface below).
  if (pieces_.empty()) pieces_.push_back({equation_, subdivide_surface(equation_, box_, budget)});
}

const std::vector<MethodInfo>& ImplicitSurface::methods() const {
  return implicit_surface_method_table().infos();
}

bool ImplicitSurface::evaluate_equations(const double* x, EquationEvaluation& out) const {
  const Vec3 at{x[0], x[1], x[2]};
  const ImplicitSurfaceJet j = written_.jet(at);
  out.equations = 1;
  out.value[0] = j.f;
  out.gradient[0] = j.grad;
  out.hessian[0] = j.hess;
  out.normal_defined = unit_normal(at, out.normal);
  out.inside_box = box_.contains(at);
  return true;
}

bool ImplicitSurface::unit_normal(Vec3 x, Vec3& n) const {
  const Vec3 g = equation_.jet(x).grad;
  const double length = norm(g);
  if (!(length > 0.0 && std::isfinite(length))) return false;
  n = g / length;
  return true;
}

bool ImplicitSurface::foot_normal(const ProjectionResult& r, std::array<double, 3>& n) const {
  Vec3 u;
  if (r.summary.location == Location::singular_point || !unit_normal({r.foot[0], r.foot[1], r.foot[2]}, u))
    return false;
  n = {u.x, u.y, u.z};
  return true;
}

const std::vector<MethodInfo>& implicit_surface_methods() { return implicit_surface_method_table().infos(); }

ProjectionResult ImplicitSurface::project_with(std::size_t index, const double* p,
                                               const Options& options) const {
  return implicit_surface_method_table().project(index, *this, {p[0], p[1], p[2]}, options);
}

std::size_t ImplicitSurface::memory_bytes() const {
  const formula::Program& written = written_.program();
  std::size_t bytes = sizeof(*this) + equation_.program().memory_bytes() +
                      (written.same_tape(equation_.program()) ? 0 : written.memory_bytes()) +
                      pieces_.capacity() * sizeof(surface_implicit::SurfacePiece);
  for (const surface_implicit::SurfacePiece& piece : pieces_)
    bytes += piece.cells.memory_bytes() + (piece.equation.program().same_tape(equation_.program())
                                               ? 0
                                               : piece.equation.program().memory_bytes());
  return bytes;
}

std::shared_ptr<const CompiledGeometry> compile_implicit_surface(const GeometryDefinition& def,
                                                                 const formula::CompileLimits& limits) {
  if (def.formulas.size() != 1 || def.formulas[0].name != "equation")
    throw GeometryError("wrong_shape", "equation", -1, "an implicit surface has one equation in x, y, z");
  declared_periodic(def, {});  // no parameters to declare
  const std::vector<std::string> names{"x", "y", "z"};
  validate_domain(def, names);
  formula::Program program = compile_formulas(def, names, limits);
  Box3 box;
  for (std::size_t k = 0; k < names.size(); ++k)
    for (const auto& [name, range] : def.domain)
      if (name == names[k]) {
        box.lo[static_cast<int>(k)] = range[0];
        box.hi[static_cast<int>(k)] = range[1];
      }
  CompileBudget budget(limits.deadline, limits.max_geometry_bytes);
  auto surface = std::make_shared<ImplicitSurface>(def, std::move(program), box, budget);
  const std::vector<surface_implicit::SurfacePiece>& pieces = surface->pieces();
  const bool points =
      std::any_of(pieces.begin(), pieces.end(), [](const surface_implicit::SurfacePiece& piece) {
        const ImplicitSurfaceCells& c = piece.cells;
        return !c.samples.empty() || !c.edge_points.empty() || !c.singular_points.empty();
      });
  if (pieces.size() == 1 && pieces.front().cells.empty())
    throw GeometryError(
        "empty_surface", "domain", -1,
        "no point of the surface lies in the box (the interval search excluded the whole box)");
  // Cells that may hold the surface but no point of it found: the leaves are too large for Newton
  // from their centres to land (a box of 1e300), or the surface is smaller than its leaves.
  if (!points)
    throw GeometryError(
        "geometry_too_complex", "domain", -1,
        "the interval search could not exclude the whole box, but no point of the surface was "
        "found in its cells; shrink the box to where the surface is");
  return surface;
}

}  // namespace footpoint
