// The certificate of a surface answer given as it is (parametric/solvers/surface_certificate.hpp:
// certify_answer, what a paper's method gets with options.certify): a local minimum that is not
// the global one is never certified - the check can fail - and is mostly refuted outright (a
// point nearer by more than the gap found); the global answer is certified, with a lower bound
// within the gap. On a rippled plane with many local minima and on the [GSA] Example 1 surface.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "parametric/solvers/projected_newton.hpp"
#include "parametric/solvers/surface_certificate.hpp"
#include "parametric/solvers/surface_convergence.hpp"
#include "surface_fixtures.hpp"

using namespace footpoint;
using namespace footpoint::test;

namespace {

struct LocalMinimum {
  double u, v, distance;
};

// Every distinct local minimum that projected Newton reaches from a grid of starts.
std::vector<LocalMinimum> local_minima(const ParametricSurface& g, const Vec3& p) {
  const ParamBox b = g.domain();
  const auto criteria = surface::convergence_criteria(Options{}, b, surface::kLocalMaxIterations);
  std::vector<LocalMinimum> out;
  constexpr int n = 24;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) {
      const auto s = surface::projected_newton(g.formulas(), b, p, b.umin + (b.umax - b.umin) * i / n,
                                               b.vmin + (b.vmax - b.vmin) * j / n, criteria);
      if (s.status != Status::converged) continue;
      const bool seen = std::any_of(out.begin(), out.end(), [&](const LocalMinimum& m) {
        return std::abs(m.u - s.u) + std::abs(m.v - s.v) < 1e-6;
      });
      if (!seen) out.push_back({s.u, s.v, s.distance});
    }
  std::sort(out.begin(), out.end(),
            [](const LocalMinimum& a, const LocalMinimum& b) { return a.distance < b.distance; });
  return out;
}

}  // namespace

TEST_CASE("a local minimum given as the answer is never certified, the global one is") {
  const auto wavy = make_surface("u", "v", "0.2*sin(7*u)*sin(5*v)", {-2, 2}, {-2, 2});
  const auto gsa = make_surface("u+v", "sin(u)+2*cos(v)", "sin(u+v)", {-3, 3}, {-3, 3});
  int refuted = 0, worse = 0, global_certified = 0;
  for (const auto& [g, point] :
       {std::pair{wavy, Vec3{0.05, 0.1, -0.28}}, std::pair{wavy, Vec3{0.4, -0.3, 0.27}},
        std::pair{wavy, Vec3{-0.8, 0.9, -0.3}}, std::pair{gsa, Vec3{1.0, 2.0, 2.0}},
        std::pair{gsa, Vec3{-1.5, 0.5, 1.0}}, std::pair{gsa, Vec3{2.0, -1.0, 3.0}},
        std::pair{gsa, Vec3{0.5, 0.5, -2.0}}}) {
    const Vec3 p = point;  // (clang 14 lambdas, as INFO's, cannot capture a structured binding)
    const std::vector<LocalMinimum> minima = local_minima(*g, p);
    INFO("p = (" << p.x << ", " << p.y << ", " << p.z << "): " << minima.size() << " local minima");
    REQUIRE(!minima.empty());
    const double global = minima.front().distance;
    const ProjectionResult r = project(*g, {p.x, p.y, p.z}, "auto");
    CHECK(r.distance <= global * (1.0 + 1e-12));
    for (const LocalMinimum& m : minima) {
      const Certificate c = surface::certify_answer(g->cells(), g->formulas(), g->domain(), p, m.u, m.v);
      REQUIRE(c.computed);
      CHECK(c.lower_bound <= global * (1.0 + 1e-15));
      if (m.distance > global * (1.0 + 1e-6)) {
        ++worse;
        CHECK_FALSE(c.certified);
        refuted += c.reason == CertificateReason::nearer_point;
      } else {
        global_certified += c.certified;
      }
    }
  }
  MESSAGE(worse << " worse local minima, " << refuted << " refuted by a nearer point");
  CHECK(worse >= 6);
  CHECK(refuted * 10 >= worse * 8);
  CHECK(global_certified >= 3);
}

TEST_CASE("a paper's method certified on request") {
  const auto g = make_surface("u+v", "sin(u)+2*cos(v)", "sin(u+v)", {-3, 3}, {-3, 3});
  const std::array<double, 3> p{1.0, 2.0, 2.0};
  const ProjectionResult a = project(*g, p, "auto");
  Options o;
  o.certify = true;
  // from the global foot's parameters Newton stays there: certified
  o.initial = {{a.params[0], a.params[1], 0.0}};
  const ProjectionResult at_global = g->project(p.data(), "newton", o).value();
  REQUIRE(at_global.summary.certificate.computed);
  CHECK(at_global.distance == doctest::Approx(a.distance).epsilon(1e-12));
  CHECK(at_global.summary.certificate.certified);
  // from (1, 2), the [GSA] paper's start, Newton converges to a local minimum only: refuted
  o.initial = {{1.0, 2.0, 0.0}};
  const ProjectionResult local = g->project(p.data(), "newton", o).value();
  REQUIRE(local.summary.certificate.computed);
  CHECK(local.distance > a.distance * 1.1);
  CHECK_FALSE(local.summary.certificate.certified);
  CHECK(local.summary.certificate.reason == CertificateReason::nearer_point);
  // without the option: no certificate
  const ProjectionResult plain = g->project(p.data(), "newton", Options{}).value();
  CHECK_FALSE(plain.summary.certificate.computed);
}

namespace {

// The quadratic B-spline on [0, 3] (knots 0, 1, 2, 3), piece k on [k, k + 1]: C^1, its pieces
// t^2/2, (-2t^2 + 6t - 3)/2, (3 - t)^2/2. As written text in `var` and as a number.
std::string spline_piece(int k, const std::string& t) {
  switch (k) {
    case 0:
      return "(" + t + "^2/2)";
    case 1:
      return "((-2*" + t + "^2+6*" + t + "-3)/2)";
    default:
      return "((3-" + t + ")^2/2)";
  }
}
double spline(double t) {
  if (t < 1) return t * t / 2;
  if (t < 2) return (-2 * t * t + 6 * t - 3) / 2;
  return (3 - t) * (3 - t) / 2;
}

// z = B(u) B(v) on [0, 3]^2, written as a 3 x 3-patch piecewise polynomial with ?:, each patch the
// product of its pieces: u < 1 ? (v < 1 ? p00 : v < 2 ? p01 : p02) : u < 2 ? (...) : (...).
std::string patches() {
  auto row = [](int i) {
    return "(v<1?" + spline_piece(i, "u") + "*" + spline_piece(0, "v") + ":v<2?" + spline_piece(i, "u") +
           "*" + spline_piece(1, "v") + ":" + spline_piece(i, "u") + "*" + spline_piece(2, "v") + ")";
  };
  return "u<1?" + row(0) + ":u<2?" + row(1) + ":" + row(2);
}

// The distance from p to the surface by brute force on the closed form: a 600 x 600 grid, then
// the best grid point refined by a shrinking pattern search (independent of the library).
double brute_distance(const Vec3& p) {
  auto d2 = [&](double u, double v) {
    const double dz = spline(u) * spline(v) - p.z;
    return (u - p.x) * (u - p.x) + (v - p.y) * (v - p.y) + dz * dz;
  };
  double bu = 0, bv = 0, best = d2(0, 0);
  constexpr int n = 600;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) {
      const double u = 3.0 * i / n, v = 3.0 * j / n, d = d2(u, v);
      if (d < best) best = d, bu = u, bv = v;
    }
  for (double h = 3.0 / n; h > 1e-13; h *= 0.5)
    for (bool moved = true; moved;) {
      moved = false;
      for (const auto& [du, dv] : {std::pair{h, 0.0}, {-h, 0.0}, {0.0, h}, {0.0, -h}}) {
        const double u = std::clamp(bu + du, 0.0, 3.0), v = std::clamp(bv + dv, 0.0, 3.0), d = d2(u, v);
        if (d < best) best = d, bu = u, bv = v, moved = true;
      }
    }
  return std::sqrt(best);
}

}  // namespace

TEST_CASE(
    "a piecewise polynomial written with ?: is certified: the branches bound the boxes its switches cross") {
  const auto g = make_surface("u", "v", patches(), {0, 3}, {0, 3});
  int certified = 0, n = 0;
  for (const Vec3 p : {Vec3{1.5, 1.5, 1.2}, Vec3{0.9, 1.1, 0.6}, Vec3{1.0, 2.0, -0.3}, Vec3{2.4, 0.7, 0.9},
                       Vec3{0.3, 0.4, 0.5}, Vec3{2.0, 2.0, 0.8}, Vec3{1.7, 0.2, -0.5}, Vec3{2.9, 2.6, 1.0}}) {
    INFO("p = (" << p.x << ", " << p.y << ", " << p.z << ")");
    const ProjectionResult r = project(*g, {p.x, p.y, p.z}, "auto", Options{});
    ++n;
    CHECK(r.summary.status == Status::converged);
    CHECK(r.distance == doctest::Approx(brute_distance(p)).epsilon(1e-9));
    const Certificate& c = r.summary.certificate;
    CHECK(c.reason != CertificateReason::non_finite);  // the formulas are finite everywhere
    CHECK(c.lower_bound <= r.distance);
    CHECK(c.certified);
    certified += c.certified;
  }
  CHECK(certified == n);
}
