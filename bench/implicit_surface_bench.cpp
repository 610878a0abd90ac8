// Implicit surfaces f(x, y, z) = 0 in a box: medians over interleaved runs of the time per point
// of `auto` with its certificate (single thread, the thread's CPU time, bench/cpu_time.hpp) on
// random points of the box, each run on a geometry compiled afresh (its leaves' enclosures are
// kept on first use, within the timed run) and again on the same points (`warm`: the enclosures
// kept), the share of certified answers, the compile time (interval subdivision, samples, edges
// and singular points included), and Newton on the Lagrange system from p for comparison (its
// mean iterations). Targets (issue 34): `auto` with its certificate
// <= 10 us per point, >= 99 % certified, compile <= 50 ms.
#include <algorithm>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "compiled/implicit_surface_geometry.hpp"
#include "cpu_time.hpp"

using namespace footpoint;

namespace {

constexpr int kRuns = 5;
constexpr int kPoints = 2000;

double median(std::vector<double> t) {
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

struct SurfaceCase {
  const char* name;
  const char* equation;
  std::array<std::array<double, 2>, 3> box;
};

// With --checksum: the sum of auto's distances and of its feet's coordinates over the points,
// to compare the answers of two builds.
bool checksum = false;

void row(const SurfaceCase& c) {
  GeometryDefinition def;
  def.type = GeometryType::implicit_surface;
  def.formulas = {{"equation", c.equation}};
  def.domain = {{"x", c.box[0]}, {"y", c.box[1]}, {"z", c.box[2]}};
  std::mt19937_64 rng(5);
  std::vector<double> points(3 * kPoints);
  for (std::size_t i = 0; i < points.size(); ++i)
    points[i] = std::uniform_real_distribution<double>(c.box[i % 3][0], c.box[i % 3][1])(rng);
  std::vector<double> compile, t_auto, t_warm, t_newton;
  std::shared_ptr<const CompiledGeometry> g;
  int certified = 0, newton_converged = 0, newton_iterations = 0;
  double sum = 0.0;
  for (int r = 0; r < kRuns; ++r) {
    double t0 = bench::thread_cpu_ns();
    g = compile_geometry(def);
    compile.push_back((bench::thread_cpu_ns() - t0) * 1e-6);
    const GeometryMethod a = g->method("auto").value(), n = g->method("lagrange_newton").value();
    certified = newton_converged = newton_iterations = 0;
    t0 = bench::thread_cpu_ns();
    sum = 0.0;
    for (int i = 0; i < kPoints; ++i) {
      const ProjectionResult r = a.project(&points[static_cast<std::size_t>(3 * i)], {});
      certified += r.summary.certificate.certified ? 1 : 0;
      sum += r.distance + r.foot[0] + r.foot[1] + r.foot[2];
    }
    t_auto.push_back((bench::thread_cpu_ns() - t0) * 1e-3 / kPoints);
    t0 = bench::thread_cpu_ns();
    for (int i = 0; i < kPoints; ++i) a.project(&points[static_cast<std::size_t>(3 * i)], {});
    t_warm.push_back((bench::thread_cpu_ns() - t0) * 1e-3 / kPoints);
    t0 = bench::thread_cpu_ns();
    for (int i = 0; i < kPoints; ++i) {
      const ProjectionResult r = n.project(&points[static_cast<std::size_t>(3 * i)], {});
      if (r.summary.status == Status::converged) {
        ++newton_converged;
        newton_iterations += r.summary.iterations;
      }
    }
    t_newton.push_back((bench::thread_cpu_ns() - t0) * 1e-3 / kPoints);
  }
  const auto& s = dynamic_cast<const ImplicitSurface&>(*g);
  std::printf("%-16s %10.2f %7zu %11.2f %8.2f %9.1f%% %11.2f %9.1f%% %8.2f\n", c.name, median(compile),
              s.cells().leaves, median(t_auto), median(t_warm), 100.0 * certified / kPoints, median(t_newton),
              100.0 * newton_converged / kPoints,
              static_cast<double>(newton_iterations) / std::max(1, newton_converged));
  if (checksum) std::printf("%-16s checksum %.17g\n", c.name, sum);
}

}  // namespace

// Arguments: the cases to run (a case runs when its name starts with one of them; none: all), and
// --checksum.
int main(int argc, char** argv) {
  std::vector<std::string> names;
  for (int i = 1; i < argc; ++i) {
    if (std::string(argv[i]) == "--checksum")
      checksum = true;
    else
      names.emplace_back(argv[i]);
  }
  std::printf("[%s]\n", bench::load_average().c_str());
  std::printf("%-16s %10s %7s %11s %8s %10s %11s %10s %8s\n", "implicit surface", "compile ms", "leaves",
              "us/pt auto", "warm", "certified", "us/pt LN", "LN conv", "LN its");
  const SurfaceCase cases[] = {
      {"sphere", "x^2+y^2+z^2-1", {{{-2, 2}, {-2, 2}, {-2, 2}}}},
      {"ellipsoid", "x^2/4+y^2+4*z^2-1", {{{-3, 3}, {-3, 3}, {-3, 3}}}},
      {"torus", "(x^2+y^2+z^2+3.75)^2-16*(x^2+y^2)", {{{-3, 3}, {-3, 3}, {-1, 1}}}},
      {"cone (apex)", "x^2+y^2-z^2", {{{-1, 1}, {-1, 1}, {0, 1}}}},
      {"hyperboloid 1", "x^2+y^2-z^2-1", {{{-3, 3}, {-3, 3}, {-3, 3}}}},
      {"hyperboloid 2", "z^2-x^2-y^2-1", {{{-3, 3}, {-3, 3}, {-3, 3}}}},
      {"Goursat", "x^4+y^4+z^4-5*(x^2+y^2+z^2)+11.8", {{{-3, 3}, {-3, 3}, {-3, 3}}}},
  };
  for (const auto& c : cases) {
    bool chosen = names.empty();
    for (const std::string& n : names) chosen = chosen || std::string(c.name).rfind(n, 0) == 0;
    if (chosen) row(c);
  }
}
