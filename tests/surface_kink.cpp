// auto on a surface whose nearest point lies on a kink curve of its formulas
// (solvers/surface/kink_minimum.hpp): converged, location kink, residual 0, against minima worked
// out by hand; a kink that is no minimum of the distance is not claimed.
#include <doctest/doctest.h>

#include <cmath>

#include "surface_fixtures.hpp"

using namespace footpoint;
using namespace footpoint::test;

TEST_CASE("a nearest point on a straight kink: z = |u| from (0, 0.2, -0.5)") {
  // f = u^2 + (v - 0.2)^2 + (|u| + 0.5)^2 has its least value 0.25 at (0, 0.2); its slope in u
  // jumps from -1 to 1 there
  const auto g = make_surface("u", "v", "abs(u)", {-1, 1}, {-1, 1});
  const ProjectionResult r = project(*g, {0, 0.2, -0.5}, "auto");
  CHECK(r.summary.status == Status::converged);
  CHECK(r.summary.location == Location::kink);
  CHECK(r.summary.orthogonality[0] == 0.0);
  CHECK(r.summary.orthogonality[1] == 0.0);
  CHECK(r.distance == doctest::Approx(0.5).epsilon(1e-15));
  CHECK(std::abs(r.params[0]) <= 1e-15);
  CHECK(std::abs(r.params[1] - 0.2) <= 1e-14);
  const Vec3 foot{r.foot[0], r.foot[1], r.foot[2]};
  CHECK(norm(foot - g->formulas().point(r.params[0], r.params[1])) == 0.0);
  CHECK(r.summary.certificate.lower_bound <= r.distance);
  CHECK(r.summary.certificate.certified);
}

TEST_CASE("a nearest point on a curved kink: z = |u - v^2| from (0.5, 0.3, -1)") {
  // On the kink u = v^2 (z = 0): (v^2 - 0.5)^2 + (v - 0.3)^2 + 1, least where 4 v^3 = 0.6. Off it
  // the gradients of the two pieces, (2(u - 0.5) ± 2, 2(v - 0.3) ∓ 4v), are normal to the kink and
  // point away from it on both sides: a kink minimum
  const auto g = make_surface("u", "v", "abs(u-v^2)", {-1, 1}, {-1, 1});
  const ProjectionResult r = project(*g, {0.5, 0.3, -1}, "auto");
  const double v = std::cbrt(0.15), u = v * v;
  const double d = std::sqrt((u - 0.5) * (u - 0.5) + (v - 0.3) * (v - 0.3) + 1.0);
  CHECK(r.summary.status == Status::converged);
  CHECK(r.summary.location == Location::kink);
  CHECK(r.distance == doctest::Approx(d).epsilon(1e-14));
  CHECK(r.params[0] == doctest::Approx(u).epsilon(1e-7));  // the distance is flat to second order
  CHECK(r.params[1] == doctest::Approx(v).epsilon(1e-7));
  CHECK(r.summary.certificate.lower_bound <= r.distance);
}

TEST_CASE("a kink that is no minimum is not claimed: z = -|u| from (0, 0.2, -0.5)") {
  // f = u^2 + (v - 0.2)^2 + (0.5 - |u|)^2 = 2u^2 - |u| + 0.25 + (v - 0.2)^2 falls away from u = 0:
  // the nearest points are the smooth minima at u = ±1/4, distance √(1/8)
  const auto g = make_surface("u", "v", "-abs(u)", {-1, 1}, {-1, 1});
  const ProjectionResult r = project(*g, {0, 0.2, -0.5}, "auto");
  CHECK(r.summary.status == Status::converged);
  CHECK(r.summary.location == Location::interior);
  CHECK(r.distance == doctest::Approx(std::sqrt(0.125)).epsilon(1e-14));
  CHECK(std::abs(std::abs(r.params[0]) - 0.25) <= 1e-12);
}
