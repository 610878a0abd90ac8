// Filling a ProjectionResult for a surface: foot point, parameters, distance, orthogonality
// residuals and where the parameters lie in the domain.
#pragma once
#include <array>

#include "parametric/geometry/parametric_surface.hpp"
#include "parametric/geometry/params.hpp"
#include "parametric/geometry/surface_closure.hpp"
#include "projection/projection_result.hpp"

namespace footpoint::surface {

// Where (u, v) lies, from exact comparisons with the bounds (the bound-constrained solver puts
// active parameters exactly on their bound): pole (on an edge that is one point), corner, edge or
// interior; a bound of a closed direction (a seam) is no edge. Unknown outside the domain.
Location location_in(const ParamBox& box, double u, double v, const SurfaceClosure* closure = nullptr);

// The parameters a seam's two sides name once: along a periodic direction (closure.periodic) the
// upper bound is the lower one, s(umax, v) = s(umin, v), and answers report the lower. A reversed
// seam (a Möbius band's) and every other parameter are kept.
Params<2> seam_representative(const ParamBox& box, double u, double v, const SurfaceClosure* closure);

// A result at parameters (u, v) with surface point s and tangents su, sv there. The summary gets
// method, orthogonality, location and on_boundary; status, iterations and step_norm are the
// caller's. The residuals are those of the Karush-Kuhn-Tucker conditions of min |p - s|^2 over the
// box, relative as |<p - s, s_i>| / (|p - s| |s_i|): for a parameter inside its range (or on a
// seam) the orthogonality itself; for one on a bound only its sign violation - at u = umin the
// admissible direction is +u, and a minimum needs <p - s, s_u> <= 0 (moving inwards does not come
// nearer), at umax >= 0 - so that a boundary answer's residual is 0 when it is right, as an
// interior one's. Non-finite residuals are reported as the largest double, never NaN. The
// parameters reported are seam_representative(u, v).
ProjectionResult surface_result(const char* method, const Vec3& p, double u, double v, const Vec3& s,
                                const Vec3& su, const Vec3& sv, const ParamBox& box,
                                const SurfaceClosure* closure = nullptr);

}  // namespace footpoint::surface
