#include "geometry/self_covering.hpp"

#include <algorithm>
#include <cmath>

namespace footpoint {

bool SelfCovering::covered(const ParamBox& box, double u0, double u1, double v0, double v1) const {
  const double size =
      std::max({std::abs(box.umin), std::abs(box.umax), std::abs(box.vmin), std::abs(box.vmax)});
  for (const auto& d : translations) {
    const double margin = 1e-12 * (std::hypot(d[0], d[1]) + size);
    if (u0 - d[0] >= box.umin + margin && u1 - d[0] <= box.umax - margin && v0 - d[1] >= box.vmin + margin &&
        v1 - d[1] <= box.vmax - margin)
      return true;
  }
  return false;
}

SelfCovering detect_self_covering(const SurfaceFormulas& formulas, const ParamBox& box) {
  SelfCovering c;
  for (const auto& d :
       formulas.program().invariant_translations({box.umax - box.umin, box.vmax - box.vmin}, 64))
    c.translations.push_back({d[0], d[1]});
  return c;
}

}  // namespace footpoint
