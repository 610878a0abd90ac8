// `auto` against an independent brute-force reference on random points: the global minimum of
// |p - s(u, v)| found by a dense parameter grid (every grid point whose distance is a local
// minimum among its 8 neighbours, within a few grid steps of the grid's best, starts a local
// projected Newton solve) - a different search from `auto`'s cell tree, so a rule of its that
// prunes a basin it should not (parametric/seeding/surface_cells.hpp, parametric/solvers/surface_auto.hpp)
// shows as `auto` farther than the reference. On the Open CASCADE comparison's S1, S2, S3, a
// torus, A1 ([GSA] Example 1 folded over [-25,25]^2), two sheets folded along curves
// and six more shapes, with points uniform in the box
// twice the surface's size and points within 2% of its size from a random surface point. Every
// answer's certificate holds against the reference (its lower bound is never above it), and 99 %
// of them are certified (95 % on a surface with a kink).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <iomanip>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "parametric/solvers/projected_newton.hpp"
#include "parametric/solvers/surface_convergence.hpp"
#include "surface_fixtures.hpp"

using namespace footpoint;
using namespace footpoint::test;

namespace {

struct Spec {
  const char* name;
  std::array<double, 2> u, v;
  const char *x, *y, *z;
};

constexpr int kGrid = 240;  // grid steps per parameter
// Points per surface and kind (box, near): 150, or FOOTPOINT_STRESS_POINTS for a longer sweep
// (e.g. FOOTPOINT_STRESS_POINTS=2000 build/tests/test_surface -tc='*brute-force*': ~40 s).
int points_per_kind() {
  const char* env = std::getenv("FOOTPOINT_STRESS_POINTS");
  const int n = env ? std::atoi(env) : 0;
  return n > 0 ? n : 150;
}
// The points' seed: FOOTPOINT_STRESS_SEED for a sweep of other points.
std::uint64_t stress_seed() {
  const char* env = std::getenv("FOOTPOINT_STRESS_SEED");
  return env ? std::strtoull(env, nullptr, 10) : 20261122;
}

// The reference distance for p: local solves from the grid's local minima.
double brute_force(const ParametricSurface& g, const std::vector<Vec3>& grid, const Vec3& p, double size) {
  const ParamBox box = g.domain();
  const auto criteria = surface::convergence_criteria(Options{}, box, surface::kLocalMaxIterations);
  std::vector<double> d(grid.size());
  double nearest = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < grid.size(); ++i) nearest = std::min(nearest, d[i] = norm(grid[i] - p));
  const auto at = [&](int i, int j) {
    return d[static_cast<std::size_t>(i) * static_cast<std::size_t>(kGrid + 1) + static_cast<std::size_t>(j)];
  };
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i <= kGrid; ++i)
    for (int j = 0; j <= kGrid; ++j) {
      if (at(i, j) > nearest + 3.0 * size / kGrid) continue;
      bool local_minimum = true;
      for (int di = -1; di <= 1 && local_minimum; ++di)
        for (int dj = -1; dj <= 1 && local_minimum; ++dj) {
          const int a = i + di, b = j + dj;
          if ((di || dj) && a >= 0 && a <= kGrid && b >= 0 && b <= kGrid && at(a, b) < at(i, j))
            local_minimum = false;
        }
      if (!local_minimum) continue;
      const double u = box.umin + (box.umax - box.umin) * i / kGrid,
                   v = box.vmin + (box.vmax - box.vmin) * j / kGrid;
      const auto s = surface::projected_newton(g.formulas(), box, p, u, v, criteria);
      if (std::isfinite(s.distance)) best = std::min(best, s.distance);
    }
  return best;
}

}  // namespace

TEST_CASE("auto is never farther than a brute-force grid search on random points") {
  const Spec specs[] = {
      {"S1", {-3, 3}, {-3, 3}, "u+v", "sin(u)+2*cos(v)", "sin(u+v)"},
      {"S2", {-2, 2}, {-2, 2}, "u^4*v^3+u*v+u", "u^3+v^3", "u+v"},
      {"S3",
       {0, 2},
       {0, 2},
       "u^6+u^5*v+v^6-u^2*v^3+u*v^4-v^5+u^4+u^3*v+v^4+u^3-u*v^2+v^3+u*v+v^2+1",
       "u^6+2*u^4*v^2-v^6+u^5+u^2*v^3+v^5+u^4-u*v^3+u^3-2*u*v^2+v^3+4*u*v+2*v^2+2*u+2*v+1",
       "u^6+u*v^5+u^4*v+u^2*v^3+u^3*v+2*u^2*v^2+v^4+u^3+2*u*v+u"},
      {"torus",
       {0, 6.283185307179586},
       {0, 6.283185307179586},
       "(2+0.5*cos(v))*cos(u)",
       "(2+0.5*cos(v))*sin(u)",
       "0.5*sin(v)"},
      {"A1", {-25, 25}, {-25, 25}, "u+v", "sin(u)+2*cos(v)", "sin(u+v)"},
      // a torus over a box of about four periods, not aligned with them: no seam, but 2π-translates
      // (parametric/geometry/self_covering.hpp) that leave an L-shaped strip of cells
      {"torus_covered",
       {-1, 12},
       {0.5, 13.5},
       "(2+0.5*cos(v))*cos(u)",
       "(2+0.5*cos(v))*sin(u)",
       "0.5*sin(v)"},
      // folded sheets (s_u x s_v = 0 along curves; tests/data/surface_fold*.json)
      {"fold", {-4, 4}, {-4, 4}, "u+0.3*sin(4*v)", "v+0.3*cos(3*u)", "0.4*sin(2*u)*cos(3*v)"},
      {"fold_near", {-3, 3}, {-3, 3}, "u+0.5*sin(3*v)", "v+0.5*cos(2*u)", "0.3*sin(3*u)*cos(2*v)"},
      // bumps and ripples a few cells wide, a cone's apex and seam, a sphere's poles, a saddle
      // with ripples, Enneper's surface (it crosses itself)
      {"wavy", {-4, 4}, {-4, 4}, "u", "v", "0.2*sin(7*u)*sin(5*v)"},
      {"ripple", {-1, 1}, {-1, 1}, "u", "v", "0.05*sin(20*u)*sin(17*v)"},
      {"cone", {0, 6.283185307179586}, {0, 1}, "v*cos(u)", "v*sin(u)", "v"},
      {"sphere",
       {0, 6.283185307179586},
       {-1.5707963267948966, 1.5707963267948966},
       "cos(u)*cos(v)",
       "sin(u)*cos(v)",
       "sin(v)"},
      {"saddle", {-2, 2}, {-2, 2}, "u", "v", "u*u*u-3*u*v*v+0.5*sin(4*u*v)"},
      {"enneper", {-2, 2}, {-2, 2}, "u-u^3/3+u*v^2", "v-v^3/3+v*u^2", "u^2-v^2"},
      // a kink along the circle u^2 + v^2 = 1/2 (parametric/solvers/kink_minimum.hpp)
      {"kinked", {-1, 1}, {-1, 1}, "u", "v", "abs(u^2+v^2-0.5)"},
      // a kink along u = v^2, which meets the box at its corners (1, ±1)
      {"kinked_corners", {-1, 1}, {-1, 1}, "u", "v", "abs(u-v^2)"},
  };
  const int points = points_per_kind();
  for (const Spec& spec : specs) {
    SUBCASE(spec.name) {
      const auto g = make_surface(spec.x, spec.y, spec.z, spec.u, spec.v);
      REQUIRE(g);
      const ParamBox box = g->domain();
      std::vector<Vec3> grid;
      Vec3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
      for (int i = 0; i <= kGrid; ++i)
        for (int j = 0; j <= kGrid; ++j) {
          const Vec3 s = g->formulas().point(box.umin + (box.umax - box.umin) * i / kGrid,
                                             box.vmin + (box.vmax - box.vmin) * j / kGrid);
          grid.push_back(s);
          for (int c = 0; c < 3; ++c) lo[c] = std::min(lo[c], s[c]), hi[c] = std::max(hi[c], s[c]);
        }
      const double size = norm(hi - lo);
      std::mt19937_64 rng(stress_seed());
      std::uniform_real_distribution<double> U(0.0, 1.0);
      int farther = 0, certified = 0;
      for (int kind = 0; kind < 2; ++kind)
        for (int k = 0; k < points; ++k) {
          Vec3 p;
          if (kind == 0) {  // the box twice the surface's size
            for (int c = 0; c < 3; ++c) p[c] = 0.5 * (lo[c] + hi[c]) + (U(rng) - 0.5) * 2.0 * (hi[c] - lo[c]);
          } else {  // within 2% of its size from a random surface point
            const Vec3 s = g->formulas().point(box.umin + (box.umax - box.umin) * U(rng),
                                               box.vmin + (box.vmax - box.vmin) * U(rng));
            const Vec3 dir{U(rng) - 0.5, U(rng) - 0.5, U(rng) - 0.5};
            p = s + dir * (0.02 * size * U(rng) / std::max(norm(dir), 1e-9));
          }
          const double reference = brute_force(*g, grid, p, size);
          const ProjectionResult r = project(*g, {p.x, p.y, p.z}, "auto");
          // a relative 1e-9 of the distance, and the rounding of |p - s| for points on the surface
          const double tolerance =
              1e-9 * reference + 64.0 * std::numeric_limits<double>::epsilon() * (norm(p) + size);
          if (!(r.distance <= reference + tolerance)) {
            ++farther;
            const std::string where = std::string(spec.name) + (kind ? " near" : " box");
            MESSAGE(where << std::setprecision(17) << " p = (" << p.x << ", " << p.y << ", " << p.z
                          << "): auto " << r.distance << ", brute force " << reference);
          }
          INFO(std::string(spec.name) << std::setprecision(17) << " p = (" << p.x << ", " << p.y << ", "
                                      << p.z << "): status " << std::string(to_string(r.summary.status)));
          CHECK(r.summary.status == Status::converged);
          check_certificate(r, reference);
          certified += r.summary.certificate.certified;
        }
      CHECK(farther == 0);
      MESSAGE(std::string(spec.name) << ": " << certified << " of " << 2 * points << " answers certified");
      // The share certified within the default budget (parametric/solvers/surface_certificate.hpp);
      // on the kinked surfaces 95 %: a box across its kink has no second-order bound (the formulas
      // are not smooth there), only its interval box, which closes near the kink only when small
      const double share = std::string(spec.name).starts_with("kinked") ? 0.95 : 0.99;
      CHECK(certified >= static_cast<int>(share * 2 * points));
    }
  }
}
