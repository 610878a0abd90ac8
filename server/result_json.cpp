#include "result_json.hpp"

#include <array>
#include <cmath>
#include <cstddef>
#include <string>

#include "json_writer.hpp"

namespace footpoint::server {

bool has_finite_answer(const ProjectionResult& r) {
  if (!std::isfinite(r.distance)) return false;
  for (int k = 0; k < r.dim; ++k)
    if (!std::isfinite(r.foot[k])) return false;
  for (int k = 0; k < r.num_params; ++k)
    if (!std::isfinite(r.params[k])) return false;
  return true;
}

namespace {

void write_certificate(JsonWriter& o, const Certificate& c, const ProjectionResult& r, bool answer) {
  if (!c.computed) return o.null();
  o.begin_object();
  o.key("certified");
  o.boolean(c.certified);
  o.key("lower_bound");
  o.number(c.lower_bound);
  o.key("gap");
  if (answer)
    o.number(std::fmax(r.distance - c.lower_bound, 0.0));
  else
    o.null();
  o.key("reason");
  o.string(to_string(c.reason));
  o.key("boxes");
  o.integer(c.boxes);
  o.end_object();
}

// How many feet are nearest (null without an answer, or from a method that does not say).
void write_multiplicity(JsonWriter& o, const AnswerMultiplicity& m, const ProjectionResult& r, bool answer) {
  if (!m.computed || !answer) return o.null();
  o.begin_object();
  o.key("kind");
  o.string(to_string(m.kind));
  if (m.kind == Multiplicity::tied) {
    o.key("count");
    o.integer(m.count);
    o.key("feet");
    o.begin_array();
    for (const auto& foot : m.feet) o.numbers(foot.data(), r.dim);
    o.end_array();
  }
  o.end_object();
}

// The member `name` with the numbers x[0..n) when `present`, else null.
void numbers_or_null(JsonWriter& o, JsonName name, bool present, const double* x, int n) {
  o.key(name);
  if (present)
    o.numbers(x, n);
  else
    o.null();
}

// The member `name` with the number x when `present`, else null.
void number_or_null(JsonWriter& o, JsonName name, bool present, double x) {
  o.key(name);
  if (present)
    o.number(x);
  else
    o.null();
}

void write_diagnostics(JsonWriter& o, const ProjectionResult& r, ResultFields f, bool answer, Status status) {
  const Summary& s = r.summary;
  o.begin_object();
  if (f.has(ResultFields::method)) {
    o.key("method");
    o.string(s.method);
  }
  if (f.has(ResultFields::status)) {
    o.key("status");
    o.string(to_string(status));
  }
  if (f.has(ResultFields::converged)) {
    o.key("converged");
    o.boolean(status == Status::converged);
  }
  if (f.has(ResultFields::iterations)) {
    o.key("iterations");
    o.integer(s.iterations);
  }
  // The residuals and the last step describe the foot point: null without one.
  if (f.has(ResultFields::residual)) number_or_null(o, "residual", answer, s.residual());
  if (f.has(ResultFields::step_norm)) number_or_null(o, "step_norm", answer, s.step_norm);
  if (f.has(ResultFields::starts)) {
    o.key("starts");
    o.integer(s.starts);
  }
  if (f.has(ResultFields::location)) {
    o.key("location");
    o.string(to_string(answer ? s.location : Location::unknown));
  }
  if (f.has(ResultFields::certificate)) {
    o.key("certificate");
    write_certificate(o, s.certificate, r, answer);
  }
  if (f.has(ResultFields::multiplicity)) {
    o.key("multiplicity");
    write_multiplicity(o, s.multiplicity, r, answer);
  }
  o.end_object();
}

void write_minima(JsonWriter& o, const ProjectionResult& r) {
  o.begin_array();
  for (const Minimum& mn : r.minima) {
    o.begin_object();
    o.key("foot_point");
    o.numbers(mn.foot.data(), r.dim);
    if (r.num_params > 0) {
      o.key("parameters");
      o.numbers(mn.params.data(), r.num_params);
    }
    o.key("distance");
    o.number(mn.distance);
    o.key("location");
    o.string(to_string(mn.location));
    if (!mn.copies.empty()) {
      o.key("parameter_copies");
      o.begin_array();
      for (const auto& copy : mn.copies) o.numbers(copy.data(), 2);
      o.end_array();
      o.key("copies_truncated");
      o.boolean(mn.copies_truncated);
    }
    o.end_object();
  }
  o.end_array();
}

// Writes one result with the members `f` selects; returns its reported status.
Status write_result(JsonWriter& o, const ProjectionResult& r, ResultFields f) {
  const bool answer = has_finite_answer(r);
  const Status status = reported_status(r);
  o.begin_object();
  if (f.has(ResultFields::foot_point)) numbers_or_null(o, "foot_point", answer, r.foot.data(), r.dim);
  if (r.num_params > 0 && f.has(ResultFields::parameters))
    numbers_or_null(o, "parameters", answer, r.params.data(), r.num_params);
  if (f.has(ResultFields::distance)) number_or_null(o, "distance", answer, r.distance);
  if (f.has(ResultFields::normal))
    numbers_or_null(o, "normal", answer && r.has_normal(), r.normal.data(), r.dim);
  if (f.has(ResultFields::signed_distance))
    number_or_null(o, "signed_distance", answer && r.has_normal(), r.signed_distance);
  if (f.has(ResultFields::kDiagnostics)) {
    o.key("diagnostics");
    write_diagnostics(o, r, f, answer, status);
  }
  if (f.has(ResultFields::minima)) {
    o.key("minima");
    write_minima(o, r);
    o.key("minima_truncated");
    o.boolean(r.minima_truncated);
  }
  if (f.has(ResultFields::trace)) {
    o.key("trace");
    o.begin_array();
    for (const auto& step : r.trace) o.numbers(step.data(), 3);
    o.end_array();
  }
  o.end_object();
  return status;
}

// Field names and the members they select, in the order of a result.
struct FieldName {
  std::string_view name;
  std::uint32_t members;
};
constexpr FieldName kFieldNames[] = {
    {"foot_point", ResultFields::foot_point},
    {"parameters", ResultFields::parameters},
    {"distance", ResultFields::distance},
    {"normal", ResultFields::normal},
    {"signed_distance", ResultFields::signed_distance},
    {"diagnostics", ResultFields::kDiagnostics},
    {"diagnostics.method", ResultFields::method},
    {"diagnostics.status", ResultFields::status},
    {"diagnostics.converged", ResultFields::converged},
    {"diagnostics.iterations", ResultFields::iterations},
    {"diagnostics.residual", ResultFields::residual},
    {"diagnostics.step_norm", ResultFields::step_norm},
    {"diagnostics.starts", ResultFields::starts},
    {"diagnostics.location", ResultFields::location},
    {"diagnostics.certificate", ResultFields::certificate},
    {"diagnostics.multiplicity", ResultFields::multiplicity},
    {"minima", ResultFields::minima},
    {"trace", ResultFields::trace},
};

}  // namespace

Status reported_status(const ProjectionResult& r) {
  if (r.summary.status == Status::converged && !has_finite_answer(r)) return Status::non_finite;
  return r.summary.status;
}

std::uint32_t ResultFields::parse(std::string_view name) {
  for (const auto& f : kFieldNames)
    if (f.name == name) return f.members;
  return 0;
}

const char* ResultFields::names() {
  static const std::string text = [] {
    std::string s;
    for (const auto& f : kFieldNames) (s += s.empty() ? "" : ", ") += f.name;
    return s;
  }();
  return text.c_str();
}

Status append_result(std::string& out, const ProjectionResult& r, ResultFields fields) {
  JsonWriter o(out);
  return write_result(o, r, fields);
}

namespace {

void write_stats(JsonWriter& o, const BatchStats& stats, const DeviationOptions& options) {
  o.begin_object();
  o.key("points");
  o.integer(static_cast<long long>(stats.points));
  o.key("converged");
  o.integer(static_cast<long long>(stats.by_status[static_cast<std::size_t>(Status::converged)]));
  o.key("statuses");
  o.begin_object();
  for (std::size_t k = 0; k < stats.by_status.size(); ++k) {
    if (stats.by_status[k] == 0) continue;
    o.key(to_string(static_cast<Status>(k)));
    o.integer(static_cast<long long>(stats.by_status[k]));
  }
  o.end_object();
  o.key("elapsed_ms");
  o.number(stats.elapsed_ms);
  const DeviationStats& d = stats.deviation;
  o.key("deviation");
  o.begin_object();
  o.key("count");
  o.integer(static_cast<long long>(d.count));
  o.key("signed");
  o.integer(static_cast<long long>(d.signed_count));
  const bool any = d.count > 0;
  number_or_null(o, "min", any, d.min);
  number_or_null(o, "max", any, d.max);
  number_or_null(o, "mean", any, d.mean);
  number_or_null(o, "rms", any, d.rms);
  o.key("histogram");
  if (any) {
    o.begin_object();
    o.key("edges");
    o.numbers(d.edges.data(), static_cast<int>(d.edges.size()));
    o.key("counts");
    o.begin_array();
    for (const std::size_t count : d.counts) o.integer(static_cast<long long>(count));
    o.end_array();
    o.key("resolution");
    o.number(d.histogram_resolution);
    o.end_object();
  } else {
    o.null();
  }
  if (options.tolerance_band) {
    o.key("tolerance_band");
    o.begin_object();
    o.key("lo");
    o.number((*options.tolerance_band)[0]);
    o.key("hi");
    o.number((*options.tolerance_band)[1]);
    o.key("within");
    o.integer(static_cast<long long>(d.within_band));
    number_or_null(o, "share", any,
                   any ? static_cast<double>(d.within_band) / static_cast<double>(d.count) : 0.0);
    o.end_object();
  }
  o.end_object();
  o.end_object();
}

}  // namespace

void append_stats(std::string& out, const BatchStats& stats, const DeviationOptions& options) {
  JsonWriter o(out);
  write_stats(o, stats, options);
}

std::string project_response(const std::string& geometry_id, const std::vector<ProjectionResult>& results,
                             bool single, ResultFields fields, double elapsed_ms,
                             const DeviationOptions& deviation) {
  // ~400 bytes per plain result; more with minima or trace, less when trimmed.
  std::string out;
  out.reserve(512 + results.size() * (fields.has(ResultFields::minima | ResultFields::trace) ? 1024 : 400));
  BatchStats stats;
  stats.points = results.size();
  stats.elapsed_ms = elapsed_ms;
  stats.deviation = deviation_stats(results, deviation);
  {
    JsonWriter o(out);
    o.begin_object();
    o.key("geometry_id");
    o.string(geometry_id);
    o.key(single ? "result" : "results");
    if (!single) o.begin_array();
    for (const ProjectionResult& r : results)
      ++stats.by_status[static_cast<std::size_t>(write_result(o, r, fields))];
    if (!single) o.end_array();
    o.key("stats");
    write_stats(o, stats, deviation);
    o.end_object();
  }
  return out;
}

}  // namespace footpoint::server
