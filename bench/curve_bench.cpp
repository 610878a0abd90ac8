// Curves (issue 4): medians of the time per projected point, single thread, with the compiled
// curve (its samples and k-d tree) built once, and of the time to compile + discover a curve.
// Targets: [Curve] Examples 1 and 2 with random points in [-300, 300]^3, `auto`
// <= 20 us per point and compile + discovery <= 50 ms; parametric helix and trefoil, `auto`
// <= 3 us per point.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "compiled/implicit_curve_geometry.hpp"
#include "compiled/parametric_curve_geometry.hpp"

using namespace footpoint;

namespace {

constexpr int kRuns = 7;

template <class F>
double median(F&& run) {
  std::vector<double> t;
  t.reserve(kRuns);
  for (int r = 0; r < kRuns; ++r) t.push_back(run());
  std::sort(t.begin(), t.end());
  return t[kRuns / 2];
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

std::vector<double> random_points(int n, int dim, double lo, double hi, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(lo, hi);
  std::vector<double> p(static_cast<std::size_t>(n * dim));
  for (double& v : p) v = u(rng);
  return p;
}

// Median over runs of the mean time per point of `method` over the points (us), and the share
// of converged results.
double per_point_us(const CompiledGeometry& g, const std::vector<double>& points, const char* method,
                    double& converged) {
  const int dim = g.point_dim();
  const std::size_t n = points.size() / static_cast<std::size_t>(dim);
  std::size_t ok = 0;
  const GeometryMethod m = g.method(method).value();
  const double s = median([&] {
    ok = 0;
    const auto t0 = std::chrono::steady_clock::now();
    for (std::size_t i = 0; i < n; ++i)
      ok += m.project(&points[i * static_cast<std::size_t>(dim)], {}).summary.converged() ? 1 : 0;
    return seconds_since(t0) / static_cast<double>(n);
  });
  converged = static_cast<double>(ok) / static_cast<double>(n);
  return s * 1e6;
}

GeometryDefinition implicit(const char* f1, const char* f2, double b) {
  GeometryDefinition def;
  def.type = GeometryType::implicit_curve;
  def.formulas = {{"equations[0]", f1}, {"equations[1]", f2}};
  def.domain = {{"x", {-b, b}}, {"y", {-b, b}}, {"z", {-b, b}}};
  return def;
}

GeometryDefinition parametric(const char* x, const char* y, const char* z, double t0, double t1) {
  GeometryDefinition def;
  def.type = GeometryType::parametric_curve;
  def.formulas = {{"x", x}, {"y", y}, {"z", z}};
  def.domain = {{"t", {t0, t1}}};
  return def;
}

}  // namespace

int main() {
  std::printf("%-34s %12s %10s %14s %10s\n", "curve", "compile ms", "samples", "auto us/pt", "converged");
  struct Implicit {
    const char* name;
    const char* f1;
    const char* f2;
  };
  const Implicit examples[] = {
      {"paper C Example 1", "x^2/9+y^2/16+z^2/9-1", "x^2+y^2-4*z"},
      {"paper C Example 2", "x^2/9+y^2/16+z^2/9+4*x*y-1", "x^2+y^2+x-4*z"},
  };
  const std::vector<double> far = random_points(20000, 3, -300.0, 300.0, 1);
  for (const auto& e : examples) {
    const GeometryDefinition def = implicit(e.f1, e.f2, 300.0);
    std::shared_ptr<const CompiledGeometry> g;
    const double compile_ms = 1e3 * median([&] {
                                const auto t0 = std::chrono::steady_clock::now();
                                g = compile_implicit_curve(def, {});
                                return seconds_since(t0);
                              });
    const auto& curve = dynamic_cast<const ImplicitCurve&>(*g);
    double converged = 0.0;
    const double us = per_point_us(*g, far, "auto", converged);
    std::printf("%-34s %12.2f %10zu %14.2f %9.1f%%\n", e.name, compile_ms, curve.discovery().samples.size(),
                us, 100.0 * converged);
    const std::vector<double> few(far.begin(), far.begin() + std::ptrdiff_t{3} * 500);
    for (const char* m : {"simplified", "complete"}) {
      const double paper_us = per_point_us(*g, few, m, converged);
      std::printf("  %-32s %12s %10s %14.2f %9.1f%%\n", m, "", "", paper_us, 100.0 * converged);
    }
  }

  struct Param {
    const char* name;
    const char* x;
    const char* y;
    const char* z;
    double t1;
  };
  const Param curves[] = {
      {"helix (2 turns)", "cos(t)", "sin(t)", "0.2*t", 4.0 * 3.141592653589793},
      {"trefoil", "sin(t)+2*sin(2*t)", "cos(t)-2*cos(2*t)", "-sin(3*t)", 2.0 * 3.141592653589793},
  };
  const std::vector<double> near = random_points(20000, 3, -4.0, 4.0, 2);
  for (const auto& c : curves) {
    const GeometryDefinition def = parametric(c.x, c.y, c.z, 0.0, c.t1);
    std::shared_ptr<const CompiledGeometry> g;
    const double compile_ms = 1e3 * median([&] {
                                const auto t0 = std::chrono::steady_clock::now();
                                g = compile_parametric_curve(def, {});
                                return seconds_since(t0);
                              });
    const auto& curve = dynamic_cast<const ParametricCurve&>(*g);
    double converged = 0.0;
    const double us = per_point_us(*g, near, "auto", converged);
    std::printf("%-34s %12.2f %10zu %14.2f %9.1f%%\n", c.name, compile_ms, curve.samples().size(), us,
                100.0 * converged);
  }
  return 0;
}
