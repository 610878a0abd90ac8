// parametric/solvers/newton_direction: the projected Newton step, -|H|^{-1} g with H's eigenvalues
// taken in absolute value (and no smaller than kSemidefinite |H|), and the direction of negative
// curvature, on 2 x 2 systems worked out by hand: definite ones (the Newton step itself), saddles
// (a descent step, the eigenvector of the negative eigenvalue), a singular H, held parameters.
#include <doctest/doctest.h>

#include <cmath>

#include "parametric/solvers/newton_direction.hpp"

using footpoint::surface::newton_direction;
using footpoint::surface::NewtonDirection;

namespace {

constexpr bool kBothFree[2] = {true, true};

// e^T H e for the direction of negative curvature.
double direction_curvature(const double (&H)[2][2], const NewtonDirection& n) {
  const auto& e = n.negative_curvature;
  return H[0][0] * e[0] * e[0] + 2 * H[0][1] * e[0] * e[1] + H[1][1] * e[1] * e[1];
}

}  // namespace

TEST_CASE("newton direction: a positive definite H gives Newton's step -H^{-1} g") {
  const double diagonal[2][2] = {{2, 0}, {0, 1}};
  const NewtonDirection d = newton_direction(diagonal, {2, -3}, kBothFree);
  CHECK(d.definite);
  CHECK(d.convex);
  CHECK(d.det == 2.0);
  CHECK(d.step[0] == -1.0);
  CHECK(d.step[1] == 3.0);
  CHECK(d.negative_curvature[0] == 0.0);
  CHECK(d.negative_curvature[1] == 0.0);
  // H = [2 1; 1 2], H^{-1} = [2 -1; -1 2] / 3: the step for g = (1, 0) is (-2/3, 1/3).
  const double coupled[2][2] = {{2, 1}, {1, 2}};
  const NewtonDirection c = newton_direction(coupled, {1, 0}, kBothFree);
  CHECK(c.definite);
  CHECK(c.det == 3.0);
  CHECK(c.step[0] == doctest::Approx(-2.0 / 3).epsilon(1e-15));
  CHECK(c.step[1] == doctest::Approx(1.0 / 3).epsilon(1e-15));
}

TEST_CASE("newton direction: at a saddle, |H| and the direction of negative curvature") {
  // H = diag(1, -2): |H| = diag(1, 2), so for g = (1, 1) the step is (-1, -1/2), a descent step
  // (g . step < 0) where Newton's own, (-1, 1/2), would climb along v.
  const double saddle[2][2] = {{1, 0}, {0, -2}};
  const NewtonDirection s = newton_direction(saddle, {1, 1}, kBothFree);
  CHECK_FALSE(s.definite);
  CHECK_FALSE(s.convex);
  CHECK(s.step[0] == doctest::Approx(-1.0).epsilon(1e-15));
  CHECK(s.step[1] == doctest::Approx(-0.5).epsilon(1e-15));
  CHECK(std::hypot(s.negative_curvature[0], s.negative_curvature[1]) == doctest::Approx(1.0).epsilon(1e-15));
  CHECK(direction_curvature(saddle, s) == doctest::Approx(-2.0).epsilon(1e-15));
  // H = [0 1; 1 0] (eigenvalues ±1, vectors (1, ±1)/√2): |H| = I, the step is -g, and the negative
  // curvature lies along (1, -1)/√2.
  const double rotated[2][2] = {{0, 1}, {1, 0}};
  const NewtonDirection r = newton_direction(rotated, {1, 2}, kBothFree);
  CHECK_FALSE(r.convex);
  CHECK(r.step[0] == doctest::Approx(-1.0).epsilon(1e-15));
  CHECK(r.step[1] == doctest::Approx(-2.0).epsilon(1e-15));
  CHECK(std::fabs(r.negative_curvature[0]) == doctest::Approx(std::sqrt(0.5)).epsilon(1e-15));
  CHECK(r.negative_curvature[0] == doctest::Approx(-r.negative_curvature[1]).epsilon(1e-15));
  CHECK(direction_curvature(rotated, r) == doctest::Approx(-1.0).epsilon(1e-15));
  // A stationary saddle (g = 0): no step, but the direction to leave it by.
  const NewtonDirection still = newton_direction(saddle, {0, 0}, kBothFree);
  CHECK(still.step[0] == 0.0);
  CHECK(still.step[1] == 0.0);
  CHECK(direction_curvature(saddle, still) == doctest::Approx(-2.0).epsilon(1e-15));
}

TEST_CASE("newton direction: a singular H is semidefinite, its zero eigenvalue floored") {
  // H = diag(1, 0): convex (semidefinite) but not definite. Along u the step is Newton's; along v
  // the eigenvalue 0 is used as kSemidefinite x |H| = 1e-12.
  const double singular[2][2] = {{1, 0}, {0, 0}};
  const NewtonDirection s = newton_direction(singular, {1, 1e-12}, kBothFree);
  CHECK_FALSE(s.definite);
  CHECK(s.convex);
  CHECK(s.step[0] == doctest::Approx(-1.0).epsilon(1e-15));
  CHECK(s.step[1] == doctest::Approx(-1e-12 / footpoint::surface::kSemidefinite).epsilon(1e-12));
  CHECK(s.negative_curvature[0] == 0.0);
  CHECK(s.negative_curvature[1] == 0.0);
}

TEST_CASE("newton direction: a held parameter does not move, the free one takes its 1-D step") {
  const double H[2][2] = {{4, 1}, {1, 3}};
  const bool hold_v[2] = {true, false};
  const NewtonDirection u = newton_direction(H, {2, 5}, hold_v);
  CHECK_FALSE(u.definite);  // definite is said of both parameters free
  CHECK(u.convex);
  CHECK(u.step[0] == -0.5);
  CHECK(u.step[1] == 0.0);
  // Held u, concave along v: the step descends with |H_vv|, and v is the direction to leave by.
  const double concave[2][2] = {{4, 1}, {1, -2}};
  const bool hold_u[2] = {false, true};
  const NewtonDirection v = newton_direction(concave, {7, 1}, hold_u);
  CHECK_FALSE(v.convex);
  CHECK(v.step[0] == 0.0);
  CHECK(v.step[1] == -0.5);
  CHECK(v.negative_curvature[0] == 0.0);
  CHECK(v.negative_curvature[1] == 1.0);
}
