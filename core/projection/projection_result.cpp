#include "projection/projection_result.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace footpoint {

const char* to_string(Status s) {
  switch (s) {
    case Status::converged:
      return "converged";
    case Status::max_iterations:
      return "max_iterations";
    case Status::diverged:
      return "diverged";
    case Status::non_finite:
      return "non_finite";
    case Status::degenerate:
      return "degenerate";
    case Status::outside_domain:
      return "outside_domain";
    case Status::not_orthogonal:
      return "not_orthogonal";
    case Status::beyond_max_distance:
      return "beyond_max_distance";
    case Status::deadline_exceeded:
      return "deadline_exceeded";
  }
  return "unknown";
}

const char* to_string(Location l) {
  switch (l) {
    case Location::interior:
      return "interior";
    case Location::edge:
      return "edge";
    case Location::corner:
      return "corner";
    case Location::endpoint:
      return "endpoint";
    case Location::box_face:
      return "box_face";
    case Location::box_edge:
      return "box_edge";
    case Location::box_corner:
      return "box_corner";
    case Location::singular_point:
      return "singular_point";
    case Location::pole:
      return "pole";
    case Location::kink:
      return "kink";
    case Location::unknown:
      return "unknown";
  }
  return "unknown";
}

const char* to_string(CertificateReason r) {
  switch (r) {
    case CertificateReason::gap_met:
      return "gap_met";
    case CertificateReason::budget_exhausted:
      return "budget_exhausted";
    case CertificateReason::non_finite:
      return "non_finite";
    case CertificateReason::singular:
      return "singular";
    case CertificateReason::nearer_point:
      return "nearer_point";
    case CertificateReason::not_requested:
      return "not_requested";
  }
  return "unknown";
}

const char* to_string(Multiplicity m) {
  switch (m) {
    case Multiplicity::unique:
      return "unique";
    case Multiplicity::tied:
      return "tied";
    case Multiplicity::continuum:
      return "continuum";
  }
  return "unique";
}

void AnswerMultiplicity::add_distinct(const std::array<double, 3>& foot, double same) {
  for (const auto& f : feet) {
    const double dx = f[0] - foot[0], dy = f[1] - foot[1], dz = f[2] - foot[2];
    if (dx * dx + dy * dy + dz * dz <= same * same) return;
  }
  feet.push_back(foot);
}

void AnswerMultiplicity::settle() {
  count = static_cast<int>(feet.size());
  if (count > 1) {
    kind = Multiplicity::tied;
  } else {
    count = 1;
    feet.clear();
  }
}

void withhold_answer(ProjectionResult& r) {
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  r.foot = {nan, nan, nan};
  r.params = {nan, nan};
  r.distance = nan;
  r.summary.status = Status::beyond_max_distance;
  r.summary.location = Location::unknown;
  r.summary.on_boundary = false;
}

void cap_minima(ProjectionResult& r, const Options& options) {
  if (r.minima.size() <= options.minima_cap()) return;
  r.minima.resize(options.minima_cap());
  r.minima_truncated = true;
}

void set_foot_normal(ProjectionResult& r, const double* p, const std::array<double, 3>& n) {
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  r.normal = {nan, nan, nan};
  r.signed_distance = nan;
  if (!std::isfinite(r.distance)) return;
  double side = 0.0;
  for (int k = 0; k < r.dim; ++k) {
    if (!std::isfinite(n[k]) || !std::isfinite(r.foot[k])) return;
    side += (p[k] - r.foot[k]) * n[k];
  }
  for (int k = 0; k < r.dim; ++k) r.normal[k] = n[k];
  r.signed_distance = side < 0.0 ? -r.distance : r.distance;
}

double Summary::residual() const {
  return std::max({orthogonality[0], orthogonality[1], equation_residual[0], equation_residual[1]});
}

}  // namespace footpoint
