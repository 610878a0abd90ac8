// Ball jets (formula/ball.hpp, Program::ball_jets1): rigorous enclosures of a formula's value and
// gradient at a point.
//  - Against references in long double (64-bit significand: within ~1e-19 of the exact value,
//    a thousand times finer than the balls' radii): the exact value lies in the ball, for formulas
//    using every fast path (sin, cos, exp, ln, log2, log10, sqrt, integer powers) and the
//    interval fallback (tan, asin, acos, atan, the hyperbolic functions, real powers, 1/x^k), at
//    random points; and the balls are tight (a few ulps of the magnitudes involved).
//  - Every operation of the tape at random points, near kinks, switches and domain ends too:
//    where defined, the ball meets the interval jet of the degenerate box (both hold the exact
//    value), and kinks, jumps and undefined points are flagged as the header says.
#include <doctest/doctest.h>

#include <cmath>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "formula/program.hpp"

using footpoint::formula::BallJet1;
using footpoint::formula::Interval;
using footpoint::formula::IntervalJet2;
using footpoint::formula::Program;

namespace {

using LD = long double;

struct Reference {
  const char* text;
  // value, d/du, d/dv in long double
  std::function<std::array<LD, 3>(LD, LD)> f;
  double lo, hi;  // u and v drawn from [lo, hi]
};

std::vector<Reference> references() {
  return {
      {"sin(u)+2*cos(v)",
       [](LD u, LD v) {
         return std::array<LD, 3>{sinl(u) + 2 * cosl(v), cosl(u), -2 * sinl(v)};
       },
       -3, 3},
      {"sin(u+v)",
       [](LD u, LD v) {
         return std::array<LD, 3>{sinl(u + v), cosl(u + v), cosl(u + v)};
       },
       -3, 3},
      {"u^4*v^3+u*v+u",
       [](LD u, LD v) {
         return std::array<LD, 3>{u * u * u * u * v * v * v + u * v + u, 4 * u * u * u * v * v * v + v + 1,
                                  3 * u * u * u * u * v * v + u};
       },
       -2, 2},
      {"exp(u*v)-ln(u+4)",
       [](LD u, LD v) {
         return std::array<LD, 3>{expl(u * v) - logl(u + 4), v * expl(u * v) - 1 / (u + 4), u * expl(u * v)};
       },
       -2, 2},
      {"sqrt(u*u+v*v+1)",
       [](LD u, LD v) {
         const LD s = sqrtl(u * u + v * v + 1);
         return std::array<LD, 3>{s, u / s, v / s};
       },
       -3, 3},
      {"log2(v+4)*log10(u+5)",
       [](LD u, LD v) {
         const LD a = log2l(v + 4), b = log10l(u + 5);
         return std::array<LD, 3>{a * b, a / ((u + 5) * logl(10.0L)), b / ((v + 4) * logl(2.0L))};
       },
       -2, 2},
      {"tan(0.4*u)+atan(u*v)",
       [](LD u, LD v) {
         const LD t = tanl(0.4L * u), q = 1 / (1 + u * v * u * v);
         return std::array<LD, 3>{t + atanl(u * v), 0.4L * (1 + t * t) + v * q, u * q};
       },
       -2, 2},
      {"asin(u/4)+acos(v/4)",
       [](LD u, LD v) {
         return std::array<LD, 3>{asinl(u / 4) + acosl(v / 4), 1 / sqrtl(16 - u * u), -1 / sqrtl(16 - v * v)};
       },
       -3, 3},
      {"sinh(u)*cosh(v)+tanh(u*v)",
       [](LD u, LD v) {
         const LD th = tanhl(u * v), q = 1 - th * th;
         return std::array<LD, 3>{sinhl(u) * coshl(v) + th, coshl(u) * coshl(v) + v * q,
                                  sinhl(u) * sinhl(v) + u * q};
       },
       -2, 2},
      {"(u+4)^1.5+(v+4)^(-0.7)",
       [](LD u, LD v) {
         return std::array<LD, 3>{powl(u + 4, 1.5L) + powl(v + 4, -0.7L), 1.5L * powl(u + 4, 0.5L),
                                  -0.7L * powl(v + 4, -1.7L)};
       },
       -2, 2},
      {"(u*u+v)/(1+v*v)",
       [](LD u, LD v) {
         const LD d = 1 + v * v;
         return std::array<LD, 3>{(u * u + v) / d, 2 * u / d, (d - 2 * v * (u * u + v)) / (d * d)};
       },
       -3, 3},
      {"u^(-2)+2.5/(v+4)",
       [](LD u, LD v) {
         return std::array<LD, 3>{1 / (u * u) + 2.5L / (v + 4), -2 / (u * u * u),
                                  -2.5L / ((v + 4) * (v + 4))};
       },
       0.5, 3},
      {"asinh(u)+acosh(v*v+1.5)+atanh(u/4)",
       [](LD u, LD v) {
         const LD w = v * v + 1.5L;
         return std::array<LD, 3>{asinhl(u) + acoshl(w) + atanhl(u / 4),
                                  1 / sqrtl(1 + u * u) + 4 / (16 - u * u), 2 * v / sqrtl(w * w - 1)};
       },
       -3, 3},
  };
}

bool holds(const footpoint::formula::Ball& b, LD exact) {
  const LD slack = 1e-18L * (fabsl(exact) + 1e-300L);  // the long double reference's own error
  return fabsl(exact - static_cast<LD>(b.mid)) <= static_cast<LD>(b.rad) + slack;
}

bool meets(const footpoint::formula::Ball& b, const Interval& i) {
  return b.mid - b.rad <= i.hi && i.lo <= b.mid + b.rad;
}

}  // namespace

TEST_CASE("ball jets hold the exact value and gradient, and are tight") {
  std::mt19937_64 rng(7);
  int checked = 0;
  for (const Reference& ref : references()) {
    INFO(std::string(ref.text));
    const Program p = Program::compile({{"f", ref.text}}, {"u", "v"}, {});
    std::uniform_real_distribution<double> U(ref.lo, ref.hi);
    for (int i = 0; i < 400; ++i) {
      const double x[2] = {U(rng), U(rng)};
      BallJet1<2> b;
      p.ball_jets1<2>(x, &b);
      REQUIRE(b.defined);
      REQUIRE(b.differentiable);
      const auto exact = ref.f(x[0], x[1]);
      CHECK(holds(b.v, exact[0]));
      CHECK(holds(b.g[0], exact[1]));
      CHECK(holds(b.g[1], exact[2]));
      // tight: within ~100 ulps of the largest magnitude a term of the evaluation reaches (4e3
      // for these formulas over their ranges)
      CHECK(b.v.rad <= 1e-13 * (1.0 + std::abs(b.v.mid)) * 4e3);
      CHECK(b.g[0].rad <= 1e-13 * (1.0 + std::abs(b.g[0].mid)) * 4e3);
      ++checked;
    }
  }
  CHECK(checked == 13 * 400);
}

TEST_CASE("ball jets meet the interval jets of the point for every operation") {
  const char* const ops[] = {
      "u+v",          "u-v",       "u*v",          "u/(v+4)",    "u/v",       "-u+v",      "u+2.5",
      "u*2.5",        "u/2.5",     "2.5-u",        "2.5/u",      "u^3*v^2",   "u^(-2)",    "(u+4)^1.5",
      "u^1.5",        "u^7",       "sqrt(u)",      "exp(u*v)",   "ln(u)",     "log2(v+4)", "sin(u*v)",
      "cos(u+v)",     "tan(u)",    "asin(u/3)",    "acos(v/4)",  "atan(u*v)", "sinh(u)",   "cosh(v)",
      "tanh(u*v)",    "asinh(u)",  "acosh(u^2+1)", "atanh(u/4)", "abs(u-v)",  "sign(u-v)", "min(u,v)",
      "max(u*v,v)",   "(u<v)+u",   "(u<=v)*v",     "(u>v)",      "(u==v)",    "(u!=v)",    "(u>0)&&(v>0)",
      "(u>0)||(v>0)", "u>v?u*u:v", "(u+4)^v"};
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> U(-3.0, 3.0);
  int defined = 0;
  for (const char* text : ops) {
    INFO(std::string(text));
    const Program p = Program::compile({{"f", text}}, {"u", "v"}, {});
    for (int i = 0; i < 300; ++i) {
      // some points on the kinks and switches u = 0, u = v
      double u = U(rng), v = U(rng);
      if (i % 10 == 0) u = 0.0;
      if (i % 10 == 1) v = u;
      const double x[2] = {u, v};
      BallJet1<2> b;
      p.ball_jets1<2>(x, &b);
      IntervalJet2<2> r;
      const Interval box[2] = {{u, u}, {v, v}};
      p.interval_jets2<2>(box, &r);
      if (!b.defined) continue;
      ++defined;
      CHECK(meets(b.v, r.v));
      if (r.lipschitz) {
        CHECK(meets(b.g[0], r.g[0]));
        CHECK(meets(b.g[1], r.g[1]));
      }
    }
  }
  CHECK(defined > 10000);
}

TEST_CASE("ball jets flag kinks, jumps and points outside the domain") {
  auto at = [](const char* text, double u, double v) {
    const Program p = Program::compile({{"f", text}}, {"u", "v"}, {});
    const double x[2] = {u, v};
    BallJet1<2> b;
    p.ball_jets1<2>(x, &b);
    return b;
  };
  {  // |u - v| on u = v: 1-Lipschitz, Clarke's gradient [-1, 1] x [-1, 1]
    const auto b = at("abs(u-v)", 0.5, 0.5);
    CHECK(b.defined);
    CHECK_FALSE(b.differentiable);
    CHECK(b.v.mid - b.v.rad <= 0.0);
    CHECK(b.g[0].mid - b.g[0].rad <= -1.0);
    CHECK(b.g[0].mid + b.g[0].rad >= 1.0);
  }
  {  // min(u, v) on u = v: the hull of e_u and e_v
    const auto b = at("min(u,v)", 1.0, 1.0);
    CHECK(b.defined);
    CHECK_FALSE(b.differentiable);
    CHECK(b.g[0].mid - b.g[0].rad <= 0.0);
    CHECK(b.g[0].mid + b.g[0].rad >= 1.0);
  }
  {  // away from the switch: one operand, differentiable and exact
    const auto b = at("min(u,v)", 1.0, 2.0);
    CHECK(b.differentiable);
    CHECK(b.v.mid == 1.0);
    CHECK(b.v.rad == 0.0);
  }
  CHECK_FALSE(at("sign(u-v)", 0.5, 0.5).defined);  // a jump
  CHECK_FALSE(at("sqrt(u)", 0.0, 0.0).defined);    // the end of the domain: no derivative
  CHECK_FALSE(at("sqrt(u)", -1.0, 0.0).defined);   // outside the domain
  CHECK_FALSE(at("u/v", 1.0, 0.0).defined);
  CHECK_FALSE(at("ln(u)", 0.0, 0.0).defined);
  CHECK(at("u<v?u:v*v", 1.0, 1.0).defined);  // exact operands: u < v decided (false)
  {
    const auto b = at("(u<v)+u", 1.0, 2.0);  // a decided comparison, then one rounded sum
    CHECK(b.defined);
    CHECK(b.v.mid == 2.0);
    CHECK(b.v.rad <= 0x1p-51);
  }
  CHECK(at("(u<v)+u", 1.0, 1.0 + 0x1p-52).defined);        // exact operands one ulp apart: decided
  CHECK_FALSE(at("(sin(u)<sin(v))+u", 1.0, 1.0).defined);  // rounded values that close: a jump
}

TEST_CASE("ball jets of sums of monomials (the polynomial fast path) hold the exact value and gradient") {
  // Coefficients folded from the tape's constants with roundings of their own (1/9, (1/3)^3, a
  // product of decimals), three variables, and points where products underflow (the tape's ball
  // arithmetic instead) or cancel.
  struct Case {
    const char* text;
    std::function<std::array<LD, 4>(LD, LD, LD)> f;  // value, d/dx, d/dy, d/dz
  };
  const Case cases[] = {
      {"x^2/9+y^2/16+z^2/9+4*x*y-1",
       [](LD x, LD y, LD z) {
         return std::array<LD, 4>{x * x / 9 + y * y / 16 + z * z / 9 + 4 * x * y - 1, 2 * x / 9 + 4 * y,
                                  2 * y / 16 + 4 * x, 2 * z / 9};
       }},
      {"(x/3)^3-0.1*x*y^2*0.7+z^5/7",
       [](LD x, LD y, LD z) {
         const LD c = static_cast<LD>(0.1) * static_cast<LD>(0.7);
         return std::array<LD, 4>{x * x * x / 27 - c * x * y * y + z * z * z * z * z / 7,
                                  x * x / 9 - c * y * y, -2 * c * x * y, 5 * z * z * z * z / 7};
       }},
      {"x^7*y^3*z-2.5*x*y*z+x-y",
       [](LD x, LD y, LD z) {
         const LD x6 = x * x * x * x * x * x;
         return std::array<LD, 4>{
             x6 * x * y * y * y * z - 2.5L * x * y * z + x - y, 7 * x6 * y * y * y * z - 2.5L * y * z + 1,
             3 * x6 * x * y * y * z - 2.5L * x * z - 1, x6 * x * y * y * y - 2.5L * x * y};
       }},
  };
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> U(-3.0, 3.0);
  for (const Case& c : cases) {
    INFO(std::string(c.text));
    const Program p = Program::compile({{"f", c.text}}, {"x", "y", "z"}, {});
    REQUIRE(p.sum_of_monomials());
    for (int i = 0; i < 600; ++i) {
      double x[3] = {U(rng), U(rng), U(rng)};
      if (i % 50 == 0) x[0] = 1e-200;  // x^2 underflows: the tape's own ball arithmetic
      if (i % 50 == 1) x[1] = 0.0;
      BallJet1<3> b;
      p.ball_jets1<3>(x, &b);
      REQUIRE(b.defined);
      const auto exact = c.f(x[0], x[1], x[2]);
      CHECK(holds(b.v, exact[0]));
      for (int j = 0; j < 3; ++j) CHECK(holds(b.g[j], exact[1 + j]));
      // tight: a few hundred ulps of the largest term (|x^7 y^3 z| <= 3^11)
      CHECK(b.v.rad <= 1e-12 * (1.0 + std::abs(b.v.mid)) * 2e5);
      CHECK(b.g[0].rad <= 1e-12 * (1.0 + std::abs(b.g[0].mid)) * 2e5);
    }
  }
}

TEST_CASE("ball jets' radii are never subnormal numbers") {
  // ball.hpp's η is the smallest normal number: an exact zero (a derivative in a variable the
  // formula does not use, a factor that vanishes at the point) gets a normal radius, so no ball
  // operation after it takes a subnormal operand. Through the tape's ball arithmetic and through
  // the sums of monomials.
  const char* const texts[] = {"(u-1)^2+3", "sin(u)*(u+2)-exp(u)", "(u-1)^2+v^2-1", "u^2/9+v^2/16+4*u*v-1"};
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> U(-2.0, 2.0);
  for (const char* text : texts) {
    INFO(std::string(text));
    const Program p = Program::compile({{"f", text}}, {"u", "v"}, {});
    for (int i = 0; i < 200; ++i) {
      const double x[2] = {i % 4 == 0 ? 1.0 : U(rng), i % 3 == 0 ? 0.0 : U(rng)};
      BallJet1<2> b;
      p.ball_jets1<2>(x, &b);
      REQUIRE(b.defined);
      CHECK(std::fpclassify(b.v.rad) != FP_SUBNORMAL);
      for (const auto& g : b.g) CHECK(std::fpclassify(g.rad) != FP_SUBNORMAL);
    }
  }
}
