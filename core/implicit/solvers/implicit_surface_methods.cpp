#include "implicit/solvers/implicit_surface_methods.hpp"

#include <cmath>
#include <vector>

#include "implicit/seeding/implicit_surface_cells.hpp"
#include "implicit/solvers/implicit_surface_lagrange.hpp"
#include "solvers/iteration_control.hpp"

namespace footpoint::surface_implicit {

namespace {

// Newton's budget and the first-order iteration's (a linear rate of 0.9 needs ~350 steps to 1e-16).
constexpr int kNewtonIterations = 100;
constexpr int kFirstOrderIterations = 2000;
constexpr double kDivergence = 1e12;

Vec3 start_of(Vec3 p, const Options& options) {
  if (!options.initial) return p;
  const auto& s = *options.initial;
  return {s[0], s[1], s[2]};
}

// The verdict on a local method's end point x: converged only where the foot-point conditions hold.
ProjectionResult finish(const ImplicitSurfaceEquation& equation, const Box3& box, Vec3 p, Vec3 x,
                        const char* method, Status status, int iterations, double step,
                        const curve::IterationControl& control, std::vector<std::array<double, 3>> trace) {
  ProjectionResult r;
  if (!is_finite(x)) {
    r.summary.method = method;
    r.summary.status = Status::non_finite;
    r.dim = 3;
    r.num_params = 0;
  } else {
    r = implicit_surface_result(equation, box, p, x, method);
    const double tolerance = control.residual_tolerance;
    const bool met = r.summary.equation_residual[0] <= tolerance * std::max(1.0, norm(x)) &&
                     r.summary.orthogonality[0] <= std::sqrt(tolerance);
    if (status == Status::converged && !met) status = Status::degenerate;
    if (status == Status::converged && !box.contains(x)) status = Status::outside_domain;
    r.summary.status = curve::within_max_distance(status, r.distance, control);
  }
  r.summary.iterations = iterations;
  r.summary.step_norm = step;
  r.trace = std::move(trace);
  if (r.summary.status == Status::beyond_max_distance) withhold_answer(r);
  return r;
}

}  // namespace

ProjectionResult lagrange_newton_method(const ImplicitSurfaceEquation& equation, const Box3& box, Vec3 p,
                                        const Options& options) {
  std::vector<std::array<double, 3>> trace;
  const curve::IterationControl control = curve::make_control(options, kNewtonIterations, &trace);
  const Vec3 x0 = start_of(p, options);
  const SurfaceMinimum m = lagrange_newton_interior(equation, p, x0, curve::kInfinity, control);
  Status status = m.converged                              ? Status::converged
                  : !is_finite(m.x)                        ? Status::non_finite
                  : m.iterations >= control.max_iterations ? Status::max_iterations
                                                           : Status::degenerate;
  return finish(equation, box, p, m.x, "lagrange_newton", status, m.iterations, m.step, control,
                std::move(trace));
}

namespace {

// The loop both surface-point iterations share: from y0 landed on the surface, x <- next(x, jet),
// each next point landed on the surface too, until the surface points stop moving.
// `next(x, j, out)` gives the next start from the surface point x with its jet j, false (with
// out.status set) where the step is undefined.
template <class Next>
HartmannEnd surface_point_iteration(const ImplicitSurfaceEquation& equation, Vec3 y0,
                                    const curve::IterationControl& control, Next&& next_start) {
  HartmannEnd out;
  out.x = y0;
  const double limit = kDivergence * std::max(1.0, norm(y0));
  // The landing on the surface: Newton along the gradient until it settles.
  auto land = [&](Vec3& x) { return land_on_surface(equation, x, 100); };
  if (!land(out.x)) {
    out.status = is_finite(out.x) ? Status::degenerate : Status::non_finite;
    return out;
  }
  double previous = curve::kInfinity;
  for (; out.iterations < control.max_iterations; ++out.iterations) {
    const ImplicitSurfaceJet j = equation.jet(out.x);
    Vec3 next;
    if (!next_start(out.x, j, next, out)) return out;
    if (!land(next)) {
      out.status = is_finite(next) ? Status::degenerate : Status::non_finite;
      return out;
    }
    const Vec3 dy = next - out.x;
    out.x = next;
    out.step = norm(dy);
    control.record(dy.x, dy.y, dy.z);
    if (norm(out.x) > limit) {
      out.status = Status::diverged;
      return out;
    }
    if (control.stop(out.step, norm(out.x), previous)) {
      ++out.iterations;
      out.status = Status::converged;
      return out;
    }
  }
  out.status = Status::max_iterations;
  return out;
}

}  // namespace

HartmannEnd hartmann_iteration(const ImplicitSurfaceEquation& equation, Vec3 p, Vec3 y0,
                               const curve::IterationControl& control) {
  return surface_point_iteration(equation, y0, control,
                                 [&](Vec3 x, const ImplicitSurfaceJet& j, Vec3& next, HartmannEnd& out) {
                                   const double g2 = norm2(j.grad);
                                   if (!(g2 > 0.0)) {
                                     out.status = Status::degenerate;
                                     return false;
                                   }
                                   // The foot of p on the tangent plane.
                                   next = p - (dot(p - x, j.grad) / g2) * j.grad;
                                   return true;
                                 });
}

bool curvature_circle_foot(const ImplicitSurfaceJet& j, Vec3 x, Vec3 p, Vec3& q) {
  const double g = norm(j.grad);
  if (!(g > 0.0)) return false;
  const Vec3 n = j.grad / g;
  const Vec3 r = p - x;
  const double rn = dot(r, n);
  const Vec3 tangent = r - rn * n;
  const double tangent_length = norm(tangent);
  if (!(tangent_length > 0.0)) {  // p on the normal line: x is stationary
    q = x;
    return true;
  }
  const Vec3 t = tangent / tangent_length;
  const double kn = -dot(t, j.hess * t) / g;  // step 2: the normal curvature along t
  // Steps 3-4: m = x + n / kn, R = 1 / |kn|, q = m + R (p - m) / |p - m|. With
  // Q = |kn| |p - m| = sqrt(1 - 2 kn <r, n> + kn^2 |r|^2), free of the cancellation of a far m:
  //   q - x = (r + n (kn |r|^2 - 2 <r, n>) / (Q + 1)) / Q   (kn = 0: the tangent-plane foot).
  const double r2 = norm2(r);
  const double Q = std::sqrt(1.0 - 2.0 * kn * rn + kn * kn * r2);
  if (!(Q > 0.0)) return false;  // p is the centre of curvature: every circle point is as near
  q = x + (r + ((kn * r2 - 2.0 * rn) / (Q + 1.0)) * n) / Q;
  return is_finite(q);
}

HartmannEnd hu_wallner_iteration(const ImplicitSurfaceEquation& equation, Vec3 p, Vec3 y0,
                                 const curve::IterationControl& control) {
  return surface_point_iteration(
      equation, y0, control, [&](Vec3 x, const ImplicitSurfaceJet& j, Vec3& next, HartmannEnd& out) {
        if (curvature_circle_foot(j, x, p, next)) return true;
        out.status = is_finite(x) && std::isfinite(j.f) ? Status::degenerate : Status::non_finite;
        return false;
      });
}

namespace {

// A surface-point iteration run as a method of its own: from options.initial, else p.
ProjectionResult surface_point_method(const char* method,
                                      HartmannEnd (*iterate)(const ImplicitSurfaceEquation&, Vec3, Vec3,
                                                             const curve::IterationControl&),
                                      const ImplicitSurfaceEquation& equation, const Box3& box, Vec3 p,
                                      const Options& options) {
  std::vector<std::array<double, 3>> trace;
  const curve::IterationControl control = curve::make_control(options, kFirstOrderIterations, &trace);
  const HartmannEnd end = iterate(equation, p, start_of(p, options), control);
  return finish(equation, box, p, end.x, method, end.status, end.iterations, end.step, control,
                std::move(trace));
}

}  // namespace

ProjectionResult first_order_method(const ImplicitSurfaceEquation& equation, const Box3& box, Vec3 p,
                                    const Options& options) {
  return surface_point_method("first_order", hartmann_iteration, equation, box, p, options);
}

ProjectionResult hu_wallner_method(const ImplicitSurfaceEquation& equation, const Box3& box, Vec3 p,
                                   const Options& options) {
  return surface_point_method("hu_wallner", hu_wallner_iteration, equation, box, p, options);
}

}  // namespace footpoint::surface_implicit
