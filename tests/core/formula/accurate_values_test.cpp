// Program::accurate_values (formula/accurate_values.cpp): at random points on and near the zero
// sets of polynomial formulas (where the value cancels to far below its terms), the ball holds
// the value computed independently in binary128 (__float128, 113 bits: formulas written out by
// hand) and its radius is the value's own rounding plus O(u^2) of the terms, where ball_jets1's
// is O(u). Operations other than a polynomial's, and values out of TwoProduct's range, give false.
#include <doctest/doctest.h>

#include <cmath>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "formula/program.hpp"

using footpoint::formula::Ball;
using footpoint::formula::BallJet1;
using footpoint::formula::Program;

namespace {

using Quad = __float128;

Program compile(const std::string& f) { return Program::compile({{"f", f}}, {"x", "y", "z"}, {}); }

double to_double(Quad q) { return static_cast<double>(q); }
Quad qabs(Quad q) { return q < 0 ? -q : q; }

struct Case {
  std::string formula;
  std::function<Quad(Quad, Quad, Quad)> exact;
  std::function<Quad(Quad, Quad, Quad)> size;  // the sum of the terms' magnitudes
};

}  // namespace

TEST_CASE("accurate_values: encloses binary128 values to O(u^2) of the terms, near zeros") {
  const std::vector<Case> cases{
      {"(x-1.9999)^2+y^2+z^2-1",
       [](Quad x, Quad y, Quad z) {
         const Quad c = 1.9999;
         return (x - c) * (x - c) + y * y + z * z - 1;
       },
       [](Quad x, Quad y, Quad z) {
         const Quad c = 1.9999;
         return (qabs(x) + c) * (qabs(x) + c) + y * y + z * z + 1;
       }},
      {"x^2/9+y^2/16+z^2/9+4*x*y-1",
       [](Quad x, Quad y, Quad z) { return x * x / 9 + y * y / 16 + z * z / 9 + 4 * x * y - 1; },
       [](Quad x, Quad y, Quad z) { return x * x / 9 + y * y / 16 + z * z / 9 + 4 * qabs(x * y) + 1; }},
      {"-(x-0.3)^5*3+y^3*x-7*(z+y)*(x-y)/3+0.125",
       [](Quad x, Quad y, Quad z) {
         const Quad a = x - Quad(0.3);
         return -(a * a * a * a * a) * 3 + y * y * y * x - 7 * (z + y) * (x - y) / 3 + Quad(0.125);
       },
       [](Quad x, Quad y, Quad z) {
         const Quad a = qabs(x) + Quad(0.3);
         return a * a * a * a * a * 3 + qabs(y * y * y * x) +
                7 * (qabs(z) + qabs(y)) * (qabs(x) + qabs(y)) / 3 + Quad(0.125);
       }},
  };
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  for (const Case& c : cases) {
    CAPTURE(c.formula);
    const Program p = compile(c.formula);
    int narrower = 0, near_zero = 0;
    for (int i = 0; i < 3000; ++i) {
      double x[3] = {u(rng), u(rng), u(rng)};
      // Every other point on the zero set: x moved by Newton's steps in binary128 along e_x,
      // then rounded, so that the value cancels to about the rounding of the coordinates.
      if (i % 2 == 0) {
        Quad q = x[0];
        for (int k = 0; k < 60; ++k) {
          const Quad h = Quad(1e-20) * (1 + qabs(q));
          const Quad d = (c.exact(q + h, x[1], x[2]) - c.exact(q - h, x[1], x[2])) / (2 * h);
          if (d == 0) break;
          q -= c.exact(q, x[1], x[2]) / d;
          if (!(qabs(q) < 10)) break;
        }
        if (qabs(q) < 10) x[0] = to_double(q);
      }
      Ball b{};
      REQUIRE(p.accurate_values(x, &b));
      const Quad exact = c.exact(x[0], x[1], x[2]);
      const Quad size = c.size(x[0], x[1], x[2]);
      // binary128's own rounding: a few dozen operations of relative error 2^-113 = 9.6e-35 each.
      const Quad reference_error = size * Quad(4e-33);
      CHECK(to_double(qabs(exact - Quad(b.mid))) <= to_double(Quad(b.rad) + reference_error));
      // The radius: the value's rounding and O(u^2) of the terms.
      CHECK(b.rad <= 2.0 * 0x1p-53 * std::abs(b.mid) + 1e-28 * to_double(size));
      BallJet1<3> j[1];
      p.ball_jets1<3>(x, j);
      if (std::abs(b.mid) < 1e-13 * to_double(size)) {
        ++near_zero;
        narrower += b.rad < 1e-3 * j[0].v.rad ? 1 : 0;
      }
    }
    CHECK(near_zero >= 300);  // Newton along e_x finds a zero from about a third of the starts
    CHECK(narrower == near_zero);
  }
}

TEST_CASE("accurate_values: false for other operations and out of range") {
  const double x[3] = {0.5, 0.25, 2.0};
  Ball b{};
  for (const char* f : {"sin(x)+y", "sqrt(x)*y", "x/y", "x^-2", "abs(x)-y", "x^0.5"}) {
    CAPTURE(f);
    CHECK_FALSE(compile(f).accurate_values(x, &b));
  }
  const double tiny[3] = {1e-200, 1.0, 1.0};
  CHECK_FALSE(compile("x*x+y").accurate_values(tiny, &b));
  const double huge[3] = {1e200, 1.0, 1.0};
  CHECK_FALSE(compile("x*x*x+y").accurate_values(huge, &b));
  // A zero operand is exact, whatever the other.
  const double zero[3] = {0.0, 1e-300, 1.0};
  REQUIRE(compile("x*y+z").accurate_values(zero, &b));
  CHECK(b.mid == 1.0);
}
