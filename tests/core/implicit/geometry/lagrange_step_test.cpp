// implicit/geometry/lagrange_step: the null-space solve of the 5 x 5 Lagrange system against systems whose
// solutions are known exactly, against Gaussian elimination of the whole system (an independent
// solve) on random well-conditioned systems, and the systems it must refuse.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <random>

#include "geometry/dense_solve.hpp"
#include "implicit/geometry/lagrange_step.hpp"

using namespace footpoint;

namespace {

// The right-hand sides (r, f) of the system [[A, J^T], [J, 0]] (dx, dl) = (-r, -f).
void right_hand_side(const Mat3& a, Vec3 g1, Vec3 g2, Vec3 dx, double dl1, double dl2, Vec3& r, double& f1,
                     double& f2) {
  r = -(a * dx + dl1 * g1 + dl2 * g2);
  f1 = -dot(g1, dx);
  f2 = -dot(g2, dx);
}

}  // namespace

TEST_CASE("lagrange_step: a system with an integer solution, solved to rounding") {
  const Mat3 a{{{3, 1, 0}, {1, 2, 1}, {0, 1, 4}}};
  const Vec3 g1{1, 0, 2}, g2{0, 1, 1};
  const Vec3 dx{1, 2, 3};
  Vec3 r;
  double f1 = 0.0, f2 = 0.0;
  right_hand_side(a, g1, g2, dx, 4.0, 5.0, r, f1, f2);
  LagrangeStep s;
  REQUIRE(lagrange_step(a, g1, g2, r, f1, f2, s));
  CHECK(norm(s.dx - dx) <= 1e-14 * 8);
  CHECK(std::fabs(s.dl1 - 4.0) <= 1e-14 * 8);
  CHECK(std::fabs(s.dl2 - 5.0) <= 1e-14 * 8);
}

TEST_CASE("lagrange_step: the planar embedding (g2 = e_z, no second Hessian) gives dz = -z") {
  // f2 = z: J dx = -f asks dz = -f2, and the multiplier of f2 takes up r_z.
  const Mat3 a{{{2, 0.5, 0}, {0.5, 1.5, 0}, {0, 0, 1}}};
  const Vec3 g1{0.6, -0.8, 0}, g2{0, 0, 1};
  LagrangeStep s;
  REQUIRE(lagrange_step(a, g1, g2, {0.1, -0.2, 0.3}, 0.05, 0.25, s));
  CHECK(s.dx.z == doctest::Approx(-0.25).epsilon(1e-15));
  CHECK(dot(g1, s.dx) == doctest::Approx(-0.05).epsilon(1e-14));
  // The first block row holds: A dx + dl1 g1 + dl2 g2 = -r.
  const Vec3 row = a * s.dx + s.dl1 * g1 + s.dl2 * g2 + Vec3{0.1, -0.2, 0.3};
  CHECK(norm(row) <= 1e-15 * 8);
}

TEST_CASE("lagrange_step: random well-conditioned systems agree with Gaussian elimination to 1e-12") {
  std::mt19937_64 rng(20261203);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int checked = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    Mat3 a;
    for (int i = 0; i < 3; ++i)
      for (int k = i; k < 3; ++k) a[i][k] = a[k][i] = u(rng) + (i == k ? 3.0 : 0.0);  // positive definite
    const Vec3 g1{u(rng), u(rng), u(rng)}, g2{u(rng), u(rng), u(rng)};
    // Gradients at least 0.3 rad apart and not small: the system is well conditioned.
    if (norm(cross(g1, g2)) < 0.3 * norm(g1) * norm(g2) || norm(g1) < 0.3 || norm(g2) < 0.3) continue;
    const Vec3 r{u(rng), u(rng), u(rng)};
    const double f1 = u(rng), f2 = u(rng);
    Matrix<5> k{};
    Vector<5> b{-r.x, -r.y, -r.z, -f1, -f2};
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) k[i][j] = a[i][j];
      k[i][3] = k[3][i] = g1[i];
      k[i][4] = k[4][i] = g2[i];
    }
    REQUIRE(dense_solve<5>(k, b));
    LagrangeStep s;
    REQUIRE(lagrange_step(a, g1, g2, r, f1, f2, s));
    const double scale =
        1.0 + std::fabs(b[0]) + std::fabs(b[1]) + std::fabs(b[2]) + std::fabs(b[3]) + std::fabs(b[4]);
    CAPTURE(trial);
    CHECK(norm(s.dx - Vec3{b[0], b[1], b[2]}) <= 1e-12 * scale);
    CHECK(std::fabs(s.dl1 - b[3]) <= 1e-12 * scale);
    CHECK(std::fabs(s.dl2 - b[4]) <= 1e-12 * scale);
    ++checked;
  }
  CHECK(checked > 500);
}

TEST_CASE("lagrange_step: singular and non-finite systems are refused") {
  const Mat3 identity{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
  LagrangeStep s;
  // Parallel gradients (a singular point of the curve): J has rank 1.
  CHECK(!lagrange_step(identity, {1, 2, 3}, {-2, -4, -6}, {1, 1, 1}, 0.1, 0.2, s));
  // A zero gradient.
  CHECK(!lagrange_step(identity, {1, 2, 3}, {0, 0, 0}, {1, 1, 1}, 0.1, 0.2, s));
  // t^T A t = 0 along t = g1 x g2 = e_z: a degenerate second variation.
  const Mat3 flat_along_t{{{1, 0, 0}, {0, 1, 0}, {0, 0, 0}}};
  CHECK(!lagrange_step(flat_along_t, {1, 0, 0}, {0, 1, 0}, {1, 1, 1}, 0.1, 0.2, s));
  // Not finite.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  CHECK(!lagrange_step(identity, {1, 0, 0}, {0, 1, 0}, {nan, 0, 0}, 0.1, 0.2, s));
  CHECK(!lagrange_step(identity, {1, 0, 0}, {0, 1, 0}, {0, 0, 0}, std::numeric_limits<double>::infinity(),
                       0.2, s));
}
