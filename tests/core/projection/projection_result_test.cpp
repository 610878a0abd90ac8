// projection/projection_result: what every answer is made of. The names the API writes for each
// status, location, certificate reason and multiplicity; the tie list (feet within `same` of one
// listed are one foot); the answer withheld beyond max_distance; the cap on all_minima; the signed
// distance, whose sign is the side of p relative to the normal at the foot (a unit sphere: outside
// +, inside -); the residual as the largest of its parts.
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <set>
#include <string>
#include <utility>

#include "projection/projection_result.hpp"

using namespace footpoint;

TEST_CASE("projection result: the names of statuses, locations, reasons and multiplicities") {
  const std::array<std::pair<Status, const char*>, 9> statuses{
      {{Status::converged, "converged"},
       {Status::max_iterations, "max_iterations"},
       {Status::diverged, "diverged"},
       {Status::non_finite, "non_finite"},
       {Status::degenerate, "degenerate"},
       {Status::outside_domain, "outside_domain"},
       {Status::not_orthogonal, "not_orthogonal"},
       {Status::beyond_max_distance, "beyond_max_distance"},
       {Status::deadline_exceeded, "deadline_exceeded"}}};
  std::set<std::string> seen;
  for (const auto& [status, name] : statuses) {
    CHECK(std::string(to_string(status)) == name);
    seen.insert(to_string(status));
  }
  CHECK(seen.size() == statuses.size());
  const std::array<std::pair<Location, const char*>, 11> locations{
      {{Location::interior, "interior"},
       {Location::edge, "edge"},
       {Location::corner, "corner"},
       {Location::endpoint, "endpoint"},
       {Location::box_face, "box_face"},
       {Location::box_edge, "box_edge"},
       {Location::box_corner, "box_corner"},
       {Location::singular_point, "singular_point"},
       {Location::pole, "pole"},
       {Location::kink, "kink"},
       {Location::unknown, "unknown"}}};
  for (const auto& [location, name] : locations) CHECK(std::string(to_string(location)) == name);
  CHECK(std::string(to_string(CertificateReason::gap_met)) == "gap_met");
  CHECK(std::string(to_string(CertificateReason::budget_exhausted)) == "budget_exhausted");
  CHECK(std::string(to_string(CertificateReason::nearer_point)) == "nearer_point");
  CHECK(std::string(to_string(CertificateReason::not_requested)) == "not_requested");
  CHECK(std::string(to_string(Multiplicity::unique)) == "unique");
  CHECK(std::string(to_string(Multiplicity::tied)) == "tied");
  CHECK(std::string(to_string(Multiplicity::continuum)) == "continuum");
}

TEST_CASE("projection result: tied feet are listed once each, a single one is unique") {
  AnswerMultiplicity m;
  m.add_distinct({1, 0, 0}, 1e-8);
  m.add_distinct({1 + 5e-9, 0, 0}, 1e-8);  // within 1e-8 of the first: the same foot
  m.add_distinct({1, 0, 0.5e-8}, 1e-8);    // likewise
  m.settle();
  CHECK(m.kind == Multiplicity::unique);
  CHECK(m.count == 1);
  CHECK(m.feet.empty());
  AnswerMultiplicity tied;
  tied.add_distinct({1, 0, 0}, 1e-8);
  tied.add_distinct({-1, 0, 0}, 1e-8);
  tied.add_distinct({0, 1, 0}, 1e-8);
  tied.add_distinct({-1, 2e-8, 0}, 1e-8);  // 2e-8 from (-1, 0, 0): a foot of its own
  tied.settle();
  CHECK(tied.kind == Multiplicity::tied);
  CHECK(tied.count == 4);
  REQUIRE(tied.feet.size() == 4);
  CHECK(tied.feet[0] == std::array<double, 3>{1, 0, 0});  // the answer's foot first
}

TEST_CASE("projection result: an answer withheld beyond max_distance, and the minima's cap") {
  ProjectionResult r;
  r.foot = {1, 2, 3};
  r.params = {0.5, 0.25};
  r.distance = 4.0;
  r.summary.status = Status::converged;
  r.summary.location = Location::edge;
  r.summary.on_boundary = true;
  withhold_answer(r);
  CHECK(std::isnan(r.foot[0]));
  CHECK(std::isnan(r.foot[2]));
  CHECK(std::isnan(r.params[1]));
  CHECK(std::isnan(r.distance));
  CHECK(r.summary.status == Status::beyond_max_distance);
  CHECK(r.summary.location == Location::unknown);
  CHECK_FALSE(r.summary.on_boundary);

  Options options;
  options.max_minima = 2;
  ProjectionResult many;
  many.minima.resize(5);
  for (std::size_t k = 0; k < 5; ++k) many.minima[k].distance = static_cast<double>(k);
  cap_minima(many, options);
  REQUIRE(many.minima.size() == 2);
  CHECK(many.minima_truncated);
  CHECK(many.minima[1].distance == 1.0);  // the best ones are kept
  ProjectionResult few;
  few.minima.resize(2);
  cap_minima(few, options);
  CHECK(few.minima.size() == 2);
  CHECK_FALSE(few.minima_truncated);
  // Without max_minima the default cap holds.
  const auto cap = static_cast<std::size_t>(Options::kDefaultMaxMinima);
  ProjectionResult defaulted;
  defaulted.minima.resize(cap + 3);
  cap_minima(defaulted, Options{});
  CHECK(defaulted.minima.size() == cap);
  CHECK(defaulted.minima_truncated);
}

TEST_CASE("projection result: the signed distance is on the normal's side of the foot") {
  // The unit sphere's outward normal at its foot (1, 0, 0).
  const std::array<double, 3> outward{1, 0, 0};
  ProjectionResult outside;
  outside.foot = {1, 0, 0};
  outside.distance = 1.0;
  const double p_out[3] = {2, 0, 0};
  set_foot_normal(outside, p_out, outward);
  CHECK(outside.has_normal());
  CHECK(outside.normal == outward);
  CHECK(outside.signed_distance == 1.0);
  ProjectionResult inside;
  inside.foot = {1, 0, 0};
  inside.distance = 0.5;
  const double p_in[3] = {0.5, 0, 0};
  set_foot_normal(inside, p_in, outward);
  CHECK(inside.signed_distance == -0.5);
  // p on the geometry: +0.
  ProjectionResult on;
  on.foot = {1, 0, 0};
  on.distance = 0.0;
  set_foot_normal(on, on.foot.data(), outward);
  CHECK(on.signed_distance == 0.0);
  CHECK_FALSE(std::signbit(on.signed_distance));
  // A planar curve reads two coordinates: a NaN third entry of n does not matter.
  ProjectionResult planar;
  planar.dim = 2;
  planar.foot = {0, 1, 0};
  planar.distance = 2.0;
  const double p_planar[2] = {0, -1};
  set_foot_normal(planar, p_planar, {0, 1, NAN});
  CHECK(planar.signed_distance == -2.0);
  // No normal (a singular point, a pole), or no answer: both stay NaN.
  ProjectionResult singular;
  singular.foot = {1, 0, 0};
  singular.distance = 1.0;
  set_foot_normal(singular, p_out, {NAN, NAN, NAN});
  CHECK_FALSE(singular.has_normal());
  CHECK(std::isnan(singular.signed_distance));
  ProjectionResult none;
  set_foot_normal(none, p_out, outward);
  CHECK_FALSE(none.has_normal());
  CHECK(std::isnan(none.signed_distance));
}

TEST_CASE("projection result: the residual is the largest of its parts") {
  Summary s;
  CHECK(s.residual() == 0.0);
  s.orthogonality = {1e-12, 3e-13};
  s.equation_residual = {2e-14, 5e-12};
  CHECK(s.residual() == 5e-12);
  s.orthogonality[1] = 7e-12;
  CHECK(s.residual() == 7e-12);
}
