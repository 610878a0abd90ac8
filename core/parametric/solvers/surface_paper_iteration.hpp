// The loop shared by the papers' methods (gsa, first_order, hybrid, newton): from a start t0
// (options.initial, else the domain's centre) repeat t <- t + Δt(t), exactly as published, with
// no clamping to the domain ([GSA] Algorithm 1 Steps 2-3; [Hybrid] Algorithm 1), until the
// increment and the orthogonality residuals meet the tolerance (surface_convergence.hpp).
// A converged result outside the domain gets status outside_domain. With options.trace every
// applied increment (Δu, Δv, 0) is recorded, which is what the papers' tables print.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "parametric/geometry/parametric_surface.hpp"
#include "parametric/solvers/surface_convergence.hpp"
#include "parametric/solvers/surface_result.hpp"
#include "projection/projection_result.hpp"

namespace footpoint::surface {

// What one iteration of a method returns: the increment, or why there is none.
struct PaperStep {
  double du = 0.0;
  double dv = 0.0;
  Status failure = Status::converged;  // degenerate / non_finite stop the iteration
};

// Budget of the papers' methods (first-order ones need a few hundred steps at 1e-15).
inline constexpr int kPaperMaxIterations = 1000;
// |t|∞ beyond this many parameter scales counts as divergence.
inline constexpr double kDivergenceScales = 1e8;

// Method provides `PaperStep step(const Vec3& p, double u, double v, const SurfaceJet3& jet)`
// (or takes a SurfaceJet); it may keep state between calls (the hybrid method's phase). A method
// that also provides `bool needs_third() const` gets the third partials of the next iterate when
// it asks for them (one jet3 evaluation instead of a jet and a jet3); otherwise they are unset.
template <class Method>
ProjectionResult run_paper_iteration(const char* name, Method& method, const SurfaceFormulas& formulas,
                                     const ParamBox& box, const Vec3& p, const Options& options) {
  const ConvergenceCriteria crit = convergence_criteria(options, box, kPaperMaxIterations);
  double u = options.initial ? (*options.initial)[0] : 0.5 * (box.umin + box.umax);
  double v = options.initial ? (*options.initial)[1] : 0.5 * (box.vmin + box.vmax);
  const double divergence = kDivergenceScales * crit.scale;
  const double norm_p = norm(p);
  ConvergenceTest test(crit);
  std::vector<std::array<double, 3>> trace;

  auto evaluate = [&](double at_u, double at_v, SurfaceJet3& out) {
    if constexpr (requires { method.needs_third(); }) {
      if (method.needs_third()) {
        out = formulas.jet3(at_u, at_v);
        return;
      }
    }
    static_cast<SurfaceJet&>(out) = formulas.jet(at_u, at_v);
  };
  SurfaceJet3 jet, next;
  evaluate(u, v, jet);
  Status status = Status::max_iterations;
  int iterations = 0;
  double last_du = 0.0, last_dv = 0.0;  // the norm is taken once, at the end
  if (!is_finite(jet)) status = Status::non_finite;
  while (status == Status::max_iterations && iterations < crit.max_iterations) {
    const PaperStep step = method.step(p, u, v, jet);
    if (step.failure != Status::converged) {
      status = step.failure;
      break;
    }
    if (!std::isfinite(step.du) || !std::isfinite(step.dv)) {
      status = Status::non_finite;
      break;
    }
    const double un = u + step.du, vn = v + step.dv;
    evaluate(un, vn, next);
    if (!is_finite(next)) {
      status = Status::non_finite;
      break;
    }
    ++iterations;
    if (options.trace) trace.push_back({step.du, step.dv, 0.0});
    u = un;
    v = vn;
    jet = next;
    last_du = step.du;
    last_dv = step.dv;
    const double step_inf = std::max(std::abs(step.du), std::abs(step.dv));
    if (test.converged(step_inf, u, v, orthogonality(p, norm_p, jet.s, jet.su, jet.sv))) {
      status = Status::converged;
    } else if (std::max(std::abs(u), std::abs(v)) > divergence) {
      status = Status::diverged;
    }
  }
  if (status == Status::converged && !box.contains(u, v)) status = Status::outside_domain;

  ProjectionResult r = surface_result(name, p, u, v, jet.s, jet.su, jet.sv, box);
  r.summary.status = status;
  r.summary.iterations = iterations;
  r.summary.step_norm = std::hypot(last_du, last_dv);
  r.summary.starts = 1;
  r.trace = std::move(trace);
  return r;
}

}  // namespace footpoint::surface
