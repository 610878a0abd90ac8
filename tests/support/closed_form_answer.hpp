// Shared by the tests of `auto` called with its own parts (parametric curves and surfaces): an
// answer checked against a distance and a foot known in closed form, and the options every `auto`
// honours (max_distance, certify off) checked on one such point.
#pragma once
#include <doctest/doctest.h>

#include <cmath>
#include <functional>

#include "geometry/vec.hpp"
#include "projection/projection_result.hpp"

namespace footpoint::test {

inline Vec3 foot_vec(const ProjectionResult& r) { return {r.foot[0], r.foot[1], r.foot[2]}; }

// Converged at distance d (1e-12 relative, 1e-15 absolute), the foot within 1e-9 of `foot` (its
// error is about the square root of the distance's) and the geometry's point at the answer's
// parameters (`at_params`, evaluated by the caller) to rounding, at `where` (a boundary location
// exactly when on_boundary); the certificate's lower bound at most d, certified.
inline void check_closed_form_answer(const ProjectionResult& r, Vec3 p, double d, Vec3 foot, Vec3 at_params,
                                     Location where) {
  CAPTURE(p.x);
  CAPTURE(p.y);
  CAPTURE(p.z);
  REQUIRE(r.summary.status == Status::converged);
  CHECK(r.summary.method == "auto");
  CHECK(std::abs(r.distance - d) <= 1e-12 * d + 1e-15);
  CHECK(norm(foot_vec(r) - foot) <= 1e-9);
  CHECK(norm(at_params - foot_vec(r)) <= 1e-15 * (1.0 + norm(foot)));
  CHECK(std::abs(norm(p - foot_vec(r)) - r.distance) <= 1e-15 * (1.0 + r.distance));
  CHECK(r.summary.location == where);
  CHECK(r.summary.on_boundary ==
        (where == Location::endpoint || where == Location::edge || where == Location::corner));
  const Certificate& c = r.summary.certificate;
  CHECK(c.computed);
  CHECK(c.lower_bound <= d * (1.0 + 0x1p-51));
  CHECK(c.certified);
}

// A continuum of nearest points at distance d (a circle's centre, a torus's axis).
inline void check_continuum(const ProjectionResult& r, double d) {
  REQUIRE(r.summary.status == Status::converged);
  CHECK(r.distance == doctest::Approx(d).epsilon(1e-12));
  CHECK(r.summary.multiplicity.kind == Multiplicity::continuum);
  CHECK(r.summary.certificate.lower_bound <= d * (1.0 + 0x1p-51));
}

// `project` at a point whose distance is d > 0: with max_distance 3d/4 no answer
// (beyond_max_distance, no distance), with 9d/8 the answer; with certify off the same answer
// without a certificate.
inline void check_max_distance_and_certify(const std::function<ProjectionResult(const Options&)>& project,
                                           double d) {
  Options near;
  near.max_distance = 0.75 * d;
  const ProjectionResult none = project(near);
  CHECK(none.summary.status == Status::beyond_max_distance);
  CHECK(std::isnan(none.distance));
  near.max_distance = 1.125 * d;
  CHECK(project(near).distance == doctest::Approx(d).epsilon(1e-12));
  Options plain;
  plain.certify = false;
  const ProjectionResult u = project(plain);
  CHECK(u.distance == doctest::Approx(d).epsilon(1e-12));
  CHECK_FALSE(u.summary.certificate.computed);
}

}  // namespace footpoint::test
