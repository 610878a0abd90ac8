#include "parametric/solvers/hybrid.hpp"

#include <cmath>

#include "parametric/solvers/first_order.hpp"
#include "parametric/solvers/newton.hpp"
#include "parametric/solvers/surface_paper_iteration.hpp"

namespace footpoint::surface {

NewtonMapDerivative newton_map_derivative(const Vec3& p, const SurfaceJet3& jet) {
  NewtonMapDerivative out;
  const OrthogonalitySystem sys = orthogonality_system(p, jet);
  const double F0 = sys.det();
  if (F0 == 0.0 || !std::isfinite(F0)) return out;
  // δ = F'^{-1} F, so that G = t - δ
  const double d1 = (sys.J22 * sys.F1 - sys.J12 * sys.F2) / F0;
  const double d2 = (sys.J11 * sys.F2 - sys.J21 * sys.F1) / F0;
  const Vec3 r = p - jet.s;
  // second and third partials of s, indexed by parameter (0 = u, 1 = v)
  const Vec3 s1[2] = {jet.su, jet.sv};
  const Vec3 s2[2][2] = {{jet.suu, jet.suv}, {jet.suv, jet.svv}};
  auto s3 = [&](int i, int j, int k) -> const Vec3& {
    switch (i + j + k) {
      case 0:
        return jet.suuu;
      case 1:
        return jet.suuv;
      case 2:
        return jet.suvv;
      default:
        return jet.svvv;
    }
  };
  for (int k = 0; k < 2; ++k) {
    // ∂F'_ij/∂t_k = -<s_k, s_ij> + <p - s, s_ijk> - <s_ik, s_j> - <s_i, s_jk>
    double dJ[2][2];
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j)
        dJ[i][j] = -dot(s1[k], s2[i][j]) + dot(r, s3(i, j, k)) - dot(s2[i][k], s1[j]) - dot(s1[i], s2[j][k]);
    const double w1 = dJ[0][0] * d1 + dJ[0][1] * d2;
    const double w2 = dJ[1][0] * d1 + dJ[1][1] * d2;
    out.d[0][k] = (sys.J22 * w1 - sys.J12 * w2) / F0;
    out.d[1][k] = (sys.J11 * w2 - sys.J21 * w1) / F0;
  }
  out.ok = std::isfinite(out.d[0][0]) && std::isfinite(out.d[0][1]) && std::isfinite(out.d[1][0]) &&
           std::isfinite(out.d[1][1]);
  return out;
}

bool newton_map_contracts(const NewtonMapDerivative& dG) {
  if (!dG.ok) return false;
  for (const auto& row : dG.d)
    for (double x : row)
      if (!(std::abs(x) < 0.5)) return false;
  return true;
}

namespace {
// Algorithm 1: Step 2 (a first-order step) comes first; from then on, Step 4 tests the new
// iterate and either switches to Newton for good or goes back to Step 2.
class Hybrid {
 public:
  // In the first-order phase every new iterate is tested: its jet comes with third partials.
  bool needs_third() const { return started_ && !newton_; }
  PaperStep step(const Vec3& p, double, double, const SurfaceJet3& jet) {
    if (!newton_ && started_ && newton_map_contracts(newton_map_derivative(p, jet))) newton_ = true;
    started_ = true;
    return newton_ ? newton_step(p, jet) : first_order_step(p, jet);
  }

 private:
  bool started_ = false;
  bool newton_ = false;
};
}  // namespace

ProjectionResult project_hybrid(const SurfaceFormulas& formulas, const ParamBox& box, const Vec3& p,
                                const Options& options) {
  Hybrid method;
  return run_paper_iteration("hybrid", method, formulas, box, p, options);
}

}  // namespace footpoint::surface
