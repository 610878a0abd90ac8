#include "result_binary.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>

#include "api_error.hpp"

namespace footpoint::server {

namespace {

struct Column {
  ResultFields::Member member;
  const char* name;
};
// Every member a record may hold, in the result's order.
constexpr Column kColumns[] = {
    {ResultFields::foot_point, "foot_point"},
    {ResultFields::parameters, "parameters"},
    {ResultFields::distance, "distance"},
    {ResultFields::normal, "normal"},
    {ResultFields::signed_distance, "signed_distance"},
    {ResultFields::status, "status"},
    {ResultFields::converged, "converged"},
    {ResultFields::iterations, "iterations"},
    {ResultFields::residual, "residual"},
    {ResultFields::step_norm, "step_norm"},
    {ResultFields::starts, "starts"},
    {ResultFields::location, "location"},
};

const char* column_name(ResultFields::Member m) {
  for (const auto& c : kColumns)
    if (c.member == m) return c.name;
  return "?";
}

void put(std::string& out, double x) {
  unsigned char bytes[8];
  std::memcpy(bytes, &x, 8);
  if constexpr (std::endian::native == std::endian::big) std::reverse(bytes, bytes + 8);
  out.append(reinterpret_cast<const char*>(bytes), 8);
}

}  // namespace

std::size_t BinaryLayout::record_bytes() const {
  std::size_t n = 0;
  for (const auto& [member, count] : columns) n += static_cast<std::size_t>(count) * 8;
  return n;
}

std::string BinaryLayout::describe() const {
  std::string s;
  for (const auto& [member, count] : columns)
    (((s += s.empty() ? "" : ",") += column_name(member)) += ':') += std::to_string(count);
  return s;
}

BinaryLayout binary_layout(ResultFields fields, bool fields_given, int point_dim, int num_params) {
  if (!fields_given)
    fields.members = ResultFields::foot_point | ResultFields::parameters | ResultFields::distance |
                     ResultFields::normal | ResultFields::signed_distance | ResultFields::status;
  constexpr std::uint32_t kNotNumbers = ResultFields::method | ResultFields::certificate |
                                        ResultFields::multiplicity | ResultFields::minima |
                                        ResultFields::trace;
  if (fields.members & kNotNumbers)
    throw ApiError(
        400, "unsupported_field",
        "a binary answer (Accept: application/octet-stream) holds numbers only: fields may name "
        "foot_point, parameters, distance, normal, signed_distance, diagnostics.status, "
        "diagnostics.converged, diagnostics.iterations, diagnostics.residual, diagnostics.step_norm, "
        "diagnostics.starts and diagnostics.location (not diagnostics as a whole, method, "
        "certificate, multiplicity, minima or trace: ask for application/x-ndjson)",
        "fields");
  BinaryLayout layout;
  for (const auto& c : kColumns) {
    if (!fields.has(c.member)) continue;
    const int count = c.member == ResultFields::foot_point || c.member == ResultFields::normal ? point_dim
                      : c.member == ResultFields::parameters                                   ? num_params
                                                                                               : 1;
    if (count > 0) layout.columns.emplace_back(c.member, count);
  }
  if (layout.columns.empty())
    throw ApiError(400, "unsupported_field", "fields names no number this geometry's results have", "fields");
  return layout;
}

Status append_record(std::string& out, const ProjectionResult& r, const BinaryLayout& layout) {
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  const Status status = reported_status(r);
  const bool answer = has_finite_answer(r);
  const Summary& s = r.summary;
  for (const auto& [member, count] : layout.columns) {
    switch (member) {
      case ResultFields::foot_point:
        for (int k = 0; k < count; ++k) put(out, answer ? r.foot[k] : nan);
        break;
      case ResultFields::parameters:
        for (int k = 0; k < count; ++k) put(out, answer ? r.params[k] : nan);
        break;
      case ResultFields::distance:
        put(out, answer ? r.distance : nan);
        break;
      case ResultFields::normal:
        for (int k = 0; k < count; ++k) put(out, answer && r.has_normal() ? r.normal[k] : nan);
        break;
      case ResultFields::signed_distance:
        put(out, answer && r.has_normal() ? r.signed_distance : nan);
        break;
      case ResultFields::status:
        put(out, static_cast<double>(status));
        break;
      case ResultFields::converged:
        put(out, status == Status::converged ? 1.0 : 0.0);
        break;
      case ResultFields::iterations:
        put(out, s.iterations);
        break;
      case ResultFields::residual:
        put(out, s.residual());
        break;
      case ResultFields::step_norm:
        put(out, s.step_norm);
        break;
      case ResultFields::starts:
        put(out, s.starts);
        break;
      case ResultFields::location:
        put(out, static_cast<double>(s.location));
        break;
      default:
        break;
    }
  }
  return status;
}

}  // namespace footpoint::server
