// Cost per (u,v) of value + gradient + Hessian of all three components of a surface, against
// muparser's plain Eval() of the three values (issue 2's target: at most 1.5x).
// Prints the median of several runs of ns per evaluation.
#include <muParser.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <numbers>
#include <vector>

#include "bench_args.hpp"
#include "formula/program.hpp"

using namespace footpoint::formula;

namespace {

struct Surface {
  const char* name;
  const char* x;
  const char* y;
  const char* z;
};

constexpr int kEvals = 200000;
constexpr int kRuns = 7;

template <class F>
double median_ns(F&& body) {
  std::vector<double> runs;
  volatile double sink = 0;
  for (int r = 0; r < kRuns; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    double acc = 0;
    for (int i = 0; i < kEvals; ++i) acc += body(i);
    const auto t1 = std::chrono::steady_clock::now();
    sink = sink + acc;
    runs.push_back(std::chrono::duration<double, std::nano>(t1 - t0).count() / kEvals);
  }
  std::sort(runs.begin(), runs.end());
  return runs[kRuns / 2];
}

}  // namespace

int main(int argc, char** argv) {
  footpoint::bench::take_no_arguments(argc, argv,
                                      "usage: formula_bench (no arguments; prints a row per surface)\n");
  const Surface surfaces[] = {
      {"S1", "u+v", "sin(u)+2*cos(v)", "sin(u+v)"},
      {"S2", "u^4*v^3+u*v+u", "u^3+v^3", "u+v"},
      {"S3 ([Hybrid] Ex. 2, degree 6)",
       "u^6+u^5*v+v^6-u^2*v^3+u*v^4-v^5+u^4+u^3*v+v^4+u^3-u*v^2+v^3+u*v+v^2+1",
       "u^6+2*u^4*v^2-v^6+u^5+u^2*v^3+v^5+u^4-u*v^3+u^3-2*u*v^2+v^3+4*u*v+2*v^2+2*u+2*v+1",
       "u^6+u*v^5+u^4*v+u^2*v^3+u^3*v+2*u^2*v^2+v^4+u^3+2*u*v+u"},
  };
  std::printf("%-36s %14s %14s %14s %10s\n", "surface", "muparser 3 val", "tape 3 values", "tape jets2 x3",
              "jets/mu");
  for (const auto& s : surfaces) {
    double uv[2] = {0.3, 0.7};
    mu::Parser parsers[3];
    const char* texts[3] = {s.x, s.y, s.z};
    for (int k = 0; k < 3; ++k) {
      parsers[k].DefineVar("u", &uv[0]);
      parsers[k].DefineVar("v", &uv[1]);
      parsers[k].SetExpr(texts[k]);
      parsers[k].Eval();
    }
    const Program p = Program::compile({{"x", s.x}, {"y", s.y}, {"z", s.z}}, {"u", "v"}, {});
    auto point = [](int i, double* q) {
      q[0] = -1.0 + 2.0 * (i % 1000) / 1000.0;
      q[1] = -1.0 + 2.0 * (i % 997) / 997.0;
    };
    const double mu_ns = median_ns([&](int i) {
      point(i, uv);
      return parsers[0].Eval() + parsers[1].Eval() + parsers[2].Eval();
    });
    const double val_ns = median_ns([&](int i) {
      double q[2], out[3];
      point(i, q);
      p.values(q, out);
      return out[0] + out[1] + out[2];
    });
    const double jet_ns = median_ns([&](int i) {
      double q[2];
      Jet2<2> out[3];
      point(i, q);
      p.jets2<2>(q, out);
      return out[0].h[0][1] + out[1].g[0] + out[2].v;
    });
    std::printf("%-36s %11.1f ns %11.1f ns %11.1f ns %9.2fx\n", s.name, mu_ns, val_ns, jet_ns,
                jet_ns / mu_ns);
  }
  return 0;
}
