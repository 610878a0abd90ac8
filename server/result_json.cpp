#include "result_json.hpp"

#include <cmath>

#include "json_writer.hpp"

namespace footpoint::server {

namespace {

bool finite_answer(const ProjectionResult& r) {
  if (!std::isfinite(r.distance)) return false;
  for (int k = 0; k < r.dim; ++k)
    if (!std::isfinite(r.foot[k])) return false;
  for (int k = 0; k < r.num_params; ++k)
    if (!std::isfinite(r.params[k])) return false;
  return true;
}

// Method, status and location names are plain identifiers; anything else is escaped.
void name(JsonAppender& o, std::string_view s) {
  for (char c : s)
    if (!((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_')) return o.string(s);
  o.literal("\"");
  o.literal(s);
  o.literal("\"");
}

// Writes one result; returns its reported status.
Status write_result(JsonAppender& o, const ProjectionResult& r, bool with_minima, bool with_trace) {
  const bool answer = finite_answer(r);
  const Status status = reported_status(r);
  o.literal("{\"foot_point\":");
  if (answer)
    o.numbers(r.foot.data(), r.dim);
  else
    o.literal("null");
  if (r.num_params > 0) {
    o.literal(",\"parameters\":");
    if (answer)
      o.numbers(r.params.data(), r.num_params);
    else
      o.literal("null");
  }
  o.literal(",\"distance\":");
  if (answer)
    o.number(r.distance);
  else
    o.literal("null");

  const Summary& s = r.summary;
  o.literal(",\"diagnostics\":{\"method\":");
  name(o, s.method);
  o.literal(",\"status\":");
  name(o, to_string(status));
  o.literal(status == Status::converged ? ",\"converged\":true,\"iterations\":"
                                        : ",\"converged\":false,\"iterations\":");
  o.integer(s.iterations);
  o.literal(",\"residual\":");
  o.number(s.residual());
  o.literal(",\"step_norm\":");
  o.number(s.step_norm);
  o.literal(",\"starts\":");
  o.integer(s.starts);
  o.literal(",\"location\":");
  name(o, to_string(s.location));
  o.literal(",\"certificate\":");
  const Certificate& c = s.certificate;
  if (c.computed) {
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
  } else {
    o.literal("null");
  }
  o.literal(",\"multiplicity\":");
  const AnswerMultiplicity& m = s.multiplicity;
  if (m.computed && answer) {
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
  } else {
    o.literal("null");
  }
  o.literal("}");

  if (with_minima) {
    o.literal(",\"minima\":[");
    for (std::size_t i = 0; i < r.minima.size(); ++i) {
      const Minimum& m = r.minima[i];
      o.literal(i ? ",{\"foot_point\":" : "{\"foot_point\":");
      o.numbers(m.foot.data(), r.dim);
      if (r.num_params > 0) {
        o.literal(",\"parameters\":");
        o.numbers(m.params.data(), r.num_params);
      }
      o.literal(",\"distance\":");
      o.number(m.distance);
      o.literal(",\"location\":");
      name(o, to_string(m.location));
      o.literal("}");
    }
    o.literal(r.minima_truncated ? "],\"minima_truncated\":true" : "],\"minima_truncated\":false");
  }
  if (with_trace) {
    o.literal(",\"trace\":[");
    for (std::size_t i = 0; i < r.trace.size(); ++i) {
      if (i) o.literal(",");
      o.numbers(r.trace[i].data(), 3);
    }
    o.literal("]");
  }
  o.literal("}");
  return status;
}

}  // namespace

Status reported_status(const ProjectionResult& r) {
  if (r.summary.status == Status::converged && !finite_answer(r)) return Status::non_finite;
  return r.summary.status;
}

std::string project_response(const std::string& geometry_id, const std::vector<ProjectionResult>& results,
                             bool single, bool with_minima, bool with_trace, double elapsed_ms) {
  // ~330 bytes per plain result; more with minima or trace.
  std::string out;
  out.reserve(128 + results.size() * (with_minima || with_trace ? 1024 : 340));
  JsonAppender o(out);
  o.literal("{\"geometry_id\":");
  o.string(geometry_id);
  std::size_t converged = 0;
  o.literal(single ? ",\"result\":" : ",\"results\":[");
  for (std::size_t i = 0; i < results.size(); ++i) {
    if (i) o.literal(",");
    converged += write_result(o, results[i], with_minima, with_trace) == Status::converged;
  }
  o.literal(single ? ",\"stats\":{\"points\":" : "],\"stats\":{\"points\":");
  o.integer(static_cast<long long>(results.size()));
  o.literal(",\"converged\":");
  o.integer(static_cast<long long>(converged));
  o.literal(",\"elapsed_ms\":");
  o.number(elapsed_ms);
  o.literal("}}");
  o.flush();
  return out;
}

}  // namespace footpoint::server
