// geometry/dense_solve: Gaussian elimination with partial pivoting against systems whose solutions
// are known exactly, and the systems it must refuse.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>

#include "geometry/dense_solve.hpp"

using namespace footpoint;

TEST_CASE("dense_solve: a 3 x 3 system that needs a row exchange, solved exactly") {
  // a[0][0] = 0: without pivoting the first step divides by zero. x = (1, -2, 3).
  Matrix<3> a{{{0, 2, 1}, {1, 1, 1}, {2, 1, -1}}};
  Vector<3> b{-4 + 3, 1 - 2 + 3, 2 - 2 - 3};
  REQUIRE(dense_solve<3>(a, b));
  CHECK(b[0] == 1.0);
  CHECK(b[1] == -2.0);
  CHECK(b[2] == 3.0);
}

TEST_CASE("dense_solve: the 5 x 5 Lagrange shape (a symmetric block with zero corner) to rounding") {
  // [[I + H, G], [G^T, 0]] with H symmetric and G of full rank, and x = (1, 2, 3, 4, 5): b = A x in
  // exact integer arithmetic.
  const Matrix<5> a{{{3, 1, 0, 1, 0}, {1, 2, 1, 0, 1}, {0, 1, 4, 2, 1}, {1, 0, 2, 0, 0}, {0, 1, 1, 0, 0}}};
  const Vector<5> x{1, 2, 3, 4, 5};
  Vector<5> b{};
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 5; ++j) b[i] += a[i][j] * x[j];
  REQUIRE(dense_solve<5>(a, b));
  for (int i = 0; i < 5; ++i) CHECK(std::fabs(b[i] - x[i]) <= 1e-14 * 5);
}

TEST_CASE("dense_solve: singular and non-finite systems are refused") {
  Matrix<3> rank2{{{1, 2, 3}, {2, 4, 6}, {1, 0, 1}}};
  Vector<3> b{1, 2, 3};
  CHECK(!dense_solve<3>(rank2, b));
  Matrix<2> zero{};
  Vector<2> c{1, 1};
  CHECK(!dense_solve<2>(zero, c));
  Matrix<2> nan{{{std::numeric_limits<double>::quiet_NaN(), 0}, {0, 1}}};
  CHECK(!dense_solve<2>(nan, c));
  Matrix<2> inf{{{std::numeric_limits<double>::infinity(), 0}, {0, 1}}};
  CHECK(!dense_solve<2>(inf, c));
}

TEST_CASE("dense_solve: the pivot tolerance decides what counts as singular") {
  // The second pivot is 1e-20 of the largest entry: below the default 64 eps, above 1e-300.
  Matrix<2> nearly{{{1.0, 0.0}, {0.0, 1e-20}}};
  Vector<2> b{2.0, 3e-20};
  CHECK(!dense_solve<2>(nearly, b));
  b = {2.0, 3e-20};
  REQUIRE(dense_solve<2>(nearly, b, 1e-300));
  CHECK(b[0] == 2.0);
  CHECK(b[1] == doctest::Approx(3.0).epsilon(1e-15));
  // An exactly singular matrix stays refused at any tolerance.
  Matrix<2> singular{{{1, 1}, {1, 1}}};
  Vector<2> c{1.0, 1.0};
  CHECK(!dense_solve<2>(singular, c, 1e-300));
}
