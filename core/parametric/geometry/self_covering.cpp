#include "parametric/geometry/self_covering.hpp"

#include <algorithm>
#include <cmath>

namespace footpoint {

namespace {
double box_size(const ParamBox& box) {
  return std::max({std::abs(box.umin), std::abs(box.umax), std::abs(box.vmin), std::abs(box.vmax)});
}
}  // namespace

bool SelfCovering::covered(const ParamBox& box, double u0, double u1, double v0, double v1) const {
  const double size = box_size(box);
  for (const auto& d : translations) {
    const double margin = 1e-12 * (std::hypot(d[0], d[1]) + size);
    if (u0 - d[0] >= box.umin + margin && u1 - d[0] <= box.umax - margin && v0 - d[1] >= box.vmin + margin &&
        v1 - d[1] <= box.vmax - margin)
      return true;
  }
  return false;
}

std::vector<Params<2>> SelfCovering::copies(const ParamBox& box, const std::vector<Params<2>>& seeds,
                                            std::size_t cap, bool* truncated) const {
  *truncated = false;
  std::vector<Params<2>> out;
  const auto known = [&](const Params<2>& t) {
    const double tol = 1e-9 * (1.0 + std::hypot(t[0], t[1]));
    return std::any_of(out.begin(), out.end(), [&](const Params<2>& c) {
      return std::abs(c[0] - t[0]) <= tol && std::abs(c[1] - t[1]) <= tol;
    });
  };
  const auto add = [&](const Params<2>& t) {
    if (known(t)) return true;
    if (out.size() == cap) {
      *truncated = true;
      return false;
    }
    out.push_back(t);
    return true;
  };
  for (const auto& t : seeds)
    if (!add(t)) break;
  const double size = box_size(box);
  // Breadth first over the steps ±δ: out grows while it is walked.
  for (std::size_t i = 0; i < out.size() && !*truncated; ++i) {
    for (const auto& d : translations) {
      const double margin = 1e-12 * (std::hypot(d[0], d[1]) + size);
      for (const double sign : {1.0, -1.0}) {
        Params<2> t{out[i][0] + sign * d[0], out[i][1] + sign * d[1]};
        if (t[0] < box.umin - margin || t[0] > box.umax + margin || t[1] < box.vmin - margin ||
            t[1] > box.vmax + margin)
          continue;
        t = {std::clamp(t[0], box.umin, box.umax), std::clamp(t[1], box.vmin, box.vmax)};
        if (!add(t)) break;
      }
      if (*truncated) break;
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

SelfCovering detect_self_covering(const SurfaceFormulas& formulas, const ParamBox& box) {
  SelfCovering c;
  for (const auto& d :
       formulas.program().invariant_translations({box.umax - box.umin, box.vmax - box.vmin}, 64))
    c.translations.push_back({d[0], d[1]});
  return c;
}

}  // namespace footpoint
