// implicit/solvers/implicit_surface_methods: the literature's local methods for implicit surfaces,
// each on cases whose foot is known in closed form, and their documented statuses:
//  - curvature_circle_foot (Hu-Wallner's steps (1)-(4)): on a sphere the normal section is a
//    great circle, whose point nearest p is R p / |p|; on the cylinder x^2 + y^2 = 1 the section
//    along the axis is a line (curvature 0: the tangent-plane foot) and across it the unit circle;
//  - Hartmann's iteration: exact in one step on a plane; on a sphere of radius 1 with p = s u
//    (|u| = 1) the next surface point's angle to u is -(s - 1) times the last one's to first
//    order, the rate |s - 1| = distance / radius of curvature, measured on the steps; beyond the
//    centre of curvature (|s - 1| > 1) it does not settle;
//  - Hu-Wallner's iteration on the cylinder off its planes of symmetry: the closed-form foot
//    ((p_x, p_y) / |(p_x, p_y)|, p_z);
//  - the three methods: converged at the closed-form foot (Eberly's on an ellipsoid), the
//    stationary point of the start's basin (a maximum of the distance) for lagrange_newton,
//    degenerate from a point with no gradient, outside_domain for a foot outside the box,
//    max_iterations, beyond_max_distance (the answer withheld), and the trace summing to the path.
#include <doctest/doctest.h>

#include <cmath>
#include <string>
#include <vector>

#include "implicit/solvers/implicit_surface_methods.hpp"
#include "implicit_surface_truths.hpp"

using namespace footpoint;
using namespace footpoint::surface_implicit;

namespace implicit_surface_methods_test {

const Box3 kWide{{-4, -4, -4}, {4, 4, 4}};

Options from(Vec3 start) {
  Options o;
  o.initial = std::array<double, 3>{start.x, start.y, start.z};
  return o;
}

Vec3 foot_of(const ProjectionResult& r) { return {r.foot[0], r.foot[1], r.foot[2]}; }

// The sum of a traced method's increments.
Vec3 traced_path(const ProjectionResult& r) {
  Vec3 s{0.0, 0.0, 0.0};
  for (const auto& d : r.trace) s += Vec3{d[0], d[1], d[2]};
  return s;
}

TEST_CASE("implicit surface methods: the curvature circle's foot on a sphere and a cylinder") {
  const ImplicitSurfaceEquation sphere = test::surface_equation("x^2+y^2+z^2-4");
  const Vec3 x = Vec3{2.0, 1.0, -2.0} * (2.0 / 3.0);
  for (const Vec3 p : {Vec3{1.0, 2.5, -0.5}, Vec3{-3.0, 0.2, 0.4}, Vec3{0.3, 0.1, 0.2}}) {
    Vec3 q;
    REQUIRE(curvature_circle_foot(sphere.jet(x), x, p, q));
    CHECK(norm(q - (2.0 / norm(p)) * p) <= 1e-15 * 4.0);
  }
  const ImplicitSurfaceEquation cylinder = test::surface_equation("x^2+y^2-1");
  const Vec3 c{1.0, 0.0, 0.0};
  Vec3 q;
  // Along the axis: the section is the line through c, the tangent-plane foot (1, 0, p_z).
  REQUIRE(curvature_circle_foot(cylinder.jet(c), c, {2.5, 0.0, -0.7}, q));
  CHECK(norm(q - Vec3{1.0, 0.0, -0.7}) <= 1e-15);
  // Across it: the unit circle, the foot (p_x, p_y) / |(p_x, p_y)|.
  REQUIRE(curvature_circle_foot(cylinder.jet(c), c, {0.3, -2.0, 0.0}, q));
  CHECK(norm(q - Vec3{0.3, -2.0, 0.0} / std::hypot(0.3, 2.0)) <= 1e-15);
  // p on the normal line (the sphere's centre, the cylinder's axis among them): x is stationary,
  // q = x.
  REQUIRE(curvature_circle_foot(cylinder.jet(c), c, {3.0, 0.0, 0.0}, q));
  CHECK(norm(q - c) == 0.0);
  REQUIRE(curvature_circle_foot(cylinder.jet(c), c, {0.0, 0.0, 0.0}, q));
  CHECK(norm(q - c) == 0.0);
  REQUIRE(curvature_circle_foot(sphere.jet(x), x, {0.0, 0.0, 0.0}, q));
  CHECK(norm(q - x) <= 1e-15);
  // No gradient: no step.
  ImplicitSurfaceJet flat;
  flat.grad = {0.0, 0.0, 0.0};
  CHECK(!curvature_circle_foot(flat, c, {3.0, 1.0, 0.0}, q));
}

TEST_CASE("implicit surface methods: Hartmann's iteration, exact on a plane, rate |s - 1| on a sphere") {
  curve::IterationControl control;
  control.max_iterations = 500;
  // The plane x + 2y - 2z = 3: the tangent plane is the plane, the first step lands on the foot
  // p - (p.n - 3) / 9 n; the second moves 0 and stops.
  const ImplicitSurfaceEquation plane = test::surface_equation("x+2*y-2*z-3");
  const Vec3 p{1.0, -2.0, 4.0}, n{1.0, 2.0, -2.0};
  const HartmannEnd flat = hartmann_iteration(plane, p, {7.0, 1.0, 0.5}, control);
  CHECK(flat.status == Status::converged);
  CHECK(flat.iterations == 2);
  CHECK(norm(flat.x - (p - ((dot(p, n) - 3.0) / 9.0) * n)) <= 1e-15 * 8.0);
  // The unit sphere, p = s u: the steps shrink by |s - 1| each (p outside at 0.4, inside at 0.45).
  const ImplicitSurfaceEquation sphere = test::surface_equation("x^2+y^2+z^2-1");
  const Vec3 u = Vec3{2.0, -1.0, 2.0} / 3.0, start = Vec3{2.0, -0.2, 2.3};
  for (const double s : {1.4, 0.55}) {
    CAPTURE(s);
    std::vector<std::array<double, 3>> trace;
    curve::IterationControl traced = control;
    traced.trace = &trace;
    const HartmannEnd e = hartmann_iteration(sphere, s * u, start, traced);
    CHECK(e.status == Status::converged);
    CHECK(norm(e.x - u) <= 1e-14);
    int measured = 0;
    for (std::size_t k = 1; k < trace.size(); ++k) {
      const double last = std::hypot(trace[k - 1][0], trace[k - 1][1], trace[k - 1][2]);
      const double step = std::hypot(trace[k][0], trace[k][1], trace[k][2]);
      if (last > 1e-4 || step < 1e-10) continue;  // first order: the ratio is |s - 1| + O(angle)
      ++measured;
      CHECK(step / last == doctest::Approx(std::fabs(s - 1.0)).epsilon(1e-3));
    }
    CHECK(measured >= 5);
  }
  // Beyond the centre of curvature (s = 3.2, the rate 2.2 at the foot and 4.2 at the far point):
  // the surface points never settle.
  const HartmannEnd wild = hartmann_iteration(sphere, 3.2 * u, start, control);
  CHECK(wild.status == Status::max_iterations);
  CHECK(wild.iterations == control.max_iterations);
}

TEST_CASE("implicit surface methods: Hu-Wallner's iteration on a cylinder, off its symmetry planes") {
  // x^2 + y^2 = 1: the foot of p is ((p_x, p_y) / |(p_x, p_y)|, p_z). The normal section toward p
  // is an ellipse whose plane misses the foot: the rate is linear.
  const ImplicitSurfaceEquation cylinder = test::surface_equation("x^2+y^2-1");
  curve::IterationControl control;
  control.max_iterations = 500;
  for (const Vec3 p : {Vec3{2.0, 1.0, 0.5}, Vec3{-0.3, 0.4, -1.2}, Vec3{0.1, -3.0, 2.0}}) {
    CAPTURE(p.x);
    const HartmannEnd e = hu_wallner_iteration(cylinder, p, {1.0, 0.0, 0.0}, control);
    CHECK(e.status == Status::converged);
    const double r = std::hypot(p.x, p.y);
    CHECK(norm(e.x - Vec3{p.x / r, p.y / r, p.z}) <= 1e-13);
  }
}

TEST_CASE("implicit surface methods: each method converges at the closed-form foot") {
  // Ellipsoid x^2/4 + y^2 + 4 z^2 = 1, p near it: Eberly's foot (bisection on the secular
  // equation). Every method from p itself; the residuals met, the method named.
  const ImplicitSurfaceEquation ellipsoid = test::surface_equation("x^2/4+y^2+4*z^2-1");
  using Method = ProjectionResult (*)(const ImplicitSurfaceEquation&, const Box3&, Vec3, const Options&);
  const std::pair<const char*, Method> methods[] = {{"lagrange_newton", lagrange_newton_method},
                                                    {"first_order", first_order_method},
                                                    {"hu_wallner", hu_wallner_method}};
  for (const Vec3 p : {Vec3{1.5, 0.7, 0.2}, Vec3{-0.4, 0.9, -0.35}, Vec3{0.9, -0.5, 0.4}}) {
    const Vec3 foot = test::ellipsoid_foot({2.0, 1.0, 0.5}, p);
    for (const auto& named : methods) {
      const char* const name = named.first;
      const Method method = named.second;
      CAPTURE(std::string(name));
      CAPTURE(p.x);
      Options o;
      o.trace = true;
      const ProjectionResult r = method(ellipsoid, kWide, p, o);
      CHECK(r.summary.method == name);
      CHECK(r.summary.status == Status::converged);
      CHECK(norm(foot_of(r) - foot) <= 1e-12);
      CHECK(r.distance == doctest::Approx(norm(p - foot)).epsilon(1e-12));
      CHECK(r.summary.equation_residual[0] <= 1e-14);
      CHECK(r.summary.location == Location::interior);
      CHECK(!r.trace.empty());
      if (std::string(name) == "lagrange_newton") CHECK(norm(p + traced_path(r) - foot) <= 1e-14);
    }
  }
  // Unsafeguarded Newton converges to the stationary point its start's basin holds: from near the
  // far side of a sphere of radius 2, the farthest point -2 p / |p|, at |p| + 2.
  const ImplicitSurfaceEquation sphere = test::surface_equation("x^2+y^2+z^2-4");
  const Vec3 p{0.6, 0.3, -0.2};
  const ProjectionResult far = lagrange_newton_method(sphere, kWide, p, from(-3.0 * p));
  CHECK(far.summary.status == Status::converged);
  CHECK(norm(foot_of(far) + (2.0 / norm(p)) * p) <= 1e-14);
  CHECK(far.distance == doctest::Approx(norm(p) + 2.0).epsilon(1e-15));
}

TEST_CASE("implicit surface methods: degenerate, outside_domain, max_iterations, beyond_max_distance") {
  const ImplicitSurfaceEquation sphere = test::surface_equation("x^2+y^2+z^2-1");
  using Method = ProjectionResult (*)(const ImplicitSurfaceEquation&, const Box3&, Vec3, const Options&);
  for (const Method method : {lagrange_newton_method, first_order_method, hu_wallner_method}) {
    // From the centre, where grad f = 0: no step is defined.
    CHECK(method(sphere, kWide, {0.3, 0.2, 0.1}, from({0.0, 0.0, 0.0})).summary.status == Status::degenerate);
    // The foot -p / |p| lies outside the box [0, 2]^3: each method reaches it and says so.
    const Vec3 p{-0.9, -0.5, -0.3};
    const ProjectionResult out = method(sphere, {{0, 0, 0}, {2, 2, 2}}, p, {});
    CHECK(out.summary.status == Status::outside_domain);
    CHECK(norm(foot_of(out) - p / norm(p)) <= 1e-14);
    // An answer farther than max_distance is withheld.
    Options near;
    near.max_distance = 0.5;
    const ProjectionResult far = method(sphere, kWide, {2.0, 0.5, 0.1}, near);
    CHECK(far.summary.status == Status::beyond_max_distance);
    CHECK(std::isnan(far.distance));
    CHECK(std::isnan(far.foot[0]));
  }
  // Hartmann's iteration with p beyond the centre of curvature (at 3.2, the rate 2.2), from a start
  // off p's ray (from p itself the first landing is the foot p / |p|): its budget runs out.
  Options wild = from({2.0, -0.2, 2.3});
  wild.max_iterations = 300;
  const ProjectionResult w = first_order_method(sphere, kWide, Vec3{2.0, -1.0, 2.0} * (3.2 / 3.0), wild);
  CHECK(w.summary.status == Status::max_iterations);
  CHECK(w.summary.iterations == 300);
  // Newton from 3 away, allowed 2 iterations.
  Options short_budget = from({0.0, 3.0, 0.0});
  short_budget.max_iterations = 2;
  const ProjectionResult s = lagrange_newton_method(sphere, kWide, {1.2, 0.1, 0.0}, short_budget);
  CHECK(s.summary.status == Status::max_iterations);
  CHECK(s.summary.iterations == 2);
}

}  // namespace implicit_surface_methods_test
