// Implicit curves whose equations are products of factors defined everywhere are searched and
// certified as the union of the factors' curves (ImplicitCurve::factors,
// formula::Program::factor_systems), against distances computed independently in closed form:
// two tangent circles (a tacnode of the product), two concentric circles in space, two crossing
// lines. The point where two factor curves meet is a singular point of the union.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "compiled/implicit_curve_geometry.hpp"
#include "implicit/solvers/implicit_curve_certificate.hpp"
#include "implicit_fixtures.hpp"

using namespace footpoint;

namespace {

using test::implicit_curve;

const ImplicitCurve& implicit(const std::shared_ptr<const CompiledGeometry>& g) {
  return dynamic_cast<const ImplicitCurve&>(*g);
}

// Answers of `auto` at random points against `exact`: the distance to 1e-12, L <= exact <= d,
// and the share certified (points where `skip` holds are left out: p at a circle's centre).
template <class Exact, class Skip>
void check_answers(const CompiledGeometry& g, const std::vector<std::array<double, 2>>& box, Exact&& exact,
                   Skip&& skip) {
  std::mt19937_64 rng(11);
  int n = 0, certified = 0;
  for (int i = 0; i < 400; ++i) {
    std::array<double, 3> p{};
    for (std::size_t k = 0; k < box.size(); ++k)
      p[k] = std::uniform_real_distribution<double>(box[k][0], box[k][1])(rng);
    if (skip(p)) continue;
    ++n;
    CAPTURE(p);
    const double e = exact(p);
    const ProjectionResult r = g.project(p.data(), "auto", {}).value();
    CHECK(r.summary.status == Status::converged);
    CHECK(std::abs(r.distance - e) <= 1e-12 * (1.0 + e));
    const Certificate& c = r.summary.certificate;
    CHECK(c.computed);
    CHECK(c.lower_bound <= e * (1.0 + 0x1p-50));
    certified += c.certified ? 1 : 0;
  }
  CHECK(certified >= 0.99 * n);
}

}  // namespace

TEST_CASE("two tangent circles: two factor curves, searched and certified, the tangency a singular point") {
  const std::vector<std::array<double, 2>> box{{-2.0, 4.0}, {-2.0, 2.0}};
  const auto g = implicit_curve({"(x^2+y^2-1)*((x-2)^2+y^2-1)"}, box);
  REQUIRE(implicit(g).factors().size() == 2);
  const auto to_a = [](const std::array<double, 3>& p) { return std::hypot(p[0], p[1]); };
  const auto to_b = [](const std::array<double, 3>& p) { return std::hypot(p[0] - 2.0, p[1]); };
  check_answers(
      *g, box, [&](const auto& p) { return std::min(std::abs(to_a(p) - 1.0), std::abs(to_b(p) - 1.0)); },
      [&](const auto& p) { return to_a(p) < 0.05 || to_b(p) < 0.05; });

  // The tangency (1, 0) lies on both circles: a singular point of the curve.
  const double inside[2] = {0.5, 0.0};
  const ProjectionResult at = g->project(inside, "auto", {}).value();
  CHECK(std::abs(at.foot[0] - 1.0) <= 1e-12);
  CHECK(std::abs(at.foot[1]) <= 1e-12);
  CHECK(at.summary.location == Location::singular_point);
  CHECK(at.summary.certificate.certified);
  // Above it, one nearest point on each circle at the same distance.
  const double above[2] = {1.0, 0.3};
  const ProjectionResult tie = g->project(above, "auto", {}).value();
  CHECK(tie.summary.location == Location::interior);
  CHECK(tie.summary.multiplicity.kind == Multiplicity::tied);
  CHECK(tie.summary.multiplicity.feet.size() == 2);
}

TEST_CASE("a wrong answer on one factor curve is refuted by the other's bound") {
  const std::vector<std::array<double, 2>> box{{-2.0, 4.0}, {-2.0, 2.0}};
  const auto g = implicit_curve({"(x^2+y^2-1)*((x-2)^2+y^2-1)"}, box);
  const ImplicitCurve& curve = implicit(g);
  // p = (1.6, 0.2): the circle about (2, 0) is nearer (sqrt(0.2) - 1 against |p| - 1).
  const Vec3 p{1.6, 0.2, 0.0};
  const double to_b = std::abs(std::hypot(0.4, 0.2) - 1.0);
  const double r = std::hypot(1.6, 0.2);
  const Vec3 on_a{1.6 / r, 0.2 / r, 0.0};  // the nearest point of the farther circle
  const Certificate wrong =
      curve::certify_implicit_curve_answer(curve.factors(), curve.box(), p, on_a, r - 1.0);
  CHECK(wrong.computed);
  CHECK_FALSE(wrong.certified);
  CHECK(wrong.lower_bound <= to_b);
  const double s = std::hypot(-0.4, 0.2);
  const Vec3 on_b{2.0 - 0.4 / s, 0.2 / s, 0.0};
  const Certificate right = curve::certify_implicit_curve_answer(curve.factors(), curve.box(), p, on_b, to_b);
  CHECK(right.certified);
  CHECK(right.lower_bound <= to_b);
  // A papers' method asked for a certificate gets the union's.
  Options o;
  o.certify = true;
  const double q[2] = {1.6, 0.2};
  const ProjectionResult t = g->project(q, "tangent_foot", o).value();
  CHECK(t.summary.certificate.computed);
  CHECK(t.summary.certificate.lower_bound <= to_b * (1.0 + 0x1p-50));
}

TEST_CASE("two concentric circles in a plane of space: two factor curves") {
  const std::vector<std::array<double, 2>> box{{-3.0, 3.0}, {-3.0, 3.0}, {-3.0, 3.0}};
  const auto g = implicit_curve({"(x^2+y^2+z^2-4)*(x^2+y^2+z^2-1)", "z-0.5"}, box);
  REQUIRE(implicit(g).factors().size() == 2);
  const double radii[2] = {std::sqrt(3.75), std::sqrt(0.75)};
  check_answers(
      *g, box,
      [&](const auto& p) {
        const double rho = std::hypot(p[0], p[1]);
        return std::min(std::hypot(rho - radii[0], p[2] - 0.5), std::hypot(rho - radii[1], p[2] - 0.5));
      },
      [](const auto& p) { return std::hypot(p[0], p[1]) < 0.05; });
}

TEST_CASE("two crossing lines: the crossing is a singular point; factors without points are dropped") {
  const std::vector<std::array<double, 2>> box{{-1.0, 1.2}, {-1.0, 1.1}};
  const auto g = implicit_curve({"x*y"}, box);
  REQUIRE(implicit(g).factors().size() == 2);
  check_answers(
      *g, box, [](const auto& p) { return std::min(std::abs(p[0]), std::abs(p[1])); },
      [](const auto&) { return false; });
  const double origin[2] = {0.0, 0.0};
  const ProjectionResult r = g->project(origin, "auto", {}).value();
  CHECK(r.distance == 0.0);
  CHECK(r.summary.location == Location::singular_point);

  // x^2 + y^2 + 1 has no real zero and the second circle lies outside the box: one factor curve.
  const auto one = implicit_curve({"(x^2+y^2+1)*(x^2+y^2-1)*((x-10)^2+y^2-1)"}, {{-2.0, 2.0}, {-2.0, 2.0}});
  CHECK(implicit(one).factors().size() == 1);
  const double p[2] = {0.3, 1.5};
  const ProjectionResult c = one->project(p, "auto", {}).value();
  CHECK(std::abs(c.distance - (std::hypot(0.3, 1.5) - 1.0)) <= 1e-14);
  CHECK(c.summary.certificate.certified);
}
