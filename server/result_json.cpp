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

// Method, status and location names are plain identifiers; anything else is escaped.
void name(JsonAppender& o, std::string_view s) {
  for (char c : s)
    if (!((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_')) return o.string(s);
  o.literal("\"");
  o.literal(s);
  o.literal("\"");
}

// The members of an object in their order: each key is written with the comma before it, which
// the first member of the object leaves out.
class Members {
 public:
  explicit Members(JsonAppender& o) : o_(o) {}
  // `key` is the comma, the quoted name and the colon: ",\"distance\":".
  void key(std::string_view key) {
    o_.literal(first_ ? key.substr(1) : key);
    first_ = false;
  }

 private:
  JsonAppender& o_;
  bool first_ = true;
};

void write_certificate(JsonAppender& o, const Certificate& c, const ProjectionResult& r, bool answer) {
  if (!c.computed) return o.literal("null");
  o.literal(c.certified ? "{\"certified\":true,\"lower_bound\":" : "{\"certified\":false,\"lower_bound\":");
  o.number(c.lower_bound);
  o.literal(",\"gap\":");
  if (answer)
    o.number(std::fmax(r.distance - c.lower_bound, 0.0));
  else
    o.literal("null");
  o.literal(",\"reason\":");
  name(o, to_string(c.reason));
  o.literal(",\"boxes\":");
  o.integer(c.boxes);
  o.literal("}");
}

// How many feet are nearest (null without an answer, or from a method that does not say).
void write_multiplicity(JsonAppender& o, const AnswerMultiplicity& m, const ProjectionResult& r,
                        bool answer) {
  if (!m.computed || !answer) {
    o.literal("null");
    return;
  }
  o.literal("{\"kind\":");
  name(o, to_string(m.kind));
  if (m.kind == Multiplicity::tied) {
    o.literal(",\"count\":");
    o.integer(m.count);
    o.literal(",\"feet\":[");
    for (std::size_t i = 0; i < m.feet.size(); ++i) {
      if (i) o.literal(",");
      o.numbers(m.feet[i].data(), r.dim);
    }
    o.literal("]");
  }
  o.literal("}");
}

// Writes one result with the members `f` selects; returns its reported status.
Status write_result(JsonAppender& o, const ProjectionResult& r, ResultFields f) {
  const bool answer = has_finite_answer(r);
  const Status status = reported_status(r);
  o.literal("{");
  Members m(o);
  if (f.has(ResultFields::foot_point)) {
    m.key(",\"foot_point\":");
    if (answer)
      o.numbers(r.foot.data(), r.dim);
    else
      o.literal("null");
  }
  if (r.num_params > 0 && f.has(ResultFields::parameters)) {
    m.key(",\"parameters\":");
    if (answer)
      o.numbers(r.params.data(), r.num_params);
    else
      o.literal("null");
  }
  if (f.has(ResultFields::distance)) {
    m.key(",\"distance\":");
    if (answer)
      o.number(r.distance);
    else
      o.literal("null");
  }
  if (f.has(ResultFields::normal)) {
    m.key(",\"normal\":");
    if (answer && r.has_normal())
      o.numbers(r.normal.data(), r.dim);
    else
      o.literal("null");
  }
  if (f.has(ResultFields::signed_distance)) {
    m.key(",\"signed_distance\":");
    if (answer && r.has_normal())
      o.number(r.signed_distance);
    else
      o.literal("null");
  }
  const Summary& s = r.summary;
  if (f.has(ResultFields::kDiagnostics)) {
    m.key(",\"diagnostics\":{");
    Members d(o);
    if (f.has(ResultFields::method)) {
      d.key(",\"method\":");
      name(o, s.method);
    }
    if (f.has(ResultFields::status)) {
      d.key(",\"status\":");
      name(o, to_string(status));
    }
    if (f.has(ResultFields::converged)) {
      d.key(",\"converged\":");
      o.literal(status == Status::converged ? "true" : "false");
    }
    if (f.has(ResultFields::iterations)) {
      d.key(",\"iterations\":");
      o.integer(s.iterations);
    }
    // The residuals and the last step describe the foot point: null without one.
    if (f.has(ResultFields::residual)) {
      d.key(",\"residual\":");
      if (answer)
        o.number(s.residual());
      else
        o.literal("null");
    }
    if (f.has(ResultFields::step_norm)) {
      d.key(",\"step_norm\":");
      if (answer)
        o.number(s.step_norm);
      else
        o.literal("null");
    }
    if (f.has(ResultFields::starts)) {
      d.key(",\"starts\":");
      o.integer(s.starts);
    }
    if (f.has(ResultFields::location)) {
      d.key(",\"location\":");
      name(o, to_string(answer ? s.location : Location::unknown));
    }
    if (f.has(ResultFields::certificate)) {
      d.key(",\"certificate\":");
      write_certificate(o, s.certificate, r, answer);
    }
    if (f.has(ResultFields::multiplicity)) {
      d.key(",\"multiplicity\":");
      write_multiplicity(o, s.multiplicity, r, answer);
    }
    o.literal("}");
  }

  if (f.has(ResultFields::minima)) {
    m.key(",\"minima\":[");
    for (std::size_t i = 0; i < r.minima.size(); ++i) {
      const Minimum& mn = r.minima[i];
      o.literal(i ? ",{\"foot_point\":" : "{\"foot_point\":");
      o.numbers(mn.foot.data(), r.dim);
      if (r.num_params > 0) {
        o.literal(",\"parameters\":");
        o.numbers(mn.params.data(), r.num_params);
      }
      o.literal(",\"distance\":");
      o.number(mn.distance);
      o.literal(",\"location\":");
      name(o, to_string(mn.location));
      if (!mn.copies.empty()) {
        o.literal(",\"parameter_copies\":[");
        for (std::size_t k = 0; k < mn.copies.size(); ++k) {
          if (k) o.literal(",");
          o.numbers(mn.copies[k].data(), 2);
        }
        o.literal(mn.copies_truncated ? "],\"copies_truncated\":true" : "],\"copies_truncated\":false");
      }
      o.literal("}");
    }
    o.literal(r.minima_truncated ? "],\"minima_truncated\":true" : "],\"minima_truncated\":false");
  }
  if (f.has(ResultFields::trace)) {
    m.key(",\"trace\":[");
    for (std::size_t i = 0; i < r.trace.size(); ++i) {
      if (i) o.literal(",");
      o.numbers(r.trace[i].data(), 3);
    }
    o.literal("]");
  }
  o.literal("}");
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
  JsonAppender o(out);
  return write_result(o, r, fields);
}

void append_stats(std::string& out, const BatchStats& stats, const DeviationOptions& options) {
  JsonAppender o(out);
  o.literal("{\"points\":");
  o.integer(static_cast<long long>(stats.points));
  o.literal(",\"converged\":");
  o.integer(static_cast<long long>(stats.by_status[static_cast<std::size_t>(Status::converged)]));
  o.literal(",\"statuses\":{");
  bool first = true;
  for (std::size_t k = 0; k < stats.by_status.size(); ++k) {
    if (stats.by_status[k] == 0) continue;
    o.literal(first ? "\"" : ",\"");
    first = false;
    o.literal(to_string(static_cast<Status>(k)));
    o.literal("\":");
    o.integer(static_cast<long long>(stats.by_status[k]));
  }
  o.literal("},\"elapsed_ms\":");
  o.number(stats.elapsed_ms);
  const DeviationStats& d = stats.deviation;
  o.literal(",\"deviation\":{\"count\":");
  o.integer(static_cast<long long>(d.count));
  o.literal(",\"signed\":");
  o.integer(static_cast<long long>(d.signed_count));
  const bool any = d.count > 0;
  for (const auto& [key, value] : {std::pair{",\"min\":", d.min}, std::pair{",\"max\":", d.max},
                                   std::pair{",\"mean\":", d.mean}, std::pair{",\"rms\":", d.rms}}) {
    o.literal(key);
    if (any)
      o.number(value);
    else
      o.literal("null");
  }
  o.literal(",\"histogram\":");
  if (any) {
    o.literal("{\"edges\":");
    o.numbers(d.edges.data(), static_cast<int>(d.edges.size()));
    o.literal(",\"counts\":[");
    for (std::size_t k = 0; k < d.counts.size(); ++k) {
      if (k) o.literal(",");
      o.integer(static_cast<long long>(d.counts[k]));
    }
    o.literal("],\"resolution\":");
    o.number(d.histogram_resolution);
    o.literal("}");
  } else {
    o.literal("null");
  }
  if (options.tolerance_band) {
    o.literal(",\"tolerance_band\":{\"lo\":");
    o.number((*options.tolerance_band)[0]);
    o.literal(",\"hi\":");
    o.number((*options.tolerance_band)[1]);
    o.literal(",\"within\":");
    o.integer(static_cast<long long>(d.within_band));
    o.literal(",\"share\":");
    if (any)
      o.number(static_cast<double>(d.within_band) / static_cast<double>(d.count));
    else
      o.literal("null");
    o.literal("}");
  }
  o.literal("}}");
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
  {
    JsonAppender o(out);
    o.literal("{\"geometry_id\":");
    o.string(geometry_id);
    o.literal(single ? ",\"result\":" : ",\"results\":[");
    for (std::size_t i = 0; i < results.size(); ++i) {
      if (i) o.literal(",");
      ++stats.by_status[static_cast<std::size_t>(write_result(o, results[i], fields))];
    }
    o.literal(single ? ",\"stats\":" : "],\"stats\":");
  }
  stats.deviation = deviation_stats(results, deviation);
  append_stats(out, stats, deviation);
  out += '}';
  return out;
}

}  // namespace footpoint::server
