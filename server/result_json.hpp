// The JSON form of projection results (see openapi.yaml, ProjectionResult):
//   {"foot_point":[...], "parameters":[u,v] | [t] (absent for implicit curves), "distance":d,
//    "diagnostics":{"method","status","converged","iterations","residual","step_norm","starts",
//                   "location"}, "minima":[...] (all_minima), "trace":[...] (trace)}
// Numbers are written in shortest round-trip form. A result without a finite answer (e.g.
// deadline_exceeded, non_finite) has null foot_point, parameters and distance; a result whose
// status claims convergence with non-finite numbers is reported as non_finite, never as converged.
#pragma once
#include <string>
#include <vector>

#include "geometry/projection_result.hpp"

namespace footpoint::server {

// The status the response reports for r (see above).
Status reported_status(const ProjectionResult& r);

// The whole response body: {"geometry_id", "result" | "results", "stats"}.
std::string project_response(const std::string& geometry_id, const std::vector<ProjectionResult>& results,
                             bool single, bool with_minima, bool with_trace, double elapsed_ms);

}  // namespace footpoint::server
