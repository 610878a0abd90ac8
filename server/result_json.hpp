// The JSON form of projection results (see openapi.yaml, ProjectionResult):
//   {"foot_point":[...], "parameters":[u,v] | [t] (absent for implicit curves), "distance":d,
//    "normal":[...] | null, "signed_distance":d | null,
//    "diagnostics":{"method","status","converged","iterations","residual","step_norm","starts",
//                   "location","certificate"}, "minima":[...] (all_minima), "trace":[...] (trace)}
// trimmed to the members the request's "fields" names. Numbers are written in shortest
// round-trip form. A result without a finite answer (e.g. deadline_exceeded, non_finite,
// beyond_max_distance) has null foot_point, parameters, distance, residual, step_norm, certificate
// gap and multiplicity, and location unknown; a result whose status claims convergence with non-finite
// numbers is reported as non_finite, never as converged.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "batch/deviation.hpp"
#include "projection/projection_result.hpp"

namespace footpoint::server {

// The members each result has: a request's "fields" (every member by default). minima and trace
// are computed only when options.all_minima and options.trace ask for them.
struct ResultFields {
  enum Member : std::uint32_t {
    foot_point = 1u << 0,
    parameters = 1u << 1,
    distance = 1u << 2,
    method = 1u << 3,
    status = 1u << 4,
    converged = 1u << 5,
    iterations = 1u << 6,
    residual = 1u << 7,
    step_norm = 1u << 8,
    starts = 1u << 9,
    location = 1u << 10,
    certificate = 1u << 11,
    minima = 1u << 12,
    trace = 1u << 13,
    multiplicity = 1u << 14,
    normal = 1u << 15,
    signed_distance = 1u << 16,
  };
  static constexpr std::uint32_t kDiagnostics = method | status | converged | iterations | residual |
                                                step_norm | starts | location | certificate | multiplicity;
  static constexpr std::uint32_t kAll =
      foot_point | parameters | distance | normal | signed_distance | kDiagnostics | minima | trace;
  // Everything a result has without options.all_minima and options.trace.
  static constexpr std::uint32_t kPlain = kAll & ~(minima | trace);

  std::uint32_t members = kAll;
  bool has(std::uint32_t m) const { return (members & m) != 0; }

  // The members a field name selects: "distance", "diagnostics" (all of it),
  // "diagnostics.status", ...; 0 for a name that is none.
  static std::uint32_t parse(std::string_view name);
  // The names parse() knows, for messages: "foot_point, parameters, ...".
  static const char* names();
};

// Whether r has a finite foot point, parameters and distance (else they are null).
bool has_finite_answer(const ProjectionResult& r);

// The status the response reports for r (see above).
Status reported_status(const ProjectionResult& r);

// Appends one result with the members `fields` selects to `out`; returns its reported status.
Status append_result(std::string& out, const ProjectionResult& r, ResultFields fields);

// What "stats" says of a batch: the points, the converged ones, each status that occurs, the time
// and the deviations.
struct BatchStats {
  std::size_t points = 0;
  std::array<std::size_t, static_cast<std::size_t>(Status::deadline_exceeded) + 1> by_status{};
  double elapsed_ms = 0.0;
  DeviationStats deviation;
};

// Appends the "stats" object: {"points", "converged", "statuses", "elapsed_ms", "deviation":
// {"count", "signed", "min", "max", "mean", "rms", "histogram": {"edges", "counts"},
// "tolerance_band": {"lo", "hi", "within", "share"} (with options.tolerance_band)}}.
void append_stats(std::string& out, const BatchStats& stats, const DeviationOptions& options);

// The whole response body: {"geometry_id", "result" | "results", "stats"}.
std::string project_response(const std::string& geometry_id, const std::vector<ProjectionResult>& results,
                             bool single, ResultFields fields, double elapsed_ms,
                             const DeviationOptions& deviation = {});

}  // namespace footpoint::server
