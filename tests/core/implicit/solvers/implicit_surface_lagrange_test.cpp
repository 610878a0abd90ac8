// implicit/solvers/implicit_surface_lagrange: Newton on the Lagrange system of the foot point,
// inside the box and on a face, and the second-order and result helpers, against closed forms:
//  - at the answer the stationarity conditions hold to 1e-12 relative (X - p + l grad f = 0,
//    f = 0; on the face x_k = c also X_k = c exactly), X is the closed-form foot (sphere R p / |p|,
//    Eberly's ellipsoid foot, the torus' meridian foot, the circle a sphere cuts on a face, the
//    line a plane cuts on a face), and the multiplier is the closed form's: on the sphere
//    f = |X|^2 - R^2, X (1 + 2 l) = p gives l = (|p| / R - 1) / 2;
//  - steps longer than max_step are shortened, and the solve gives up after 8 of them;
//  - the tangent form of I + l H has the trace and determinant of the restriction to the plane
//    normal to n (trace A - n.A n, n.adj(A) n), and the cylinder's and sphere's least eigenvalues;
//  - box_location and implicit_surface_result by hand.
#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "implicit/solvers/implicit_surface_lagrange.hpp"
#include "implicit_fixtures.hpp"
#include "implicit_surface_truths.hpp"

using namespace footpoint;
using namespace footpoint::surface_implicit;

namespace implicit_surface_lagrange_test {

curve::IterationControl newton_control() {
  curve::IterationControl c;
  c.max_iterations = 50;
  return c;
}

// Newton from `start` to the closed-form `foot` of p on f = 0: converged there (within `close`),
// with |X - p + l grad f| and |f| / |grad f| below 1e-12 relative to max(1, |X|, |p|).
SurfaceMinimum check_reaches(const ImplicitSurfaceEquation& f, Vec3 p, Vec3 foot, Vec3 start, double close) {
  const SurfaceMinimum m = lagrange_newton_interior(f, p, start, curve::kInfinity, newton_control());
  CHECK(m.converged);
  CHECK(norm(m.x - foot) <= close);
  const ImplicitSurfaceJet j = f.jet(m.x);
  const double scale = std::max({1.0, norm(m.x), norm(p)});
  CHECK(norm(m.x - p + m.multiplier * j.grad) <= 1e-12 * scale);
  CHECK(std::fabs(j.f) / norm(j.grad) <= 1e-12 * scale);
  return m;
}

TEST_CASE("implicit surface lagrange: interior Newton reaches the closed-form feet, stationary") {
  const curve::IterationControl control = newton_control();
  std::mt19937 rng(37);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  auto near = [&](Vec3 foot, double offset) { return foot + offset * Vec3{u(rng), u(rng), u(rng)}; };
  const ImplicitSurfaceEquation sphere = test::surface_equation("x^2+y^2+z^2-4");
  const ImplicitSurfaceEquation ellipsoid = test::surface_equation("x^2/4+y^2+4*z^2-1");
  const ImplicitSurfaceEquation torus = test::surface_equation("(x^2+y^2+z^2+3.75)^2-16*(x^2+y^2)");
  for (int i = 0; i < 20; ++i) {
    CAPTURE(i);
    // Sphere of radius 2: the foot 2 p / |p|, the multiplier (|p| / 2 - 1) / 2; started 0.05 away.
    const Vec3 p = 3.0 * Vec3{u(rng), u(rng), u(rng)};
    const Vec3 foot = (2.0 / norm(p)) * p;
    const SurfaceMinimum m = check_reaches(sphere, p, foot, near(foot, 0.05), 2e-14);
    CHECK(std::fabs(m.multiplier - (norm(p) / 2.0 - 1.0) / 2.0) <= 1e-13);
    CHECK(m.iterations <= 8);  // quadratic from 0.05 away
    // Ellipsoid x^2/4 + y^2 + 4 z^2 = 1 (semi-axes 2, 1, 0.5): Eberly's foot by bisection.
    const Vec3 q{2.5 * u(rng), 1.5 * u(rng), 1.0 * u(rng)};
    const Vec3 on_ellipsoid = test::ellipsoid_foot({2.0, 1.0, 0.5}, q);
    check_reaches(ellipsoid, q, on_ellipsoid, near(on_ellipsoid, 0.02), 1e-12);
    // Torus of radii 2 and 0.5: the meridian foot (p off the axis).
    const Vec3 r{3.0 * u(rng), 3.0 * u(rng), 1.0 * u(rng)};
    if (std::hypot(r.x, r.y) < 0.5) continue;
    const Vec3 on_torus = test::torus_foot(2.0, 0.5, r);
    check_reaches(torus, r, on_torus, near(on_torus, 0.02), 1e-12);
  }
  // No gradient at the start (the sphere's centre): nothing to solve, not converged.
  const SurfaceMinimum none =
      lagrange_newton_interior(sphere, {1, 1, 1}, {0, 0, 0}, curve::kInfinity, control);
  CHECK(!none.converged);
  CHECK(none.iterations == 0);
}

TEST_CASE("implicit surface lagrange: steps are shortened to max_step, and 8 of them end the solve") {
  const ImplicitSurfaceEquation sphere = test::surface_equation("x^2+y^2+z^2-1");
  const curve::IterationControl control = newton_control();
  const Vec3 p{3.0, 0.2, 0.1}, x0{0.0, 1.0, 0.0};
  // Unlimited: the foot p / |p| (the start lies in its basin).
  const SurfaceMinimum free = lagrange_newton_interior(sphere, p, x0, curve::kInfinity, control);
  REQUIRE(free.converged);
  CHECK(norm(free.x - p / norm(p)) <= 1e-15);
  // Steps of at most 1e-3 from 1.4 away: the ninth shortened step ends the solve, after 8 steps of
  // exactly 1e-3.
  const SurfaceMinimum limited = lagrange_newton_interior(sphere, p, x0, 1e-3, control);
  CHECK(!limited.converged);
  CHECK(limited.iterations == 8);
  CHECK(limited.step == doctest::Approx(1e-3).epsilon(1e-12));
  CHECK(norm(limited.x - x0) <= 8e-3 * (1.0 + 1e-12));
}

TEST_CASE("implicit surface lagrange: on a face, the foot on the curve the face cuts") {
  const curve::IterationControl control = newton_control();
  std::mt19937 rng(41);
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  // The sphere |X| = 2 on the face z = 1: the circle of radius sqrt(3) about (0, 0, 1), foot
  // sqrt(3) (p_x, p_y) / |(p_x, p_y)| (implicit_fixtures.hpp); in the plane,
  // (X - p) + 2 l X = 0 gives l = (|(p_x, p_y)| / sqrt(3) - 1) / 2.
  const ImplicitSurfaceEquation sphere = test::surface_equation("x^2+y^2+z^2-4");
  for (int i = 0; i < 20; ++i) {
    const Vec3 p{u(rng), u(rng), u(rng)};
    const Vec3 foot = test::circle_foot(p);
    const SurfaceMinimum m =
        lagrange_newton_face(sphere, p, foot + Vec3{0.03, -0.02, 0.4}, 2, 1.0, curve::kInfinity, control);
    CAPTURE(i);
    REQUIRE(m.converged);
    CHECK(m.x.z == 1.0);
    CHECK(norm(m.x - foot) <= 1e-14 * 2.0);
    const double rho = std::hypot(p.x, p.y);
    CHECK(std::fabs(m.multiplier - (rho / test::kCircleRadius - 1.0) / 2.0) <= 1e-12 * (1.0 + rho));
    // p - X = l grad f + m e_z: its part in the face's plane is l grad f's.
    const ImplicitSurfaceJet j = sphere.jet(m.x);
    CHECK(std::hypot(m.x.x - p.x + m.multiplier * j.grad.x, m.x.y - p.y + m.multiplier * j.grad.y) <=
          1e-12 * 3.0);
  }
  // The plane x + y + z = 1 on the face x = 0.25: the line y + z = 0.75, x = 0.25, whose foot is
  // p's projection onto it.
  const ImplicitSurfaceEquation plane = test::surface_equation("x+y+z-1");
  const Vec3 p{2.0, -1.0, 0.5};
  const Vec3 a{0.25, 0.75, 0.0}, d = Vec3{0.0, -1.0, 1.0} / std::sqrt(2.0);
  const Vec3 foot = a + dot(p - a, d) * d;
  const SurfaceMinimum m =
      lagrange_newton_face(plane, p, {0.0, 0.0, 0.0}, 0, 0.25, curve::kInfinity, control);
  REQUIRE(m.converged);
  CHECK(m.x.x == 0.25);
  CHECK(norm(m.x - foot) <= 1e-15);
  CHECK(m.iterations <= 3);  // a linear system: exact in one step, then a zero step
}

TEST_CASE("implicit surface lagrange: the tangent form of the Lagrangian's Hessian") {
  // Any symmetric A and unit n: the form on the plane normal to n in an orthonormal basis has the
  // trace tr A - n.A n and the determinant n.adj(A) n (the (3, 3) cofactor in a basis completing
  // the plane's with n).
  std::mt19937 rng(43);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  for (int i = 0; i < 50; ++i) {
    Mat3 a;
    for (int r = 0; r < 3; ++r)
      for (int c = r; c < 3; ++c) a[r][c] = a[c][r] = u(rng);
    Vec3 n{u(rng), u(rng), u(rng)};
    n = n / norm(n);
    Mat3 adj;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) {
        const int r1 = (r + 1) % 3, r2 = (r + 2) % 3, c1 = (c + 1) % 3, c2 = (c + 2) % 3;
        adj[c][r] = a[r1][c1] * a[r2][c2] - a[r1][c2] * a[r2][c1];
      }
    const TangentForm t = tangent_form(a, n);
    CAPTURE(i);
    CHECK(t.a11 + t.a22 == doctest::Approx(a[0][0] + a[1][1] + a[2][2] - dot(n, a * n)).epsilon(1e-12));
    CHECK(t.a11 * t.a22 - t.a12 * t.a12 == doctest::Approx(dot(n, adj * n)).epsilon(1e-11).scale(10.0));
    // The least eigenvalue is a root of the form's characteristic polynomial, the lesser one.
    const double e = t.least_eigenvalue();
    CHECK((t.a11 - e) * (t.a22 - e) - t.a12 * t.a12 == doctest::Approx(0.0).scale(10.0).epsilon(1e-12));
    CHECK(e <= std::min(t.a11, t.a22) + 1e-15);
  }
  // The cylinder x^2 + y^2 = 1 (H = diag(2, 2, 0)) at X = (1, 0, 0), p = (s, 0, 0):
  // l = (s - 1) / 2, I + l H = diag(s, s, 1), on the tangent plane (y, z) eigenvalues s and 1.
  const ImplicitSurfaceEquation cylinder = test::surface_equation("x^2+y^2-1");
  const ImplicitSurfaceJet j = cylinder.jet({1, 0, 0});
  for (const double s : {0.0, 0.4, 3.0}) {
    const Mat3 a = lagrangian_hessian(j, (s - 1.0) / 2.0);
    CHECK(a[0][0] == doctest::Approx(s).epsilon(1e-15));
    CHECK(a[1][1] == doctest::Approx(s).epsilon(1e-15));
    CHECK(a[2][2] == 1.0);
    CHECK(a[0][1] == 0.0);
    CHECK(tangent_form(a, {1, 0, 0}).least_eigenvalue() == doctest::Approx(std::min(s, 1.0)).epsilon(1e-15));
  }
  // The unit sphere from its centre: l = -1/2, I + l H = 0, flat in every direction.
  const ImplicitSurfaceEquation sphere = test::surface_equation("x^2+y^2+z^2-1");
  const Vec3 x = Vec3{1.0, 2.0, 2.0} / 3.0;
  const TangentForm flat = tangent_form(lagrangian_hessian(sphere.jet(x), -0.5), x);
  CHECK(std::fabs(flat.least_eigenvalue()) <= 1e-15);
}

TEST_CASE("implicit surface lagrange: box_location and the result's residuals by hand") {
  const Box3 box{{0, 0, 0}, {2, 2, 2}};
  CHECK(box_location(box, {1, 1, 1}) == Location::interior);
  CHECK(box_location(box, {0, 1, 1}) == Location::box_face);
  CHECK(box_location(box, {2, 1, 0}) == Location::box_edge);
  CHECK(box_location(box, {0, 2, 0}) == Location::box_corner);
  CHECK(box_location(box, {1e-9, 1, 1}) == Location::interior);
  CHECK(box_location(box, {1e-9, 1, 1}, 1e-8) == Location::box_face);
  // The unit sphere in [-2, 2]^2 x [0, 2].
  const ImplicitSurfaceEquation sphere = test::surface_equation("x^2+y^2+z^2-1");
  const Box3 half{{-2, -2, 0}, {2, 2, 2}};
  // At the foot of p: the distance, residual 0, orthogonality 0, interior.
  const Vec3 p{1.2, 1.6, 0.0};
  const ProjectionResult at = implicit_surface_result(sphere, half, 2.0 * p, p / 2.0, "test");
  CHECK(at.distance == doctest::Approx(norm(2.0 * p - p / 2.0)).epsilon(1e-15));
  CHECK(at.summary.method == "test");
  CHECK(at.summary.location == Location::box_face);  // z = 0 is the box's lower face
  CHECK(at.summary.on_boundary);
  CHECK(at.summary.orthogonality[0] <= 1e-15);
  CHECK(at.summary.equation_residual[0] <= 1e-16);
  // Not the foot: p = (2, 0, 1), X = (0, 0.6, 0.8) inside the box, p - X = (2, -0.6, 0.2),
  // grad f = (0, 1.2, 1.6): the sine |(p - X) x grad f| / (|p - X| |grad f|).
  const Vec3 q{2.0, 0.0, 1.0}, x{0.0, 0.6, 0.8};
  const ProjectionResult off = implicit_surface_result(sphere, half, q, x, "test");
  CHECK(off.summary.location == Location::interior);
  CHECK(!off.summary.on_boundary);
  const Vec3 d = q - x, g{0.0, 1.2, 1.6};
  CHECK(off.summary.orthogonality[0] ==
        doctest::Approx(norm(cross(d, g)) / (norm(d) * norm(g))).epsilon(1e-15));
  // A point off the surface, (0, 1.5, 0.5): f = 2.25 + 0.25 - 1 = 1.5, |grad f| = |(0, 3, 1)| =
  // sqrt(10).
  const ProjectionResult away = implicit_surface_result(sphere, half, q, {0.0, 1.5, 0.5}, "test");
  CHECK(away.summary.equation_residual[0] == doctest::Approx(1.5 / std::sqrt(10.0)).epsilon(1e-15));
  // On an edge of the box the foot cannot move along the surface: orthogonality 0 by definition.
  const ProjectionResult edge =
      implicit_surface_result(sphere, {{-2, -2, 0}, {2, 1, 2}}, q, {0, 1, 0}, "test");
  CHECK(edge.summary.location == Location::box_edge);
  CHECK(edge.summary.orthogonality[0] == 0.0);
}

}  // namespace implicit_surface_lagrange_test
