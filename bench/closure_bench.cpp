// The closure checks (parametric/geometry/surface_closure.hpp, parametric/geometry/curve_closure.hpp) per
// geometry: medians of the thread's CPU time of one detection, beside the time of compiling the whole
// geometry (which includes it). Target: well under 1 ms for the papers' surfaces.
#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "bench_args.hpp"
#include "compiled/compiled_geometry.hpp"
#include "cpu_time.hpp"
#include "parametric/geometry/curve_closure.hpp"
#include "parametric/geometry/surface_closure.hpp"

using namespace footpoint;

namespace {

constexpr int kRuns = 21;

template <class F>
double median_us(F&& run) {
  std::vector<double> t;
  for (int r = 0; r < kRuns; ++r) {
    const double t0 = bench::thread_cpu_ns();
    run();
    t.push_back((bench::thread_cpu_ns() - t0) * 1e-3);
  }
  return bench::percentile(t, 0.5);
}

struct Surface {
  const char *name, *x, *y, *z;
  ParamBox box;
};

struct Curve {
  const char *name, *x, *y, *z;
  ParamInterval domain;
};

constexpr double kTwoPi = 6.283185307179586;

}  // namespace

int main(int argc, char** argv) {
  bench::take_no_arguments(argc, argv, "usage: closure_bench (no arguments; prints a row per geometry)\n");
  const Surface surfaces[] = {
      {"[GSA] Ex. 1 over [-25,25]^2", "u+v", "sin(u)+2*cos(v)", "sin(u+v)", {-25, 25, -25, 25}},
      {"[GSA] Ex. 2", "u^4*v^3+u*v+u", "u^3+v^3", "u+v", {-5, 5, -5, 5}},
      {"[Hybrid] Ex. 1", "u+2*v", "cos(u+v)", "sin(u+v)", {-2, 2, -2, 2}},
      {"[Hybrid] Ex. 2 (degree 6)",
       "u^6+u^5*v+v^6-u^2*v^3+u*v^4-v^5+u^4+u^3*v+v^4+u^3-u*v^2+v^3+u*v+v^2+1",
       "u^6+2*u^4*v^2-v^6+u^5+u^2*v^3+v^5+u^4-u*v^3+u^3-2*u*v^2+v^3+4*u*v+2*v^2+2*u+2*v+1",
       "u^6+u*v^5+u^4*v+u^2*v^3+u^3*v+2*u^2*v^2+v^4+u^3+2*u*v+u",
       {0, 2, 0, 2}},
      {"[Hybrid] C3", "u", "v", "cos(u+v)", {0, 2, 0, 2}},
      {"torus (2 seams)",
       "(2+0.5*cos(v))*cos(u)",
       "(2+0.5*cos(v))*sin(u)",
       "0.5*sin(v)",
       {0, kTwoPi, 0, kTwoPi}},
      {"sphere (seam, 2 poles)",
       "cos(u)*cos(v)",
       "sin(u)*cos(v)",
       "sin(v)",
       {0, kTwoPi, -kTwoPi / 4, kTwoPi / 4}},
      {"cone (seam, apex)", "v*cos(u)", "v*sin(u)", "v", {0, kTwoPi, 0, 1}},
      {"Moebius band (reversed seam)",
       "(1+v*cos(u/2))*cos(u)",
       "(1+v*cos(u/2))*sin(u)",
       "v*sin(u/2)",
       {0, kTwoPi, -0.5, 0.5}},
  };
  std::printf("closure detection, median of %d runs, thread CPU time (%s)\n", kRuns,
              bench::load_average().c_str());
  std::printf("%-32s %12s %14s\n", "surface", "detect (us)", "compile (us)");
  for (const Surface& s : surfaces) {
    const SurfaceFormulas f(formula::Program::compile({{"x", s.x}, {"y", s.y}, {"z", s.z}}, {"u", "v"}, {}));
    const double detect = median_us([&] { detect_surface_closure(f, s.box); });
    GeometryDefinition def;
    def.formulas = {{"x", s.x}, {"y", s.y}, {"z", s.z}};
    def.domain = {{"u", {s.box.umin, s.box.umax}}, {"v", {s.box.vmin, s.box.vmax}}};
    const double compile = median_us([&] { compile_geometry(def); });
    std::printf("%-32s %12.1f %14.1f\n", s.name, detect, compile);
  }
  const Curve curves[] = {
      {"circle", "cos(t)", "sin(t)", "", {0, kTwoPi}},
      {"trefoil", "sin(t)+2*sin(2*t)", "cos(t)-2*cos(2*t)", "-sin(3*t)", {0, kTwoPi}},
      {"helix", "cos(t)", "sin(t)", "0.2*t", {0, 2 * kTwoPi}},
  };
  std::printf("%-32s %12s\n", "curve", "detect (us)");
  for (const Curve& c : curves) {
    std::vector<formula::NamedFormula> formulas = {{"x", c.x}, {"y", c.y}};
    if (*c.z) formulas.push_back({"z", c.z});
    const CurveFormulas f(formula::Program::compile(formulas, {"t"}, {}));
    std::printf("%-32s %12.1f\n", c.name, median_us([&] { detect_curve_closure(f, c.domain); }));
  }
}
