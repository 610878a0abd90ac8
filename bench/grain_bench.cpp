// What sizing grains by time costs a batch (batch/thread_pool.hpp): project_batch of 100,000
// points on pools of 2 workers whose grains aim at ThreadPool::kDefaultGrainTime against pools
// whose grains aim at an hour, which makes every grain after the first few the batch's maximum
// (1,024 points): the fixed chunks the pool used before. Interleaved runs, wall time, medians.
// Geometries from cheap points to dear ones, where a grain's fixed cost weighs most to least:
// the unit circle with `newton` (a handful of iterations per point), the torus with `auto`, and
// the [GSA] Example 1 surface over [-3,3]^2 with `auto` (bench/http_bench.sh's S1 and points).
//
// Usage: grain_bench [runs, default 7] [points, default 100000]
#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "batch/batch.hpp"
#include "bench_args.hpp"
#include "footpoint.hpp"

using namespace footpoint;
using Clock = std::chrono::steady_clock;

namespace {

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

struct Case {
  const char* name;
  GeometryDefinition definition;
  const char* method;
};

GeometryDefinition definition(GeometryType type, std::vector<std::pair<std::string, std::string>> formulas,
                              std::vector<std::pair<std::string, std::array<double, 2>>> domain) {
  GeometryDefinition d;
  d.type = type;
  for (auto& [name, text] : formulas) d.formulas.push_back({name, text});
  for (auto& [name, range] : domain) d.domain.push_back({name, {range[0], range[1]}});
  return d;
}

}  // namespace

int main(int argc, char** argv) {
  const char* usage =
      "usage: grain_bench [runs, default 7] [points, default 100000]\n"
      "  project_batch on 2 workers with grains sized by time against fixed 1,024-point chunks\n";
  bench::exit_on_help(argc, argv, usage);
  if (argc > 3) bench::refuse_argument(argv[0], "unexpected argument", argv[3], usage);
  const int runs = argc > 1 ? static_cast<int>(bench::count_argument(argv[0], argv[1], usage)) : 7;
  const std::size_t count =
      argc > 2 ? static_cast<std::size_t>(bench::count_argument(argv[0], argv[2], usage)) : 100000;
  const double two_pi = 6.283185307179586;
  const std::vector<Case> cases{
      {"circle, newton",
       definition(GeometryType::parametric_curve, {{"x", "cos(t)"}, {"y", "sin(t)"}}, {{"t", {-3.0, 3.0}}}),
       "newton"},
      {"torus, auto",
       definition(GeometryType::parametric_surface,
                  {{"x", "(2+0.5*cos(v))*cos(u)"}, {"y", "(2+0.5*cos(v))*sin(u)"}, {"z", "0.5*sin(v)"}},
                  {{"u", {0.0, two_pi}}, {"v", {0.0, two_pi}}}),
       "auto"},
      {"[GSA] Ex. 1 [-3,3]^2, auto",
       definition(GeometryType::parametric_surface,
                  {{"x", "u+v"}, {"y", "sin(u)+2*cos(v)"}, {"z", "sin(u+v)"}},
                  {{"u", {-3.0, 3.0}}, {"v", {-3.0, 3.0}}}),
       "auto"},
  };
  std::printf(
      "grain_bench: %zu points, 2 workers, grains of %lld us against fixed chunks, medians of %d "
      "interleaved runs\n",
      count, static_cast<long long>(ThreadPool::kDefaultGrainTime.count()), runs);
  ThreadPool by_time(2), fixed(2, std::chrono::hours(1));
  for (const Case& c : cases) {
    const auto geometry = compile_geometry(c.definition);
    const int dim = geometry->point_dim();
    std::mt19937_64 rng(42);
    std::uniform_real_distribution<double> U(-1.0, 1.0);
    std::vector<double> coords(count * static_cast<std::size_t>(dim));
    const double scale = c.definition.type == GeometryType::parametric_curve ? 2.0 : 20.0;
    for (std::size_t i = 0; i < coords.size(); ++i) coords[i] = U(rng) * (i % 3 == 0 ? scale : 3.0);
    BatchRequest request{geometry->method(c.method).value()};
    request.points = coords.data();
    request.count = count;
    std::vector<double> t_time, t_fixed, ratio;
    for (int r = 0; r < runs; ++r)
      for (ThreadPool* pool : {&by_time, &fixed}) {
        const auto t0 = Clock::now();
        const auto results = project_batch(*pool, request);
        const double s = std::chrono::duration<double>(Clock::now() - t0).count();
        if (results.size() != count) std::abort();
        (pool == &by_time ? t_time : t_fixed).push_back(s);
        if (pool == &fixed) ratio.push_back(t_time.back() / s);
      }
    std::printf("  %-28s by time %9.0f points/s, fixed %9.0f points/s, time/fixed %.3f (pairs %.3f-%.3f)\n",
                c.name, static_cast<double>(count) / median(t_time),
                static_cast<double>(count) / median(t_fixed), median(ratio),
                *std::min_element(ratio.begin(), ratio.end()), *std::max_element(ratio.begin(), ratio.end()));
  }
  return 0;
}
