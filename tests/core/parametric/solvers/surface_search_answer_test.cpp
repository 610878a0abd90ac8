// all_minima's parameter copies (Minimum::copies): every (u, v) of the domain known to give a foot
// point - across seams, along the closure's translations, and the folds the search solved -
// against the copies worked out by hand.
//  - The torus ((3 + cos v) cos u, (3 + cos v) sin u, sin v) over [0, 4π] x [0, 2π]: from (5, 0, 0)
//    the foot (4, 0, 0) is s(u, v) for u in {0, 2π, 4π} and v in {0, 2π}, six copies; from
//    (3, 3, 3) the foot has u in {π/4, π/4 + 2π} and one v, inside.
//  - [GSA] Ex. 1, s = (u + v, sin u + 2 cos v, sin(u + v)) over [-25, 25]^2: s(u', v') = s(u, v)
//    exactly when u' + v' = w := u + v and (1 + 2 sin w) sin u' + 2 cos w cos u' = sin u + 2 cos v
//    (the second coordinate with v' = w - u'): R sin(u' + φ) = c, with R = |(1 + 2 sin w, 2 cos w)|
//    and φ its angle, solved by u' = asin(c/R) - φ + 2πk and π - asin(c/R) - φ + 2πk. The copies
//    are those with u' and w - u' in the box.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "surface_fixtures.hpp"

using namespace footpoint;
using namespace footpoint::test;

namespace {

constexpr double kPeriod = 2 * std::numbers::pi;

// Each expected copy has exactly one listed copy within tol, and nothing else is listed.
void check_same_copies(const std::vector<std::array<double, 2>>& listed,
                       const std::vector<std::array<double, 2>>& expected, double tol) {
  CHECK(listed.size() == expected.size());
  for (const auto& e : expected) {
    CAPTURE(e[0]);
    CAPTURE(e[1]);
    CHECK(std::count_if(listed.begin(), listed.end(), [&](const std::array<double, 2>& c) {
            return std::abs(c[0] - e[0]) <= tol && std::abs(c[1] - e[1]) <= tol;
          }) == 1);
  }
  CHECK(std::is_sorted(listed.begin(), listed.end()));
}

}  // namespace

TEST_CASE("torus over two periods: the copies across both seams and along the translation") {
  const auto g =
      make_surface("(3+cos(v))*cos(u)", "(3+cos(v))*sin(u)", "sin(v)", {0, 2 * kPeriod}, {0, kPeriod});
  Options all;
  all.all_minima = true;
  const ProjectionResult r = project(*g, {5, 0, 0}, "auto", all);
  REQUIRE(r.summary.status == Status::converged);
  REQUIRE(r.minima.size() >= 1);
  const Minimum& m = r.minima[0];
  CHECK(m.distance == doctest::Approx(1.0).epsilon(1e-14));
  CHECK_FALSE(m.copies_truncated);
  check_same_copies(
      m.copies,
      {{0, 0}, {0, kPeriod}, {kPeriod, 0}, {kPeriod, kPeriod}, {2 * kPeriod, 0}, {2 * kPeriod, kPeriod}},
      1e-7);

  const ProjectionResult q = project(*g, {3, 3, 3}, "auto", all);
  REQUIRE(q.summary.status == Status::converged);
  const double v = std::atan2(3.0, std::hypot(3.0, 3.0) - 3.0);
  check_same_copies(q.minima[0].copies, {{std::numbers::pi / 4, v}, {std::numbers::pi / 4 + kPeriod, v}},
                    1e-7);
}

TEST_CASE("[GSA] Ex. 1 over [-25, 25]^2: every copy gives the foot point; the translates are all listed") {
  const auto g = make_surface("u+v", "sin(u)+2*cos(v)", "sin(u+v)", {-25, 25}, {-25, 25});
  Options all;
  all.all_minima = true;
  for (const std::array<double, 3> p :
       {std::array<double, 3>{0.3, 1.1, -0.4}, std::array<double, 3>{7, -2, 0.5},
        std::array<double, 3>{-20, 0.5, 2}}) {
    CAPTURE(p[0]);
    const ProjectionResult r = project(*g, p, "auto", all);
    REQUIRE(r.summary.status == Status::converged);
    REQUIRE(r.minima.size() >= 1);
    const Minimum& m = r.minima[0];
    CHECK_FALSE(m.copies_truncated);
    REQUIRE(!m.copies.empty());
    // Every listed copy is a copy: the same point of the surface, to rounding.
    for (const auto& c : m.copies) {
      const Vec3 s = g->formulas().point(c[0], c[1]);
      CHECK(std::hypot(s.x - m.foot[0], s.y - m.foot[1], s.z - m.foot[2]) <= 1e-12 * (1 + std::abs(s.x)));
    }
    // The copies worked out by hand, from the answer's (u, v).
    const double w = m.params[0] + m.params[1];
    const double c = std::sin(m.params[0]) + 2 * std::cos(m.params[1]);
    const double a = 1 + 2 * std::sin(w), b = 2 * std::cos(w);
    const double R = std::hypot(a, b), phi = std::atan2(b, a);
    std::vector<std::array<double, 2>> expected;
    for (const double base : {std::asin(c / R) - phi, std::numbers::pi - std::asin(c / R) - phi})
      for (int k = -10; k <= 10; ++k) {
        const double u = base + kPeriod * k;
        if (u >= -25 && u <= 25 && w - u >= -25 && w - u <= 25) expected.push_back({u, w - u});
      }
    // The translates of the answer, k (2π, -2π), are all listed; so are the fold's copies (the
    // search solves the fold's copy in the strip for these points, and its translates follow).
    const auto listed = [&](const std::array<double, 2>& e) {
      return std::any_of(m.copies.begin(), m.copies.end(), [&](const std::array<double, 2>& x) {
        return std::abs(x[0] - e[0]) <= 1e-7 && std::abs(x[1] - e[1]) <= 1e-7;
      });
    };
    int translates = 0, folds = 0, folds_listed = 0;
    for (const auto& e : expected) {
      const double k = (e[0] - m.params[0]) / kPeriod;
      if (std::abs(k - std::round(k)) < 1e-9) {
        ++translates;
        CHECK(listed(e));
      } else {
        ++folds;
        folds_listed += listed(e) ? 1 : 0;
      }
    }
    CHECK(translates >= 5);
    CHECK(folds_listed == folds);
    CHECK(m.copies.size() == static_cast<std::size_t>(translates + folds_listed));
  }
}

TEST_CASE("max_minima caps the copies too, and says so") {
  const auto g =
      make_surface("(3+cos(v))*cos(u)", "(3+cos(v))*sin(u)", "sin(v)", {0, 2 * kPeriod}, {0, kPeriod});
  Options all;
  all.all_minima = true;
  all.max_minima = 4;
  const ProjectionResult r = project(*g, {5, 0, 0}, "auto", all);
  REQUIRE(r.minima.size() >= 1);
  CHECK(r.minima[0].copies.size() == 4);
  CHECK(r.minima[0].copies_truncated);
}
