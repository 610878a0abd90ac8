// `auto` on closed surfaces and at the domain's boundary, as a geometer reads the answers: a seam is
// no edge, a pole is its own location, a continuum of nearest points is said to be one (with one
// representative, never a long sample), ties are listed, a boundary answer's residual is the KKT
// residual (0 when right), beyond max_distance there is no foot point, options.initial is a warm
// start that never replaces the global search.
// References in closed form: the torus ((3 + cos v) cos u, (3 + cos v) sin u, sin v) is at distance
// ||(ρ - 3, z)| - 1| from p (ρ = |(p_x, p_y)|), nearest at u = atan2(p_y, p_x) unless ρ = 0, where
// every u is nearest; the unit sphere is at |p| - 1; z = u v over [-1, 1]^2 from (1, 2, 3): every
// point has (v - 2)^2 >= 1 and (uv - 3)^2 >= 4, both equalities at the corner (1, 1), so the
// nearest point is (1, 1, 1) at sqrt(5).
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

#include "closed_forms.hpp"
#include "surface_fixtures.hpp"

using namespace footpoint;
using namespace footpoint::test;

namespace {

constexpr double kPi = std::numbers::pi;

std::shared_ptr<const ParametricSurface> torus() {
  return make_surface("(3+cos(v))*cos(u)", "(3+cos(v))*sin(u)", "sin(v)", {0, 2 * kPi}, {0, 2 * kPi});
}

double torus_distance(std::array<double, 3> p) { return test::torus_distance(3, 1, {p[0], p[1], p[2]}); }

}  // namespace

TEST_CASE("torus: a point over the seam is answered in the interior, once, uniquely") {
  const auto g = torus();
  const ProjectionResult r = project(*g, {5, 0, 0}, "auto");
  REQUIRE(r.summary.status == Status::converged);
  CHECK(r.distance == doctest::Approx(1.0).epsilon(1e-14));
  CHECK(r.summary.location == Location::interior);
  CHECK_FALSE(r.summary.on_boundary);
  CHECK(r.summary.multiplicity.computed);
  CHECK(r.summary.multiplicity.kind == Multiplicity::unique);
  CHECK(r.summary.certificate.certified);

  Options all;
  all.all_minima = true;
  const ProjectionResult m = project(*g, {3, 3, 3}, "auto", all);
  CHECK(m.distance == doctest::Approx(torus_distance({3, 3, 3})).epsilon(1e-14));
  // No minimum on the seams v = 0 / 2π or u = 0 / 2π is an edge or a corner.
  for (const Minimum& x : m.minima) {
    CHECK(x.location != Location::edge);
    CHECK(x.location != Location::corner);
  }
}

TEST_CASE("torus and sphere: a circle or a sphere of nearest points is one continuum, one representative") {
  const auto g = torus();
  Options all;
  all.all_minima = true;
  for (const std::array<double, 3> p : {std::array<double, 3>{0, 0, 2}, std::array<double, 3>{0, 0, 0}}) {
    CAPTURE(p[2]);
    const ProjectionResult r = project(*g, p, "auto", all);
    CHECK(r.distance == doctest::Approx(torus_distance(p)).epsilon(1e-13));
    CHECK(r.summary.multiplicity.kind == Multiplicity::continuum);
    // One representative of the circle, not a sample of it.
    CHECK(r.minima.size() <= 2);
    CHECK_FALSE(r.minima_truncated);
  }
  const auto sphere =
      make_surface("cos(u)*cos(v)", "sin(u)*cos(v)", "sin(v)", {0, 2 * kPi}, {-kPi / 2, kPi / 2});
  const ProjectionResult c = project(*sphere, {0, 0, 0}, "auto", all);
  CHECK(c.distance == doctest::Approx(1.0).epsilon(1e-14));
  CHECK(c.summary.multiplicity.kind == Multiplicity::continuum);
  CHECK(c.minima.size() <= 4);
}

TEST_CASE("sphere: a point over a pole is answered at the pole") {
  const auto sphere =
      make_surface("cos(u)*cos(v)", "sin(u)*cos(v)", "sin(v)", {0, 2 * kPi}, {-kPi / 2, kPi / 2});
  const ProjectionResult r = project(*sphere, {0, 0, 3}, "auto");
  REQUIRE(r.summary.status == Status::converged);
  CHECK(r.distance == doctest::Approx(2.0).epsilon(1e-14));
  CHECK(r.summary.location == Location::pole);
  CHECK(std::fabs(r.foot[2] - 1.0) <= 1e-14);
  // Off the pole, on the seam u = 0: interior.
  const ProjectionResult s = project(*sphere, {2, 0, 1}, "auto");
  CHECK(s.distance == doctest::Approx(std::sqrt(5.0) - 1.0).epsilon(1e-14));
  CHECK(s.summary.location == Location::interior);
}

TEST_CASE("two tied nearest points are both listed") {
  // The parabolic cylinder (u, v, u^2) over [-2, 2] x [-1, 1] seen from (0, 0, 2), on its plane of
  // symmetry: d^2 = u^2 + v^2 + (u^2 - 2)^2 is least at v = 0, u = ±sqrt(3/2).
  const auto g = make_surface("u", "v", "u^2", {-2, 2}, {-1, 1});
  const ProjectionResult r = project(*g, {0, 0, 2}, "auto");
  // d^2 = 3/2 + 1/4: d = sqrt(7) / 2.
  CHECK(r.distance == doctest::Approx(std::sqrt(7.0) / 2.0).epsilon(1e-14));
  REQUIRE(r.summary.multiplicity.kind == Multiplicity::tied);
  CHECK(r.summary.multiplicity.count == 2);
  REQUIRE(r.summary.multiplicity.feet.size() == 2);
  CHECK(r.summary.multiplicity.feet[0][0] * r.summary.multiplicity.feet[1][0] < 0.0);  // ±sqrt(3/2)
  for (const auto& f : r.summary.multiplicity.feet)
    CHECK(std::fabs(std::fabs(f[0]) - std::sqrt(1.5)) <= 1e-7);
}

TEST_CASE("a corner answer is converged with a KKT residual of zero") {
  const auto g = make_surface("u", "v", "u*v", {-1, 1}, {-1, 1});
  const ProjectionResult r = project(*g, {1, 2, 3}, "auto");
  REQUIRE(r.summary.status == Status::converged);
  CHECK(r.distance == doctest::Approx(std::sqrt(5.0)).epsilon(1e-15));
  CHECK(r.summary.location == Location::corner);
  CHECK(r.summary.residual() <= 1e-12);
  CHECK(r.summary.certificate.certified);
}

TEST_CASE(
    "beyond max_distance: no foot point, parameters or distance, and a certificate that none is nearer") {
  const auto g = torus();
  Options o;
  o.max_distance = 2.0;
  const ProjectionResult r = project(*g, {10, 10, 10}, "auto", o);
  CHECK(r.summary.status == Status::beyond_max_distance);
  CHECK(std::isnan(r.distance));
  CHECK(std::isnan(r.foot[0]));
  CHECK(std::isnan(r.params[0]));
  // A point within the distance is answered as always.
  const ProjectionResult near = project(*g, {5, 0, 0.5}, "auto", o);
  CHECK(near.summary.status == Status::converged);
  CHECK(near.distance == doctest::Approx(torus_distance({5, 0, 0.5})).epsilon(1e-14));
}

TEST_CASE("options.initial is a warm start: the same global answer from any start") {
  const auto g = torus();
  const std::array<double, 3> p{1.0, 4.5, -0.7};
  const ProjectionResult cold = project(*g, p, "auto");
  for (const auto& start : {start_at(0.1, 0.1), start_at(1.6, 5.0), start_at(4.0, 3.0)}) {
    const ProjectionResult warm = project(*g, p, "auto", start);
    CHECK(warm.summary.status == Status::converged);
    CHECK(warm.distance == doctest::Approx(cold.distance).epsilon(1e-14));
    CHECK(warm.distance == doctest::Approx(torus_distance(p)).epsilon(1e-14));
  }
}

TEST_CASE(
    "property: a rigid motion of the torus, or a shift of its domain by a period, changes no distance") {
  const auto g = torus();
  // Rotated about z by the angle whose cosine is 0.6 and sine 0.8, and moved by (1, -2, 0.5).
  const double cs = 0.6, sn = 0.8;
  const std::string X = "(3+cos(v))*cos(u)", Y = "(3+cos(v))*sin(u)";
  const auto moved = make_surface("0.6*" + X + "-0.8*" + Y + "+1", "0.8*" + X + "+0.6*" + Y + "-2",
                                  "sin(v)+0.5", {0, 2 * kPi}, {0, 2 * kPi});
  // Shifted by one period in u and by half a period in v (still a whole torus).
  const auto shifted =
      make_surface("(3+cos(v))*cos(u)", "(3+cos(v))*sin(u)", "sin(v)", {-2 * kPi, 0}, {-kPi, kPi});
  unsigned state = 12345;
  auto uniform = [&](double lo, double hi) {
    state = state * 1664525u + 1013904223u;
    return lo + (hi - lo) * (state >> 8) / double(1u << 24);
  };
  for (int i = 0; i < 40; ++i) {
    const std::array<double, 3> p{uniform(-6, 6), uniform(-6, 6), uniform(-3, 3)};
    CAPTURE(p[0]);
    CAPTURE(p[1]);
    CAPTURE(p[2]);
    const double d = project(*g, p, "auto").distance;
    const std::array<double, 3> q{cs * p[0] - sn * p[1] + 1, sn * p[0] + cs * p[1] - 2, p[2] + 0.5};
    CHECK(project(*moved, q, "auto").distance == doctest::Approx(d).epsilon(1e-12));
    CHECK(project(*shifted, p, "auto").distance == doctest::Approx(d).epsilon(1e-13));
    CHECK(d == doctest::Approx(torus_distance(p)).epsilon(1e-13));
  }
}
