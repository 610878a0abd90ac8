// Exact derivatives of the formula tape against sympy references (tests/data/formula_refs.json,
// 40-digit symbolic differentiation) and against identities that hold to rounding.
#include <doctest/doctest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>

#include "formula/program.hpp"

using footpoint::formula::Jet2;
using footpoint::formula::Jet3;
using footpoint::formula::Program;

namespace {

Program compile1(const std::string& text, const std::vector<std::string>& vars = {"x", "y"},
                 const std::map<std::string, double>& constants = {}) {
  return Program::compile({{"f", text}}, vars, constants);
}

// |got - want| <= 1e-13 relative to max(|want|, 1).
void check_close(double got, double want, const std::string& what) {
  INFO(what << ": got " << got << " want " << want);
  CHECK(std::fabs(got - want) <= 1e-13 * std::max(1.0, std::fabs(want)));
}

}  // namespace

TEST_CASE("jets of every function and operator match sympy's exact partials to 1e-13") {
  std::ifstream in(FOOTPOINT_TESTS_DIR "/data/formula_refs.json");
  REQUIRE(in);
  const auto refs = nlohmann::json::parse(in);
  REQUIRE(refs["cases"].size() >= 25);
  for (const auto& c : refs["cases"]) {
    const std::string text = c["formula"];
    const auto constants = c["constants"].get<std::map<std::string, double>>();
    const Program p = compile1(text, {"x", "y"}, constants);
    const double pt[2] = {c["point"][0], c["point"][1]};
    const std::string where = text + " at (" + std::to_string(pt[0]) + "," + std::to_string(pt[1]) + ")";
    double value;
    p.values(pt, &value);
    check_close(value, c["value"], where + " value");
    Jet2<2> j2;
    p.jets2<2>(pt, &j2);
    Jet3<2> j3;
    p.jets3<2>(pt, &j3);
    check_close(j2.v, c["value"], where + " jet2 value");
    check_close(j3.v, c["value"], where + " jet3 value");
    for (int i = 0; i < 2; ++i) {
      check_close(j2.g[i], c["gradient"][i], where + " d/d" + "xy"[i]);
      check_close(j3.g[i], c["gradient"][i], where + " jet3 d/d" + "xy"[i]);
      for (int k = 0; k < 2; ++k) {
        check_close(j2.h[i][k], c["hessian"][i][k], where + " second partial");
        check_close(j3.h[i][k], c["hessian"][i][k], where + " jet3 second partial");
        for (int l = 0; l < 2; ++l) check_close(j3.t[i][k][l], c["third"][i][k][l], where + " third partial");
      }
    }
  }
}

TEST_CASE("a function composed with its inverse has the jet of its argument") {
  // w = x*y + x has gradient (y+1, x), Hessian [[0,1],[1,0]] and no third derivatives.
  const char* identities[] = {"asin(sin(x*y+x))",   "acos(cos(x*y+x))",       "atan(tan(x*y+x))",
                              "asinh(sinh(x*y+x))", "acosh(cosh(x*y+x))",     "atanh(tanh(x*y+x))",
                              "ln(exp(x*y+x))",     "exp(ln(x*y+x))",         "sqrt(x*y+x)^2",
                              "2^log2(x*y+x)",      "10^log10(x*y+x)",        "((x*y+x)^3)^(1/3)",
                              "abs(-(x*y+x))",      "(x*y+x)*(x*y+x)/(x*y+x)"};
  const double pt[2] = {0.35, 0.6};
  for (const char* text : identities) {
    INFO(text);
    const Program p = compile1(text);
    Jet3<2> j;
    p.jets3<2>(pt, &j);
    const double w = pt[0] * pt[1] + pt[0];
    check_close(j.v, w, std::string(text) + " value");
    check_close(j.g[0], pt[1] + 1.0, "d/dx");
    check_close(j.g[1], pt[0], "d/dy");
    check_close(j.h[0][0], 0.0, "xx");
    check_close(j.h[0][1], 1.0, "xy");
    check_close(j.h[1][0], 1.0, "yx");
    check_close(j.h[1][1], 0.0, "yy");
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b)
        for (int c = 0; c < 2; ++c) check_close(j.t[a][b][c], 0.0, "third");
  }
}

TEST_CASE("powers with constant exponents use the power rule, also for negative bases") {
  const Program p = compile1("x^6 + y^3", {"x", "y"});
  const double pt[2] = {-1.5, -2.0};
  Jet3<2> j;
  p.jets3<2>(pt, &j);
  CHECK(j.v == std::pow(-1.5, 6) + std::pow(-2.0, 3));
  CHECK(j.g[0] == doctest::Approx(6 * std::pow(-1.5, 5)).epsilon(1e-15));
  CHECK(j.h[0][0] == doctest::Approx(30 * std::pow(-1.5, 4)).epsilon(1e-15));
  CHECK(j.t[0][0][0] == doctest::Approx(120 * std::pow(-1.5, 3)).epsilon(1e-15));
  CHECK(j.t[1][1][1] == 6.0);
  // At zero: x^2 has second derivative 2 and third derivative 0, not NaN.
  const Program q = compile1("x^2*y", {"x", "y"});
  const double zero[2] = {0.0, 0.0};
  q.jets3<2>(zero, &j);
  CHECK(j.h[0][0] == 0.0);
  CHECK(j.t[0][0][1] == 2.0);
}

TEST_CASE("one-sided conventions where derivatives do not exist are finite") {
  const Program p = compile1("abs(x) + sign(y) + min(x, y) + max(x, y)");
  const double pt[2] = {0.0, 0.0};
  Jet2<2> j;
  p.jets2<2>(pt, &j);
  CHECK(std::isfinite(j.v));
  CHECK(j.g[0] == 1.0 + 1.0 + 1.0);  // abs'(0) = +1; min and max take their first argument at ties
  CHECK(j.g[1] == 0.0);
}

TEST_CASE("precedence follows muparser: -x^2 is -(x^2), 2^3^2 is 512") {
  const Program p = compile1("-x^2 + 2^3^2");
  const double pt[2] = {3.0, 0.0};
  double v;
  p.values(pt, &v);
  CHECK(v == -9.0 + 512.0);
}

TEST_CASE("_pi and _e have full double precision") {
  const Program p = compile1("_pi + 0*x", {"x"});
  const double pt[1] = {0.0};
  double v;
  p.values(pt, &v);
  CHECK(v == 3.141592653589793);
  const Program e = compile1("_e", {"x"});
  e.values(pt, &v);
  CHECK(v == 2.718281828459045);
}

TEST_CASE("several formulas share one tape and common subexpressions") {
  const Program p =
      Program::compile({{"x", "u+v"}, {"y", "sin(u)+2*cos(v)"}, {"z", "sin(u+v)"}}, {"u", "v"}, {});
  CHECK(p.num_outputs() == 3);
  CHECK(p.num_inputs() == 2);
  // u, v, u+v, sin(u), cos(v), 2*cos(v), sin(u)+2cos(v), sin(u+v): u+v appears once and the
  // constant 2 is absorbed into a multiply-by-constant node.
  CHECK(p.num_nodes() == 8);
  const double pt[2] = {0.3, -0.8};
  Jet2<2> j[3];
  p.jets2<2>(pt, j);
  CHECK(j[2].v == std::sin(0.3 - 0.8));
  CHECK(j[1].h[1][1] == -2.0 * std::cos(-0.8));
  CHECK(j[2].h[0][1] == -std::sin(0.3 - 0.8));
}

TEST_CASE("two-variable jets (paired arithmetic) agree with the generic third-order jets, op by op") {
  // jets2<2> runs its own arithmetic on pairs of doubles (program.cpp, Jet2PairArith); jets3 runs
  // the generic rules. Every op on the tape, at many points: value, gradient and Hessian agree to a
  // few ulps of the jet's largest entry, and the Hessian is symmetric.
  const char* formulas[] = {"x*y - x/y + 3*x - y/4 + 5 - (2 - x)",
                            "x^3*y^-2 + (x*y)^2.5 + 2^x + 7/(1 + x*x)",
                            "sqrt(x*y) + exp(x-y) + ln(x+y) + log2(x*y) + log10(3*x)",
                            "sin(x*y) + cos(x/y) + tan(0.3*x*y)",
                            "asin(0.2*x*y) + acos(0.3*x-0.1*y) + atan(x/y)",
                            "sinh(x-y) + cosh(x*y) + tanh(x/y)",
                            "asinh(x*y) + acosh(1+x*y) + atanh(0.2*x*y)",
                            "abs(x-y)*y + sign(x-y)*x^2 + min(x*y, x+y) + max(x, y^2)",
                            "x > y ? x^2*y : y^3 - x",
                            "(x < y) + (x >= y)*x + (x != y)*y + (x*y > 1 && x < 2)*x*y",
                            "-x*(-y) + -(x/y)"};
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> coord(0.2, 1.8);
  for (const char* text : formulas) {
    const Program p = compile1(text);
    for (int trial = 0; trial < 200; ++trial) {
      const double pt[2] = {coord(rng), coord(rng)};
      Jet2<2> j2;
      Jet3<2> j3;
      p.jets2<2>(pt, &j2);
      p.jets3<2>(pt, &j3);
      double scale = std::max(1.0, std::fabs(j3.v));
      for (int a = 0; a < 2; ++a) {
        scale = std::max(scale, std::fabs(j3.g[a]));
        for (int b = 0; b < 2; ++b) scale = std::max(scale, std::fabs(j3.h[a][b]));
      }
      INFO(text << " at (" << pt[0] << ", " << pt[1] << ")");
      const double tol = 64 * 1e-16 * scale;
      CHECK(std::fabs(j2.v - j3.v) <= tol);
      for (int a = 0; a < 2; ++a) {
        CHECK(std::fabs(j2.g[a] - j3.g[a]) <= tol);
        for (int b = 0; b < 2; ++b) CHECK(std::fabs(j2.h[a][b] - j3.h[a][b]) <= tol);
      }
      CHECK(j2.h[0][1] == j2.h[1][0]);
    }
  }
}
