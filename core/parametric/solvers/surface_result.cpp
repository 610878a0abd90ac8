#include "parametric/solvers/surface_result.hpp"

#include <cmath>
#include <limits>

#include "parametric/solvers/surface_convergence.hpp"

namespace footpoint::surface {

namespace {

// -1 on the lower bound, +1 on the upper one, 0 inside (or on a seam: no bound there).
int side(double x, double lo, double hi, bool periodic) {
  if (periodic) return 0;
  return x == lo ? -1 : (x == hi ? 1 : 0);
}

}  // namespace

Location location_in(const ParamBox& box, double u, double v, const SurfaceClosure* closure) {
  if (!box.contains(u, v)) return Location::unknown;
  if (closure) {
    const bool on[4] = {u == box.umin, u == box.umax, v == box.vmin, v == box.vmax};
    for (int e = 0; e < 4; ++e)
      if (on[e] && closure->pole(static_cast<BoxEdge>(e))) return Location::pole;
  }
  const bool u_edge = side(u, box.umin, box.umax, closure && closure->periodic(0)) != 0;
  const bool v_edge = side(v, box.vmin, box.vmax, closure && closure->periodic(1)) != 0;
  if (u_edge && v_edge) return Location::corner;
  if (u_edge || v_edge) return Location::edge;
  return Location::interior;
}

Params<2> seam_representative(const ParamBox& box, double u, double v, const SurfaceClosure* closure) {
  if (closure && closure->periodic(0) && u == box.umax) u = box.umin;
  if (closure && closure->periodic(1) && v == box.vmax) v = box.vmin;
  return {u, v};
}

ProjectionResult surface_result(const char* method, const Vec3& p, double u, double v, const Vec3& s,
                                const Vec3& su, const Vec3& sv, const ParamBox& box,
                                const SurfaceClosure* closure) {
  ProjectionResult r;
  r.dim = 3;
  r.num_params = 2;
  r.params = {u, v};
  r.foot = {s.x, s.y, s.z};
  r.distance = norm(p - s);
  r.summary.method = method;
  r.summary.location = location_in(box, u, v, closure);
  r.params = seam_representative(box, u, v, closure);
  const Orthogonality o = orthogonality(p, s, su, sv);
  const Vec3 d = p - s;
  const int sides[2] = {side(u, box.umin, box.umax, closure && closure->periodic(0)),
                        side(v, box.vmin, box.vmax, closure && closure->periodic(1))};
  const Vec3 tangents[2] = {su, sv};
  for (int i = 0; i < 2; ++i) {
    double residual = o.relative[i];
    // on a bound, only the sign's violation (along a pole's edge the tangent vanishes: 0 anyway)
    if (sides[i] != 0) {
      const double along = dot(d, tangents[i]);  // <p - s, s_i>
      const bool violated = sides[i] < 0 ? along > 0.0 : along < 0.0;
      if (!violated) residual = 0.0;
    }
    r.summary.orthogonality[i] = std::isfinite(residual) ? residual : std::numeric_limits<double>::max();
  }
  r.summary.on_boundary = r.summary.location == Location::edge || r.summary.location == Location::corner;
  return r;
}

}  // namespace footpoint::surface
