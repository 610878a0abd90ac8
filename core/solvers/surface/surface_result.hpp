// Filling a ProjectionResult for a surface: foot point, parameters, distance, orthogonality
// residuals and where the parameters lie in the domain.
#pragma once
#include "geometry/parametric_surface.hpp"
#include "geometry/projection_result.hpp"

namespace footpoint::surface {

// interior / edge / corner from exact comparisons with the bounds (the bound-constrained solver
// puts active parameters exactly on their bound); unknown outside the domain.
Location location_in(const ParamBox& box, double u, double v);

// A result at parameters (u, v) with surface point s and tangents su, sv there. The summary gets
// method, orthogonality, location and on_boundary; status, iterations and step_norm are the
// caller's. Non-finite residuals are reported as the largest double, never NaN.
ProjectionResult surface_result(const char* method, const Vec3& p, double u, double v, const Vec3& s,
                                const Vec3& su, const Vec3& sv, const ParamBox& box);

}  // namespace footpoint::surface
