// parametric/solvers/surface_auto: project_auto called with its own parts (the cells, the formulas,
// the box, the closure), against closed forms:
//  - the unit sphere (cos u cos v, sin u cos v, sin v), u in [0, 2π], v in [-π/2, π/2]: from
//    p != 0 the foot p/|p| at ||p| - 1| (interior, across the seam u = 0 = 2π too); on the axis
//    the pole (0, 0, ±1), a location of its own; from the centre every point (a continuum);
//  - the torus ((2 + cos v/2) cos u, (2 + cos v/2) sin u, sin v/2) over [0, 2π]^2: from p at
//    distance ρ > 0 from the axis, in the half-plane of angle φ, the foot is the tube's point
//    towards (ρ, z) from the core circle's point (2, 0) in that half-plane, at
//    |(ρ - 2, z)| - 1/2; from the axis point (0, 0, 1) the whole circle at √5 - 1/2 (a continuum);
//  - a quarter cylinder (cos u, sin u, v), u in [0, π/2], v in [0, 1]: from p = (ρ cos φ, ρ sin φ,
//    z) the squared distance 1 + ρ^2 - 2ρ cos(u - φ) + (v - z)^2 is least at the u of [0, π/2]
//    nearest φ and the v of [0, 1] nearest z: an interior, edge or corner foot;
//  - the parabolic sheet (u, v, u^2) from (0, 0.3, 2): u^2 + (u^2 - 2)^2 + (v - 0.3)^2 is least at
//    v = 0.3, u = ±√(3/2), two feet tied at √7/2.
// Every answer's certificate has its lower bound <= the true distance and is certified.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "closed_form_answer.hpp"
#include "closed_forms.hpp"
#include "parametric/solvers/surface_auto.hpp"

using namespace footpoint;

namespace surface_auto_test {

constexpr double kPi = std::numbers::pi;

// What a compiled parametric surface holds, built from its parts as the compiler does.
struct Patch {
  SurfaceFormulas formulas;
  ParamBox box;
  CompileBudget budget;
  SurfaceClosure closure;
  SelfCovering covering;
  SurfaceCells cells;
  Patch(const std::string& x, const std::string& y, const std::string& z, const ParamBox& b)
      : formulas(formula::Program::compile({{"x", x}, {"y", y}, {"z", z}}, {"u", "v"}, {})),
        box(b),
        closure(detect_surface_closure(formulas, box)),
        covering(detect_self_covering(formulas, box)),
        cells(formulas, box, budget, {}, covering) {}
  ProjectionResult project(Vec3 p, const Options& o = {}) const {
    return surface::project_auto(cells, formulas, box, closure, p, o);
  }
};

// The answer against the closed form, the surface evaluated at its parameters.
void check_answer(const Patch& s, const ProjectionResult& r, Vec3 p, double d, Vec3 foot, Location where) {
  test::check_closed_form_answer(r, p, d, foot, s.formulas.point(r.params[0], r.params[1]), where);
  CHECK(s.box.contains(r.params[0], r.params[1]));
}

const char* const kSphere[3] = {"cos(u)*cos(v)", "sin(u)*cos(v)", "sin(v)"};
const char* const kTorus[3] = {"(2+0.5*cos(v))*cos(u)", "(2+0.5*cos(v))*sin(u)", "0.5*sin(v)"};

TEST_CASE("surface_auto: the sphere's foot is p/|p|, across the seam, at a pole; its centre is a continuum") {
  const Patch sphere(kSphere[0], kSphere[1], kSphere[2], {0, 2 * kPi, -kPi / 2, kPi / 2});
  for (const Vec3 p : {Vec3{1, 2, 2}, Vec3{-0.2, 0.1, 0.3}, Vec3{2, -1e-7, 0.5}, Vec3{3, 0, -1}}) {
    const ProjectionResult r = sphere.project(p);
    check_answer(sphere, r, p, std::abs(norm(p) - 1), p / norm(p), Location::interior);
    CHECK(r.summary.multiplicity.kind == Multiplicity::unique);
  }
  check_answer(sphere, sphere.project({0, 0, 5}), {0, 0, 5}, 4, {0, 0, 1}, Location::pole);
  check_answer(sphere, sphere.project({0, 0, -0.5}), {0, 0, -0.5}, 0.5, {0, 0, -1}, Location::pole);
  test::check_continuum(sphere.project({0, 0, 0}), 1.0);
}

TEST_CASE("surface_auto: the torus, off its axis and on it; a warm start elsewhere changes nothing") {
  const Patch torus(kTorus[0], kTorus[1], kTorus[2], {0, 2 * kPi, 0, 2 * kPi});
  for (const Vec3 p : {Vec3{3, 0, 1}, Vec3{1, 2, 0.3}, Vec3{-0.5, -1.2, -0.4}, Vec3{-4, 1, 2}}) {
    check_answer(torus, torus.project(p), p, test::torus_distance(2, 0.5, p), test::torus_foot(2, 0.5, p),
                 Location::interior);
  }
  // started at the far side of the torus, the search is global all the same
  Options warm;
  warm.initial = std::array<double, 3>{kPi, kPi, 0};
  const Vec3 p{3, 0, 1};
  check_answer(torus, torus.project(p, warm), p, std::sqrt(2.0) - 0.5, test::torus_foot(2, 0.5, p),
               Location::interior);
  test::check_continuum(torus.project({0, 0, 1}), std::sqrt(5.0) - 0.5);
}

TEST_CASE("surface_auto: a quarter cylinder's feet inside, on an edge and at a corner") {
  const Patch quarter("cos(u)", "sin(u)", "v", {0, kPi / 2, 0, 1});
  // φ = π/4 inside [0, π/2], z inside [0, 1]
  check_answer(quarter, quarter.project({2, 2, 0.5}), {2, 2, 0.5}, 2 * std::sqrt(2.0) - 1,
               {std::sqrt(0.5), std::sqrt(0.5), 0.5}, Location::interior);
  // φ < 0: u = 0; z inside: the edge u = 0, foot (1, 0, z), distance |(2, -1, 0)|
  check_answer(quarter, quarter.project({3, -1, 0.5}), {3, -1, 0.5}, std::sqrt(5.0), {1, 0, 0.5},
               Location::edge);
  // φ inside, z > 1: the edge v = 1, foot (cos φ, sin φ, 1), distance |(ρ - 1, 1)|
  const double phi = 0.6, rho = 0.5;
  const Vec3 p{rho * std::cos(phi), rho * std::sin(phi), 2};
  check_answer(quarter, quarter.project(p), p, std::hypot(rho - 1, 1.0), {std::cos(phi), std::sin(phi), 1},
               Location::edge);
  // φ < 0 and z > 1: the corner (1, 0, 1)
  check_answer(quarter, quarter.project({3, -1, 2}), {3, -1, 2}, std::sqrt(6.0), {1, 0, 1}, Location::corner);
  // φ > π/2 and z < 0: the corner (0, 1, 0)
  check_answer(quarter, quarter.project({-1, 2, -0.5}), {-1, 2, -0.5}, std::sqrt(1 + 1 + 0.25), {0, 1, 0},
               Location::corner);
}

TEST_CASE("surface_auto: the parabolic sheet's two tied feet, both listed by all_minima") {
  const Patch sheet("u", "v", "u^2", {-2, 2, -1, 1});
  Options all;
  all.all_minima = true;
  const ProjectionResult r = sheet.project({0, 0.3, 2}, all);
  const double d = std::sqrt(7.0) / 2, u = std::sqrt(1.5);
  REQUIRE(r.summary.status == Status::converged);
  CHECK(r.distance == doctest::Approx(d).epsilon(1e-12));
  CHECK(std::abs(std::abs(r.params[0]) - u) <= 1e-9);
  CHECK(std::abs(r.params[1] - 0.3) <= 1e-9);
  CHECK(r.summary.multiplicity.kind == Multiplicity::tied);
  CHECK(r.summary.multiplicity.count == 2);
  CHECK(r.summary.certificate.certified);
  CHECK(r.summary.certificate.lower_bound <= d * (1.0 + 0x1p-51));
  REQUIRE(r.minima.size() == 2);
  for (const Minimum& m : r.minima) {
    CHECK(m.distance == doctest::Approx(d).epsilon(1e-12));
    CHECK(std::abs(std::abs(m.params[0]) - u) <= 1e-9);
  }
  CHECK(r.minima[0].params[0] * r.minima[1].params[0] < 0.0);
}

TEST_CASE("surface_auto: beyond max_distance no foot, with a certificate that none is nearer") {
  const Patch sphere(kSphere[0], kSphere[1], kSphere[2], {0, 2 * kPi, -kPi / 2, kPi / 2});
  // the sphere is 4 from (0, 0, 5): beyond 3, the certificate proves none nearer than 3
  Options near;
  near.max_distance = 3.0;
  const ProjectionResult none = sphere.project({0, 0, 5}, near);
  CHECK(none.summary.certificate.computed);
  CHECK(none.summary.certificate.certified);
  CHECK(none.summary.certificate.lower_bound <= 4.0);
  CHECK(none.summary.certificate.lower_bound >= 3.0 * (1.0 - 1e-9));
  test::check_max_distance_and_certify([&](const Options& o) { return sphere.project({0, 0, 5}, o); }, 4.0);
  // a point on the surface: distance 0 to rounding, certified within the absolute gap
  const Vec3 on{0.6, 0, 0.8};
  const ProjectionResult r = sphere.project(on);
  REQUIRE(r.summary.status == Status::converged);
  CHECK(r.distance <= 1e-15);
  CHECK(r.summary.certificate.certified);
}

}  // namespace surface_auto_test
