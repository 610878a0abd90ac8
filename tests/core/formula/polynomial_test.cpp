// Sums of monomials: jets2 evaluates them term by term (core/formula/polynomial.cpp). Their
// values against sympy are in program_test.cpp (the reference file has such formulas);
// here: which formulas qualify, and agreement with the tape's own jets (jets3 always runs the tape)
// over many points in one, two and three variables.
#include <doctest/doctest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "formula/program.hpp"

using footpoint::formula::Jet2;
using footpoint::formula::Jet3;
using footpoint::formula::NamedFormula;
using footpoint::formula::Program;

namespace {

// Scale of a jet entry's rounding error: the sum of the magnitudes of its terms is not known
// here, so compare relative to the largest entry of the jet (and 1).
template <int N>
double jet_scale(const Jet3<N>& j) {
  double s = std::max(1.0, std::fabs(j.v));
  for (int a = 0; a < N; ++a) {
    s = std::max(s, std::fabs(j.g[a]));
    for (int b = 0; b < N; ++b) s = std::max(s, std::fabs(j.h[a][b]));
  }
  return s;
}

template <int N>
void check_against_tape(const std::vector<std::string>& formulas, const std::vector<std::string>& vars) {
  std::vector<NamedFormula> named;
  for (std::size_t k = 0; k < formulas.size(); ++k) {
    std::string name = "f";  // (not "f" + to_string: GCC 12 warns -Wrestrict there, a false positive)
    name += std::to_string(k);
    named.push_back({name, formulas[k]});
  }
  const Program p = Program::compile(named, vars, {{"R", 2.5}});
  REQUIRE(p.sum_of_monomials());
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> coord(-1.7, 1.7);
  std::vector<Jet2<N>> j2(formulas.size());
  std::vector<Jet3<N>> j3(formulas.size());
  for (int trial = 0; trial < 500; ++trial) {
    double x[N];
    for (double& xi : x) xi = coord(rng);
    p.jets2<N>(x, j2.data());
    p.jets3<N>(x, j3.data());
    for (std::size_t k = 0; k < formulas.size(); ++k) {
      INFO(formulas[k] << " at trial " << trial);
      const double tol = 1e-14 * jet_scale(j3[k]) * 16;  // a few ulps of the largest entry
      CHECK(std::fabs(j2[k].v - j3[k].v) <= tol);
      for (int a = 0; a < N; ++a) {
        CHECK(std::fabs(j2[k].g[a] - j3[k].g[a]) <= tol);
        for (int b = 0; b < N; ++b) CHECK(std::fabs(j2[k].h[a][b] - j3[k].h[a][b]) <= tol);
      }
    }
  }
}

}  // namespace

TEST_CASE("which formulas are evaluated as sums of monomials") {
  auto qualifies = [](const std::string& f) {
    return Program::compile({{"f", f}}, {"u", "v"}, {{"R", 2.0}}).sum_of_monomials();
  };
  CHECK(qualifies("u^4*v^3+u*v+u"));
  CHECK(qualifies("1 - (u^2*v - 3*u) - v^3/4 + u*(-v)^2*R"));
  CHECK(qualifies("-(u^3 - 2*v) + 4 - u*v"));
  CHECK(qualifies("(2*u*v^2)^3 - u^7 + 5"));
  CHECK(qualifies("7"));
  CHECK(qualifies("u^64"));
  // A product or constant multiple of a sum, a sum of two sums (another order of summation),
  // other functions, negative or too high powers: the tape.
  CHECK_FALSE(qualifies("(u+v)^2"));
  CHECK_FALSE(qualifies("2*(u+v)"));
  CHECK_FALSE(qualifies("u*(v+1)"));
  CHECK_FALSE(qualifies("(u+1)+(v+1)"));
  CHECK_FALSE(qualifies("u^2+sin(v)"));
  CHECK_FALSE(qualifies("u^-2+v"));
  CHECK_FALSE(qualifies("u^65"));
  CHECK_FALSE(qualifies("u/v"));
  // All formulas of a program or none.
  CHECK_FALSE(Program::compile({{"x", "u+v"}, {"y", "sin(u)"}}, {"u", "v"}, {}).sum_of_monomials());
}

TEST_CASE("term-by-term jets agree with the tape's jets in one, two and three variables") {
  check_against_tape<1>({"t^5 - 2*t + 1", "3*t^2", "-(t^3 - t) + 0.5"}, {"t"});
  check_against_tape<2>({"u^4*v^3+u*v+u", "u^3+v^3", "u+v",
                         "u^6+u^5*v+v^6-u^2*v^3+u*v^4-v^5+u^4+u^3*v+v^4+u^3-u*v^2+v^3+u*v+v^2+1",
                         "u^6+2*u^4*v^2-v^6+u^5+u^2*v^3+v^5+u^4-u*v^3+u^3-2*u*v^2+v^3+4*u*v+2*v^2+2*u+2*v+1",
                         "1 - (u^2*v - 3*u) - v^3/4 + u*(-v)^2*R"},
                        {"u", "v"});
  check_against_tape<3>({"x^2*y*z - 3*z^4 + y", "x^2+y^2+z^2-R^2", "-(x*y*z)^2 + x - z"}, {"x", "y", "z"});
}
