#include "solvers/surface/surface_result.hpp"

#include <cmath>
#include <limits>

#include "solvers/surface/surface_convergence.hpp"

namespace footpoint::surface {

Location location_in(const ParamBox& box, double u, double v) {
  if (!box.contains(u, v)) return Location::unknown;
  const bool u_edge = u == box.umin || u == box.umax;
  const bool v_edge = v == box.vmin || v == box.vmax;
  if (u_edge && v_edge) return Location::corner;
  if (u_edge || v_edge) return Location::edge;
  return Location::interior;
}

ProjectionResult surface_result(const char* method, const Vec3& p, double u, double v, const Vec3& s,
                                const Vec3& su, const Vec3& sv, const ParamBox& box) {
  ProjectionResult r;
  r.dim = 3;
  r.num_params = 2;
  r.params = {u, v};
  r.foot = {s.x, s.y, s.z};
  r.distance = norm(p - s);
  r.summary.method = method;
  const Orthogonality o = orthogonality(p, s, su, sv);
  for (int i = 0; i < 2; ++i)
    r.summary.orthogonality[i] =
        std::isfinite(o.relative[i]) ? o.relative[i] : std::numeric_limits<double>::max();
  r.summary.location = location_in(box, u, v);
  r.summary.on_boundary = r.summary.location == Location::edge || r.summary.location == Location::corner;
  return r;
}

}  // namespace footpoint::surface
