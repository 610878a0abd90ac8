// The tape's sin and cos (formula/sin_cos.hpp) against long double sinl/cosl (64-bit
// significands: 2^-11 of a double's ulp), in ulps of the double result.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include "formula/sin_cos.hpp"

using footpoint::formula::sin_cos;

namespace {

// |got - exact| in units of the last place of the exact value rounded to double.
double ulps(double got, long double exact) {
  const double rounded = static_cast<double>(exact);
  if (rounded == 0.0) return got == 0.0 ? 0.0 : std::numeric_limits<double>::infinity();
  const double ulp =
      std::nextafter(std::fabs(rounded), std::numeric_limits<double>::infinity()) - std::fabs(rounded);
  return static_cast<double>(std::fabs(static_cast<long double>(got) - exact)) / ulp;
}

struct WorstError {
  double sin = 0.0, cos = 0.0;
  void add(double x) {
    double s = 0.0, c = 0.0;
    sin_cos(x, &s, &c);
    sin = std::max(sin, ulps(s, sinl(static_cast<long double>(x))));
    cos = std::max(cos, ulps(c, cosl(static_cast<long double>(x))));
  }
};

}  // namespace

TEST_CASE("sin_cos is within 1 ulp of sin and cos from tiny arguments to 2^20") {
  std::mt19937_64 rng(20261122);
  for (const double range : {1e-6, 1.0, 4.0, 30.0, 1e3, 1e5, 1e6}) {
    std::uniform_real_distribution<double> draw(-range, range);
    WorstError worst;
    for (int i = 0; i < 200000; ++i) worst.add(draw(rng));
    INFO("|x| < " << range);
    CHECK(worst.sin < 1.0);
    CHECK(worst.cos < 1.0);
  }
}

TEST_CASE("sin_cos keeps its accuracy next to multiples of pi/2, where the reduction cancels") {
  // the doubles nearest k pi/2 and their neighbours: r is tiny, and only the reduction's
  // extra precision (pi/2 in three parts, its roundings carried along) keeps sin r accurate
  WorstError worst;
  for (int k = -300000; k <= 300000; k += 7) {
    double x = static_cast<double>(k) * (std::numbers::pi / 2);
    for (int step = 0; step < 4; ++step) {
      worst.add(x);
      worst.add(-x);
      x = std::nextafter(x, std::numeric_limits<double>::infinity());
    }
  }
  CHECK(worst.sin < 1.0);
  CHECK(worst.cos < 1.0);
}

TEST_CASE("sin_cos: signed zero, tiny, huge and non-finite arguments") {
  double s = 1.0, c = 0.0;
  sin_cos(-0.0, &s, &c);
  CHECK(s == 0.0);
  CHECK(std::signbit(s));
  CHECK(c == 1.0);
  sin_cos(1e-300, &s, &c);
  CHECK(s == 1e-300);
  CHECK(c == 1.0);
  // beyond 2^20 glibc's sincos answers, bit for bit
  for (const double x : {0x1p20, -3.5e7, 1e300}) {
    double gs = 0.0, gc = 0.0;
    ::sincos(x, &gs, &gc);
    sin_cos(x, &s, &c);
    CHECK(s == gs);
    CHECK(c == gc);
  }
  for (const double x : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
                         -std::numeric_limits<double>::infinity()}) {
    sin_cos(x, &s, &c);
    CHECK(std::isnan(s));
    CHECK(std::isnan(c));
  }
}
