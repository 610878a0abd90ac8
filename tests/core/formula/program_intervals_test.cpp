// Interval enclosures contain every value over the box; many threads evaluating one compiled
// formula get bit-identical results.
#include <doctest/doctest.h>

#include <cstring>
#include <random>
#include <thread>

#include "formula/program.hpp"

using footpoint::formula::Interval;
using footpoint::formula::Jet2;
using footpoint::formula::Program;

TEST_CASE("interval ranges enclose sampled values of every function") {
  const char* texts[] = {"x^2/9+y^2/16+x*y-1",
                         "sin(3*x)*cos(y)-tan(0.2*x)",
                         "exp(x)-ln(y+5)+sqrt(x^2+1)",
                         "asin(x/4)+acos(y/4)+atan(x*y)",
                         "sinh(x)-cosh(y)+tanh(x*y)+abs(x-y)+sign(x)",
                         "min(x,y)+max(x^3,y)-x^y*0+(x>y?x:y)",
                         "asinh(x)+acosh(y^2+1)+atanh(x/5)",
                         "1/(x-y+10)"};
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(-3.0, 3.0);
  for (const char* text : texts) {
    INFO(text);
    const Program p = Program::compile({{"f", text}}, {"x", "y"}, {});
    for (int box = 0; box < 200; ++box) {
      double a = U(rng), b = U(rng), c = U(rng), d = U(rng);
      if (a > b) std::swap(a, b);
      if (c > d) std::swap(c, d);
      const Interval in[2] = {{a, b}, {c, d}};
      Interval out;
      p.intervals(in, &out);
      if (std::isnan(out.lo)) continue;  // no enclosure claimed
      for (int s = 0; s < 30; ++s) {
        const double pt[2] = {a + (b - a) * s / 29.0, c + (d - c) * ((s * 7) % 30) / 29.0};
        double v;
        p.values(pt, &v);
        if (std::isfinite(v)) {
          CHECK(v >= out.lo);
          CHECK(v <= out.hi);
        }
      }
    }
  }
}

TEST_CASE("an interval excludes zero where the curve cannot be") {
  const Program p = Program::compile({{"f", "x^2+y^2-1"}}, {"x", "y"}, {});
  const Interval far[2] = {{2.0, 3.0}, {2.0, 3.0}};
  Interval out;
  p.intervals(far, &out);
  CHECK(out.excludes_zero());
  const Interval near[2] = {{0.5, 1.5}, {-0.1, 0.1}};
  p.intervals(near, &out);
  CHECK(!out.excludes_zero());
}

TEST_CASE("many threads evaluating one compiled program get bit-identical results") {
  const Program p = Program::compile(
      {{"x", "u^6+u^5*v+v^6-u^2*v^3"}, {"y", "sin(u)*exp(v)"}, {"z", "sqrt(u^2+v^2+1)"}}, {"u", "v"}, {});
  constexpr int kPoints = 2000;
  auto evaluate = [&](std::vector<double>& out) {
    out.clear();
    for (int i = 0; i < kPoints; ++i) {
      const double pt[2] = {-1.0 + 2.0 * i / kPoints, 0.5 - 1.3 * i / kPoints};
      Jet2<2> j[3];
      p.jets2<2>(pt, j);
      for (const auto& jj : j) {
        out.push_back(jj.v);
        out.insert(out.end(), jj.g.begin(), jj.g.end());
        for (const auto& row : jj.h) out.insert(out.end(), row.begin(), row.end());
      }
    }
  };
  std::vector<double> reference;
  evaluate(reference);
  std::vector<std::vector<double>> results(8);
  std::vector<std::thread> threads;
  threads.reserve(results.size());
  for (auto& r : results) threads.emplace_back([&] { evaluate(r); });
  for (auto& t : threads) t.join();
  for (const auto& r : results) {
    REQUIRE(r.size() == reference.size());
    CHECK(std::memcmp(r.data(), reference.data(), r.size() * sizeof(double)) == 0);
  }
}

TEST_CASE("interval enclosures hold for huge integral exponents and where subexpressions are NaN") {
  // Found by fuzzing: integral exponents above pow_int's old limit were treated as real powers
  // (argument clipped to x >= 0), and NaN-producing points were ignored by comparisons.
  struct Case {
    const char* text;
    double lo, hi, at, value;
  } cases[] = {
      {"(u-1)^2302", 0.0, 1.0, 0.0, 1.0},         {"9+u^-1261/-1", -1.0, -0.5, -1.0, 10.0},
      {"0>=u^1.0241-24", -3.0, 3.0, -2.75, 0.0},  {"sign(sqrt(u))", -1.0, 1.0, -0.5, 0.0},
      {"min(sqrt(u), 5)", -1.0, 1.0, -0.5, 5.0},  {"sqrt(u) ? 1 : 2", -1.0, 1.0, -0.5, 1.0},
      {"u^-1024^1025", -2.0, 2.0, 1.0, 1.0},       // an infinite constant exponent
      {"cos(1+u)", 0.5, 0.5, 0.5, std::cos(1.5)},  // a point box: no shifted-argument rounding
  };
  for (const auto& c : cases) {
    INFO(c.text);
    const Program p = Program::compile({{"f", c.text}}, {"u"}, {});
    double v;
    p.values(&c.at, &v);
    CHECK(v == c.value);
    const Interval box{c.lo, c.hi};
    Interval out;
    p.intervals(&box, &out);
    CHECK(out.lo <= v);
    CHECK(v <= out.hi);
  }
}
