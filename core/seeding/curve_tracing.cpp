#include "seeding/curve_tracing.hpp"

#include <cmath>

#include "geometry/compile_budget.hpp"
#include "geometry/curve_correction.hpp"
#include "geometry/implicit_curve_differentials.hpp"
#include "geometry/singular_point.hpp"

namespace footpoint {

bool SampleGrid::near(const std::vector<Vec3>& points, Vec3 x, double radius) const {
  const double r2 = radius * radius;
  return any_nearby(x, [&](std::int32_t i) { return norm2(points[static_cast<std::size_t>(i)] - x) <= r2; });
}

std::int32_t SampleGrid::nearest_end(const CurveSamples& samples, Vec3 x, double radius,
                                     std::int32_t below) const {
  double best = radius * radius;
  std::int32_t found = -1;
  any_nearby(x, [&](std::int32_t i) {
    const auto k = static_cast<std::size_t>(i);
    if (i >= below || samples.kind[k] != SampleKind::regular ||
        (samples.prev[k] >= 0 && samples.next[k] >= 0))
      return false;
    const double d2 = norm2(samples.points[k] - x);
    if (d2 <= best) best = d2, found = i;
    return false;
  });
  return found;
}

namespace {

double sine_between_normals(const ImplicitJet& j) {
  const double d = norm(j.grad[0]) * norm(j.grad[1]);
  return d > 0.0 ? norm(j.tangent()) / d : 0.0;
}

double angle_between(Vec3 a, Vec3 b) {  // both non-zero
  return std::atan2(norm(cross(a, b)), dot(a, b));
}

bool already_found(const std::vector<Vec3>& found, Vec3 s, double tolerance) {
  for (const Vec3& f : found)
    if (norm(f - s) <= tolerance) return true;
  return false;
}

}  // namespace

TraceOutcome trace_curve(const ImplicitEquations& equations, const Box3& box, Vec3 start, Vec3 direction,
                         Vec3 close_on, const TraceSettings& settings, const SampleGrid& existing,
                         const CurveSamples& samples, std::int32_t own_first) {
  TraceOutcome out;
  Vec3 x = start;
  Vec3 t = direction / norm(direction);
  double h = settings.max_step;
  const double join_radius = 0.5 * settings.max_step;
  const double same_point = 1e-9 * std::max(1.0, norm(start));
  double largest_tangent = norm(equations.jet(start).tangent());
  while (out.points.size() < settings.max_points) {
    CompileBudget::check();
    if (h < settings.min_step) {
      // Stalled: most likely at a singular point (T -> 0 makes the corrector fail).
      Vec3 s = x;
      if (curve::refine_singular_point(equations, s) && norm(s - x) <= 4.0 * settings.max_step) {
        out.end = TraceEnd::singular_point;
        out.end_point = s;
      } else {
        out.end = TraceEnd::stalled;
      }
      return out;
    }
    const Vec3 y = x + h * t;
    Vec3 z;
    int iterations = 0;
    if (!curve::correct_in_normal_plane(equations, y, t, z, iterations)) {
      h *= 0.5;
      continue;
    }
    const ImplicitJet jz = equations.jet(z);
    Vec3 tz = curve::unit_tangent(jz);
    const Vec3 chord = z - x;
    const double chord_length = norm(chord);
    if (norm2(tz) == 0.0 || chord_length == 0.0) {
      h *= 0.5;
      continue;
    }
    if (dot(tz, t) < 0.0) tz = -tz;  // orient by continuity (T flips sign through a crossing)
    const double turn = angle_between(t, tz);
    if (turn > settings.max_turn || angle_between(t, chord) > settings.max_turn || chord_length > 1.5 * h) {
      h *= 0.5;
      continue;
    }
    // Closing the loop: close_on lies ahead within this step.
    const Vec3 to_close = close_on - x;
    if (!(out.points.empty() && norm(close_on - start) <= same_point) &&
        norm(to_close) <= 1.05 * chord_length && norm(to_close) > 0.0 &&
        angle_between(t, to_close) <= settings.max_turn) {
      out.end = TraceEnd::closed;
      return out;
    }
    if (!box.contains(z)) {
      Vec3 f;
      if (curve::locate_face_crossing(equations, box, x, z, f)) {
        out.end = TraceEnd::box_face;
        out.end_point = f;
      } else {
        out.end = TraceEnd::stalled;
      }
      return out;
    }
    out.points.push_back(z);
    out.joined_to = existing.nearest_end(samples, z, join_radius, own_first);
    if (out.joined_to >= 0) {
      out.end = TraceEnd::joined;
      return out;
    }
    x = z;
    t = tz;
    // Near a singular point T = grad f1 x grad f2 shrinks: in angle between the normals, or (for
    // planar curves, grad f2 = e_z, where the angle says nothing) in length against the largest
    // |T| met on this walk. Record the point; the walk usually goes on along the same branch.
    const double tangent_length = norm(jz.tangent());
    largest_tangent = std::max(largest_tangent, tangent_length);
    if (sine_between_normals(jz) < settings.singular_sine ||
        tangent_length < settings.singular_sine * largest_tangent) {
      Vec3 s = x;
      if (curve::refine_singular_point(equations, s) && norm(s - x) <= 2.0 * settings.max_step &&
          !already_found(out.singular_points, s, 1e-6 * std::max(1.0, norm(s))))
        out.singular_points.push_back(s);
    }
    if (iterations <= 3 && turn <= 0.5 * settings.max_turn) h = std::min(settings.max_step, 1.5 * h);
  }
  out.end = TraceEnd::budget;
  return out;
}

}  // namespace footpoint
