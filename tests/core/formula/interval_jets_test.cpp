// Interval jets (formula/interval_jet.hpp) and the rounding of the interval arithmetic
// (formula/interval.hpp, formula/interval_arith.hpp):
//  - for every operation of the tape, at random points of random boxes (boxes straddling kinks,
//    jumps and the ends of the functions' domains among them), the point jets lie in the interval
//    jets; where the flags say so, the mean value inclusion and Taylor's theorem with the interval
//    Hessian hold between random pairs of points, and the flags are those the contract states;
//  - the rounding: next_up/next_down are the neighbouring doubles; point enclosures of powers and
//    of the C library's functions contain the value computed in long double (64-bit significand,
//    2^11 times finer than the margins tested); sin and cos near 1e9 keep their extrema.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "formula/program.hpp"

using footpoint::formula::Interval;
using footpoint::formula::IntervalJet2;
using footpoint::formula::Jet2;
using footpoint::formula::Program;

namespace {

bool inside(double x, const Interval& r) { return r.lo <= x && x <= r.hi; }

// One formula per operation (and a few per piecewise operation), over u, v.
const char* const kOps[] = {"u+v",
                            "u-v",
                            "u*v",
                            "u/(v+4)",
                            "u/v",
                            "-u+v",
                            "u+2.5",
                            "u*2.5",
                            "u/2.5",
                            "2.5-u",
                            "2.5/(u+4)",
                            "2.5/u",
                            "u^3*v^2",
                            "u^(-2)",
                            "(u+4)^1.5",
                            "u^1.5",
                            "(u+4)^(-0.7)",
                            "u^7",
                            "sqrt(u+4)",
                            "sqrt(u)",
                            "exp(u*v)",
                            "ln(u+4)",
                            "log2(v+4)",
                            "log10(u*v+10)",
                            "ln(u)",
                            "sin(u*v)",
                            "cos(u+v)",
                            "tan(0.4*u)",
                            "tan(u)",
                            "asin(u/4)",
                            "acos(v/4)",
                            "asin(u/3)",
                            "atan(u*v)",
                            "sinh(u)",
                            "cosh(v)",
                            "tanh(u*v)",
                            "asinh(u)",
                            "acosh(u^2+1.5)",
                            "acosh(u^2+1)",
                            "atanh(u/4)",
                            "abs(u-v)",
                            "sign(u-v)",
                            "min(u,v)",
                            "max(u*v,v)",
                            "(u<v)+u",
                            "(u<=v)*v",
                            "(u>v)",
                            "(u>=v)",
                            "(u==v)",
                            "(u!=v)",
                            "(u>0)&&(v>0)",
                            "(u>0)||(v>0)",
                            "u>v?u*u:v",
                            "(u+4)^v",
                            "sin(u)*cos(v)+u*exp(-v*v)",
                            "(u*u+v)/(1+v*v)"};

struct Box {
  Interval u, v;
};

Box random_box(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> U(-3.0, 3.0);
  const double widths[] = {1e-9, 1e-4, 0.05, 0.5, 2.0};
  std::uniform_int_distribution<int> W(0, 4);
  const double cu = rng() % 4 == 0 ? 1e-3 * U(rng) : U(rng);       // some boxes around u = 0 (kinks)
  const double cv = rng() % 4 == 0 ? cu + 1e-3 * U(rng) : U(rng);  // some around u = v (switches)
  const double hu = widths[W(rng)], hv = widths[W(rng)];
  return {{cu - hu, cu + hu}, {cv - hv, cv + hv}};
}

double in_box(std::mt19937_64& rng, const Interval& a) {
  std::uniform_real_distribution<double> U(0.0, 1.0);
  const int pick = static_cast<int>(rng() % 8);
  if (pick == 0) return a.lo;
  if (pick == 1) return a.hi;
  return a.lo + (a.hi - a.lo) * U(rng);
}

}  // namespace

TEST_CASE("point jets lie in the interval jets of every operation, on random boxes") {
  std::mt19937_64 rng(15);
  int checked = 0;
  for (const char* text : kOps) {
    INFO(std::string(text));
    const Program p = Program::compile({{"f", text}}, {"u", "v"}, {});
    for (int b = 0; b < 300; ++b) {
      const Box box = random_box(rng);
      const Interval x[2] = {box.u, box.v};
      IntervalJet2<2> r;
      p.interval_jets2<2>(x, &r);
      CHECK((!r.smooth || r.lipschitz));
      for (int s = 0; s < 12; ++s) {
        const double t[2] = {in_box(rng, box.u), in_box(rng, box.v)};
        Jet2<2> j;
        p.jets2<2>(t, &j);
        double value;
        p.values(t, &value);
        INFO("box [" << box.u.lo << ", " << box.u.hi << "] x [" << box.v.lo << ", " << box.v.hi << "] at ("
                     << t[0] << ", " << t[1] << ")");
        if (std::isfinite(value) && !std::isnan(r.v.lo)) CHECK(inside(value, r.v));
        if (!r.lipschitz) {
          CHECK(r.g[0].lo == -std::numeric_limits<double>::infinity());
          continue;
        }
        // a Lipschitz jet: the formula is defined on the whole box
        REQUIRE(std::isfinite(value));
        for (int i = 0; i < 2; ++i)
          if (std::isfinite(j.g[i])) CHECK(inside(j.g[i], r.g[i]));
        if (r.smooth)
          for (int i = 0; i < 2; ++i)
            for (int k = 0; k < 2; ++k)
              if (std::isfinite(j.h[i][k])) CHECK(inside(j.h[i][k], r.h[i][k]));
        ++checked;
      }
    }
  }
  CHECK(checked > 50000);
}

TEST_CASE("mean value and Taylor inclusions hold where the flags say so") {
  // Between random points a, c of a box: f(c) - f(a) ∈ g · (c - a) where `lipschitz`, and
  // f(c) - f(a) - ∇f(a)·(c - a) ∈ ½ (c - a)^T h (c - a) where `smooth`. The exact f(a), f(c) and
  // ∇f(a) are known only within their own point enclosures (the interval jets of the boxes [a, a]
  // and [c, c]): an inclusion fails when no exact values within those could satisfy it.
  using namespace footpoint::formula::interval;
  std::mt19937_64 rng(16);
  int checked = 0;
  for (const char* text : kOps) {
    INFO(std::string(text));
    const Program p = Program::compile({{"f", text}}, {"u", "v"}, {});
    for (int b = 0; b < 200; ++b) {
      const Box box = random_box(rng);
      const Interval x[2] = {box.u, box.v};
      IntervalJet2<2> r;
      p.interval_jets2<2>(x, &r);
      if (!r.lipschitz) continue;
      for (int s = 0; s < 8; ++s) {
        const double a[2] = {in_box(rng, box.u), in_box(rng, box.v)};
        const double c[2] = {in_box(rng, box.u), in_box(rng, box.v)};
        const Interval ia[2] = {point(a[0]), point(a[1])}, ic[2] = {point(c[0]), point(c[1])};
        IntervalJet2<2> ja, jc;
        p.interval_jets2<2>(ia, &ja);
        p.interval_jets2<2>(ic, &jc);
        const Interval du = sub(point(c[0]), point(a[0])), dv = sub(point(c[1]), point(a[1]));
        const Interval diff = sub(jc.v, ja.v);
        INFO("box [" << box.u.lo << ", " << box.u.hi << "] x [" << box.v.lo << ", " << box.v.hi << "] from ("
                     << a[0] << ", " << a[1] << ") to (" << c[0] << ", " << c[1] << ")");
        const Interval mean_value = add(mul(r.g[0], du), mul(r.g[1], dv));
        CHECK(diff.hi >= mean_value.lo);
        CHECK(diff.lo <= mean_value.hi);
        ++checked;
        if (!r.smooth || !ja.lipschitz) continue;
        const Interval rest = sub(diff, add(mul(ja.g[0], du), mul(ja.g[1], dv)));
        const Interval taylor =
            mul(point(0.5), add(add(mul(r.h[0][0], sqr(du)), mul(point(2.0), mul(r.h[0][1], mul(du, dv)))),
                                mul(r.h[1][1], sqr(dv))));
        CHECK(rest.hi >= taylor.lo);
        CHECK(rest.lo <= taylor.hi);
      }
    }
  }
  CHECK(checked > 30000);
}

TEST_CASE("the flags: kinks, switches, jumps and domain ends") {
  struct Expect {
    const char* text;
    Box box;
    bool lipschitz, smooth;
  };
  const Expect cases[] = {
      {"abs(u-v)", {{-1, 1}, {-1, 1}}, true, false},    {"abs(u-v)", {{1, 2}, {-1, 0}}, true, true},
      {"abs(u)", {{0, 1}, {0, 1}}, true, true},         {"sign(u-v)", {{-1, 1}, {-1, 1}}, false, false},
      {"sign(u-v)", {{1, 2}, {-1, 0}}, true, true},     {"min(u,v)", {{-1, 1}, {-1, 1}}, true, false},
      {"min(u,v)", {{-1, 0}, {0, 1}}, true, true},      {"max(u,v)", {{2, 3}, {0, 1}}, true, true},
      {"sqrt(u)", {{0, 1}, {0, 1}}, false, false},      {"sqrt(u)", {{0.5, 1}, {0, 1}}, true, true},
      {"u^1.5", {{-1, 1}, {0, 1}}, false, false},       {"u^1.5", {{0.1, 1}, {0, 1}}, true, true},
      {"ln(u)", {{0, 1}, {0, 1}}, false, false},        {"1/u", {{-1, 1}, {0, 1}}, false, false},
      {"tan(u)", {{1, 2}, {0, 1}}, false, false},       {"tan(u)", {{-1, 1}, {0, 1}}, true, true},
      {"asin(u)", {{0, 1}, {0, 1}}, false, false},      {"acosh(u)", {{1, 2}, {0, 1}}, false, false},
      {"u<v?u*u:v", {{-1, 1}, {-1, 1}}, false, false},  {"u<v?u*u:v", {{-2, -1}, {0, 1}}, true, true},
      {"(u>0)&&(v>0)", {{1, 2}, {1, 2}}, true, true},   {"(u>0)&&(v>0)", {{-1, 2}, {1, 2}}, false, false},
      {"sin(u)*v+u^3", {{-3, 3}, {-3, 3}}, true, true}, {"sqrt(u*u+v*v)", {{-1, 1}, {-1, 1}}, false, false},
      {"sqrt(u*u+v*v)", {{1, 2}, {-1, 1}}, true, true}, {"abs(u)*0+v", {{-1, 1}, {0, 1}}, true, false},
  };
  for (const Expect& e : cases) {
    INFO(e.text << " on [" << e.box.u.lo << ", " << e.box.u.hi << "] x [" << e.box.v.lo << ", " << e.box.v.hi
                << "]");
    const Program p = Program::compile({{"f", e.text}}, {"u", "v"}, {});
    const Interval x[2] = {e.box.u, e.box.v};
    IntervalJet2<2> r;
    p.interval_jets2<2>(x, &r);
    CHECK(r.lipschitz == e.lipschitz);
    CHECK(r.smooth == e.smooth);
  }
  // abs across its kink: Clarke's gradient [-1, 1] times the argument's
  const Program p = Program::compile({{"f", "abs(u)"}}, {"u", "v"}, {});
  const Interval x[2] = {{-1, 2}, {0, 1}};
  IntervalJet2<2> r;
  p.interval_jets2<2>(x, &r);
  CHECK(r.g[0].lo <= -1.0);
  CHECK(r.g[0].hi >= 1.0);
  CHECK(r.g[1].lo == 0.0);
  CHECK(r.g[1].hi == 0.0);
}

TEST_CASE("interval_jets1: the values, gradients and flags of interval_jets2, without the Hessian") {
  // The same operations on the same enclosures, bit for bit: only the Hessian steps are left out.
  std::mt19937_64 rng(18);
  int checked = 0;
  for (const char* text : kOps) {
    INFO(std::string(text));
    const Program p = Program::compile({{"f", text}}, {"u", "v"}, {});
    for (int b = 0; b < 100; ++b) {
      const Box box = random_box(rng);
      const Interval x[2] = {box.u, box.v};
      IntervalJet2<2> two;
      footpoint::formula::IntervalJet1<2> one;
      p.interval_jets2<2>(x, &two);
      p.interval_jets1<2>(x, &one);
      const auto same = [](const Interval& a, const Interval& b) {
        return (a.lo == b.lo || (std::isnan(a.lo) && std::isnan(b.lo))) &&
               (a.hi == b.hi || (std::isnan(a.hi) && std::isnan(b.hi))) && a.partial == b.partial;
      };
      CHECK(same(one.v, two.v));
      CHECK(same(one.g[0], two.g[0]));
      CHECK(same(one.g[1], two.g[1]));
      CHECK(one.lipschitz == two.lipschitz);
      CHECK(one.smooth == two.smooth);
      ++checked;
    }
  }
  CHECK(checked > 4000);
}

TEST_CASE("interval jets in one and three variables") {
  const Program p1 = Program::compile({{"x", "t^3-sin(t)"}}, {"t"}, {});
  const Interval t[1] = {{0.5, 0.75}};
  IntervalJet2<1> r1;
  p1.interval_jets2<1>(t, &r1);
  for (double s : {0.5, 0.6, 0.75}) {
    Jet2<1> j;
    p1.jets2<1>(&s, &j);
    CHECK(inside(j.v, r1.v));
    CHECK(inside(j.g[0], r1.g[0]));
    CHECK(inside(j.h[0][0], r1.h[0][0]));
  }
  const Program p3 = Program::compile({{"f", "x*y*z+exp(x-z)"}}, {"x", "y", "z"}, {});
  const Interval b[3] = {{0, 1}, {-1, 0}, {0.5, 1}};
  IntervalJet2<3> r3;
  p3.interval_jets2<3>(b, &r3);
  const double pt[3] = {0.3, -0.2, 0.9};
  Jet2<3> j3;
  p3.jets2<3>(pt, &j3);
  CHECK(inside(j3.v, r3.v));
  for (int i = 0; i < 3; ++i) {
    CHECK(inside(j3.g[i], r3.g[i]));
    for (int k = 0; k < 3; ++k) CHECK(inside(j3.h[i][k], r3.h[i][k]));
  }
}

TEST_CASE("next_up and next_down are the neighbouring doubles") {
  using footpoint::formula::next_down;
  using footpoint::formula::next_up;
  std::mt19937_64 rng(17);
  constexpr double inf = std::numeric_limits<double>::infinity();
  std::vector<double> xs = {0.0,
                            -0.0,
                            1.0,
                            -1.0,
                            0x1p-1074,
                            -0x1p-1074,
                            0x1p-1022,
                            std::numeric_limits<double>::max(),
                            -std::numeric_limits<double>::max(),
                            2.0,
                            0x1p52,
                            1e300};
  for (int i = 0; i < 2000; ++i) {
    std::uint64_t bits = rng();
    double x;
    std::memcpy(&x, &bits, sizeof x);
    if (std::isfinite(x)) xs.push_back(x);
  }
  for (double x : xs) {
    INFO(x);
    CHECK(next_up(x) == std::nextafter(x, inf));
    CHECK(next_down(x) == std::nextafter(x, -inf));
  }
  CHECK(next_up(inf) == inf);
  CHECK(next_down(-inf) == -inf);
  CHECK(next_up(-inf) == -std::numeric_limits<double>::max());
  CHECK(next_down(inf) == std::numeric_limits<double>::max());
  CHECK(std::isnan(next_up(std::numeric_limits<double>::quiet_NaN())));
  CHECK(std::isnan(next_down(-std::numeric_limits<double>::quiet_NaN())));
}

TEST_CASE("point enclosures of powers and of the C library's functions hold the long double value") {
  struct Fn {
    const char* text;
    long double (*exact)(long double);
    double lo, hi;  // argument range
  };
  const Fn fns[] = {
      {"exp(u)", [](long double x) { return std::exp(x); }, -700, 700},
      {"ln(u)", [](long double x) { return std::log(x); }, 1e-300, 1e300},
      {"log2(u)", [](long double x) { return std::log2(x); }, 1e-300, 1e300},
      {"log10(u)", [](long double x) { return std::log10(x); }, 1e-300, 1e300},
      {"sin(u)", [](long double x) { return std::sin(x); }, -1e6, 1e6},
      {"cos(u)", [](long double x) { return std::cos(x); }, -1e6, 1e6},
      {"tan(u)", [](long double x) { return std::tan(x); }, -1.5, 1.5},
      {"asin(u)", [](long double x) { return std::asin(x); }, -1, 1},
      {"acos(u)", [](long double x) { return std::acos(x); }, -1, 1},
      {"atan(u)", [](long double x) { return std::atan(x); }, -1e10, 1e10},
      {"sinh(u)", [](long double x) { return std::sinh(x); }, -700, 700},
      {"cosh(u)", [](long double x) { return std::cosh(x); }, -700, 700},
      {"tanh(u)", [](long double x) { return std::tanh(x); }, -20, 20},
      {"asinh(u)", [](long double x) { return std::asinh(x); }, -1e10, 1e10},
      {"acosh(u)", [](long double x) { return std::acosh(x); }, 1, 1e10},
      {"atanh(u)", [](long double x) { return std::atanh(x); }, -1, 1},
      {"u^2.37", [](long double x) { return std::pow(x, static_cast<long double>(2.37)); }, 0, 1e10},
      {"u^7", [](long double x) { return x * x * x * x * x * x * x; }, -1e40, 1e40},
      {"u^13", [](long double x) { return std::pow(x, 13.0L); }, -1e20, 1e20},
      {"sqrt(u)", [](long double x) { return std::sqrt(x); }, 0, 1e300},
  };
  std::mt19937_64 rng(18);
  for (const Fn& f : fns) {
    INFO(std::string(f.text));
    const Program p = Program::compile({{"f", f.text}}, {"u", "v"}, {});
    std::uniform_real_distribution<double> U(0.0, 1.0);
    for (int i = 0; i < 4000; ++i) {
      // uniform in the range, and log-uniform in magnitude for wide ranges
      double x = f.lo + (f.hi - f.lo) * U(rng);
      if (i % 2 && f.hi > 100.0)
        x = std::copysign(std::exp(std::log(f.hi) * U(rng)), f.lo < 0 ? U(rng) - 0.5 : 1.0);
      x = std::clamp(x, f.lo, f.hi);
      const Interval box[2] = {{x, x}, {0, 0}};
      Interval r;
      p.intervals(box, &r);
      const long double exact = f.exact(x);
      if (!std::isfinite(static_cast<double>(exact))) continue;
      INFO(x);
      CHECK(static_cast<long double>(r.lo) <= exact);
      CHECK(exact <= static_cast<long double>(r.hi));
    }
  }
}

TEST_CASE("sin and cos keep an extremum inside a short box near 1e9 and 1e11") {
  // Around the extrema 2πk + jπ/2 for k near 1e9 / 2π and 1e11 / 2π, boxes of 0-2 ulps on each
  // side of the nearest double: the ends are below 1 by ~1e-14 (1e-10 at 1e11), distinguishable,
  // while the rounding of the phase is about an ulp (a slack of 1e-12 misses ~2% of the peaks at
  // 1e11). The enclosure's top must reach the true maximum over the box (long double), 1 when the
  // peak lies inside.
  const Program ps = Program::compile({{"f", "sin(u)"}}, {"u", "v"}, {});
  const Program pc = Program::compile({{"f", "cos(u)"}}, {"u", "v"}, {});
  const long double two_pi = 6.283185307179586476925286766559L;
  int peaks_inside = 0;
  for (long long base : {159154943LL, 15915494309LL})
    for (long long k = base; k < base + 150; ++k)
      for (int quarter = 0; quarter < 4; ++quarter) {
        const long double extremum = two_pi * k + quarter * two_pi / 4;
        const double c = static_cast<double>(extremum);
        for (int n = 0; n < 9; ++n) {
          const double lo = footpoint::formula::down(c, n / 3), hi = footpoint::formula::up(c, n % 3);
          const Interval box[2] = {{lo, hi}, {0, 0}};
          Interval rs, rc;
          ps.intervals(box, &rs);
          pc.intervals(box, &rc);
          const bool in = lo <= extremum && extremum <= hi;
          peaks_inside += in;
          const long double s_lo = std::sin(static_cast<long double>(lo)),
                            s_hi = std::sin(static_cast<long double>(hi));
          const long double c_lo = std::cos(static_cast<long double>(lo)),
                            c_hi = std::cos(static_cast<long double>(hi));
          // quarter 0: cos max, 1: sin max, 2: cos min, 3: sin min
          const long double smax = in && quarter == 1 ? 1.0L : std::max(s_lo, s_hi);
          const long double smin = in && quarter == 3 ? -1.0L : std::min(s_lo, s_hi);
          const long double cmax = in && quarter == 0 ? 1.0L : std::max(c_lo, c_hi);
          const long double cmin = in && quarter == 2 ? -1.0L : std::min(c_lo, c_hi);
          INFO("k = " << k << ", quarter " << quarter << ", ulps " << n / 3 << " " << n % 3);
          CHECK(static_cast<long double>(rs.hi) >= smax);
          CHECK(static_cast<long double>(rs.lo) <= smin);
          CHECK(static_cast<long double>(rc.hi) >= cmax);
          CHECK(static_cast<long double>(rc.lo) <= cmin);
        }
      }
  CHECK(peaks_inside > 5000);
}
