// Surface projection timings, single thread unless stated. Per point: the thread's CPU time
// (the machine is shared: wall time would include descheduling), less the timer's own overhead,
// median over the runs; over points: median, mean, 90th and 99th percentile of those; and the
// batch mean: one timer around all the points, the mean per point (median over the runs).
//  1. `auto` on S1, S2, S3 (bench/occt/surfaces.json) and on the [GSA] Example 1 surface
//     over [-25,25]^2 (8 periods each way: it covers itself ~16 times): box points uniform in the
//     box centred on the surface's bounding box with twice its extent, and points within 1% of it;
//     the slowest 5% of the points, described (local solves, distance, where the answer lies);
//  2. `newton` and `gsa` per point from a given start (the auto answer's parameters moved by 1% of
//     the domain) on the near points;
//  3. the methods of [GSA] and [Hybrid] and `auto` side by side from the papers' starting values;
//  4. project_batch over the thread pool, 100,000 points, 2 threads against 1 (wall time);
//  5. `auto` on A1 and S1 with bench/http_bench.sh's point distribution (uniform in
//     x in [-20,20], y in [-3,3], z in [-1.5,1.5]), with the local solves per point;
//  6. `auto` on a coherent sequence of points (a path sweeping across the surface at 0.2 of its
//     size off it, as an ICP loop sends them), cold and warm started (options.initial: the
//     previous point's answer), interleaved; the answers must agree.
// S1-S3 and A1 are the papers' and Open CASCADE's surfaces; torus and sphere close (seams, poles).
// The load average (/proc/loadavg) is printed with every section.
//
// Usage: surface_bench [points per set, default 2000] [runs, default 5] [--sections 123456]
//        surface_bench --peer [--peer-dir DIR] [--reps R] [NAME ...]
// --peer: `auto` on the point sets of the Open CASCADE comparison (bench/occt/data/NAME.json, all
// of bench/occt/surfaces.json by default; --peer-dir another copy of bench/occt), per point the
// median over R runs (default 5) of the thread CPU time, and the accuracy against the sets'
// 50-digit references. bench/occt/occt_compare prints the same beside Open CASCADE's.

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "batch/batch.hpp"
#include "batch/thread_pool.hpp"
#include "bench_args.hpp"
#include "compiled_surface.hpp"
#include "cpu_time.hpp"
#include "occt/point_sets.hpp"
#include "surface_points.hpp"

using namespace footpoint;
using Clock = std::chrono::steady_clock;

namespace {

using bench::kS3x;
using bench::kS3y;
using bench::kS3z;
using bench::kSurfaces;
using bench::SurfaceSpec;

std::shared_ptr<const ParametricSurface> compile(const SurfaceSpec& s) {
  return bench::compile_surface(s.x, s.y, s.z, s.u, s.v);
}

using bench::load_average;
using bench::percentile;
double cpu_ns() { return bench::thread_cpu_ns(); }
double timer_overhead() { return bench::timer_overhead_ns(); }
double median(std::vector<double> v) { return percentile(std::move(v), 0.5); }
double mean(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x;
  return v.empty() ? 0.0 : s / static_cast<double>(v.size());
}

struct Timed {
  std::vector<double> ns;                 // per point: median over runs of the CPU time
  std::vector<double> wall_ns;            // the same, wall time
  std::vector<ProjectionResult> results;  // of the last run
  double batch_ns = 0.0;                  // one timer around all points: mean per point, median over runs
};

Timed time_points(const ParametricSurface& g, const std::vector<Vec3>& points, const char* method,
                  const std::vector<Options>& options, int runs, double overhead) {
  const GeometryMethod m = g.method(method).value();
  std::vector<std::vector<double>> cpu(points.size()), wall(points.size());
  Timed t;
  t.results.resize(points.size());
  for (int r = 0; r < runs; ++r)
    for (std::size_t i = 0; i < points.size(); ++i) {
      const double p[3] = {points[i].x, points[i].y, points[i].z};
      const auto w0 = Clock::now();
      const double c0 = cpu_ns();
      t.results[i] = m.project(p, options.empty() ? Options{} : options[i]);
      const double c1 = cpu_ns();
      const auto w1 = Clock::now();
      cpu[i].push_back(std::max(0.0, c1 - c0 - overhead));
      wall[i].push_back(std::chrono::duration<double, std::nano>(w1 - w0).count());
    }
  for (std::size_t i = 0; i < points.size(); ++i) {
    t.ns.push_back(median(cpu[i]));
    t.wall_ns.push_back(median(wall[i]));
  }
  // the mean without the per-point timer's noise (a syscall of a few hundred ns here)
  std::vector<double> batch;
  for (int r = 0; r < runs; ++r) {
    double sink = 0.0;
    const double c0 = cpu_ns();
    for (std::size_t i = 0; i < points.size(); ++i) {
      const double p[3] = {points[i].x, points[i].y, points[i].z};
      sink += m.project(p, options.empty() ? Options{} : options[i]).distance;
    }
    batch.push_back((cpu_ns() - c0) / static_cast<double>(points.size()));
    if (sink == -1.0) std::printf(" ");
  }
  t.batch_ns = median(batch);
  return t;
}

using PointSets = bench::SurfacePoints;

PointSets make_points(const ParametricSurface& g, int n, unsigned seed) {
  return bench::make_surface_points(g, n, n / 2, seed);
}

void print_row(const char* label, const Timed& t) {
  std::printf("   %-28s %7.2f %7.2f %7.2f %7.2f %7.2f µs", label, median(t.ns) / 1e3, mean(t.ns) / 1e3,
              t.batch_ns / 1e3, percentile(t.ns, 0.9) / 1e3, percentile(t.ns, 0.99) / 1e3);
}

// The share of the answers whose certificate meets the gap (projection/certificate.hpp).
void print_certified(const Timed& t) {
  const auto certified = std::count_if(t.results.begin(), t.results.end(), [](const ProjectionResult& r) {
    return r.summary.certificate.certified;
  });
  std::printf(" %6.1f%%", 100.0 * static_cast<double>(certified) / static_cast<double>(t.results.size()));
}

// The slowest 5% of the points: how many local solves they started, how far they are (relative
// to the surface's size) and where their answers lie, against the other 95%.
void print_tail(const char* label, const Timed& t, double size) {
  const double cut = percentile(t.ns, 0.95);
  struct Acc {
    int n = 0;
    double starts = 0, dist = 0;
    int where[3] = {0, 0, 0};
  } slow, rest;
  for (std::size_t i = 0; i < t.ns.size(); ++i) {
    Acc& a = t.ns[i] >= cut ? slow : rest;
    const ProjectionResult& r = t.results[i];
    ++a.n;
    a.starts += r.summary.starts;
    a.dist += r.distance / size;
    a.where[r.summary.location == Location::corner ? 2 : (r.summary.location == Location::edge ? 1 : 0)]++;
  }
  auto show = [](const char* name, const Acc& a) {
    std::printf("%s %5.1f starts, d/size %.2f, interior/edge/corner %3.0f/%3.0f/%3.0f%%", name,
                a.starts / a.n, a.dist / a.n, 100.0 * a.where[0] / a.n, 100.0 * a.where[1] / a.n,
                100.0 * a.where[2] / a.n);
  };
  std::printf("     %-26s", label);
  show("slowest 5%:", slow);
  show(" | rest:", rest);
  std::printf("\n");
}

struct PaperCase {
  const char* name;
  const char *x, *y, *z;
  std::array<double, 2> u, v;
  std::array<double, 3> p;
  std::array<double, 2> start;
};

const PaperCase kPaperCases[] = {
    {"A ex1 (1,2)", "u+v", "sin(u)+2*cos(v)", "sin(u+v)", {-25, 25}, {-25, 25}, {1, 2, 2}, {1, 2}},
    {"A ex2 (2,-2)", "u^4*v^3+u*v+u", "u^3+v^3", "u+v", {-5, 5}, {-5, 5}, {3, 4, 5}, {2, -2}},
    {"B ex1 (1,-2)", "u+2*v", "cos(u+v)", "sin(u+v)", {-2, 2}, {-2, 2}, {0.3, 0.5, 1}, {1, -2}},
    {"B ex2 (1,1)", kS3x, kS3y, kS3z, {0, 2}, {0, 2}, {15, 20, 25}, {1, 1}},
    {"B C1 (1,1)", "u", "v", "1+u^2+v^2", {-2, 2}, {-2, 2}, {0, 0, 0}, {1, 1}},
    {"B C2 (1,1)", "u", "v", "sin(u+v)", {0, 2}, {0, 2}, {3, 4, 5}, {1, 1}},
    {"B C3 (1,1)", "u", "v", "cos(u+v)", {0, 2}, {0, 2}, {4, 5, 6}, {1, 1}},
    {"B C4 (1,1)", "u", "v", "sin(u^2+v^2)", {0, 2}, {0, 2}, {4, 5, 6}, {1, 1}},
    {"B C5 (1,1)", "u", "v", "cos(u^2+v^2)", {0, 2}, {0, 2}, {4, 5, 6}, {1, 1}},
};

void section_auto(const std::vector<std::shared_ptr<const ParametricSurface>>& surfaces,
                  const std::vector<PointSets>& sets, const std::vector<double>& compile_ms, int runs,
                  double overhead) {
  std::printf(
      "1. auto (global), CPU time per point     median    mean   batch     p90     p99"
      "     certified    cells  memory  compile\n");
  std::vector<std::string> tails;
  for (std::size_t k = 0; k < surfaces.size(); ++k) {
    const ParametricSurface& g = *surfaces[k];
    const std::string name = kSurfaces[k].name;
    const Timed box = time_points(g, sets[k].box, "auto", {}, runs, overhead);
    const Timed near = time_points(g, sets[k].near, "auto", {}, runs, overhead);
    print_row((name + " box  (2x bounding box)").c_str(), box);
    print_certified(box);
    std::printf("  %6zu %5zu KB %5.1f ms\n", g.cells().cells().size(), g.memory_bytes() / 1024,
                compile_ms[k]);
    print_row((name + " near (within 1%)").c_str(), near);
    print_certified(near);
    std::printf("\n");
    print_tail((name + " box").c_str(), box, sets[k].size);
    print_tail((name + " near").c_str(), near, sets[k].size);
  }
}

void section_from_start(const std::vector<std::shared_ptr<const ParametricSurface>>& surfaces,
                        const std::vector<PointSets>& sets, int runs, double overhead) {
  std::printf("2. from a given start (auto's answer + 1%% of the domain), near points, CPU time\n");
  for (std::size_t k = 0; k < 3; ++k) {  // S1, S2, S3
    const ParametricSurface& g = *surfaces[k];
    const ParamBox& b = g.domain();
    std::vector<Options> starts;
    for (const Vec3& p : sets[k].near) {
      const double q[3] = {p.x, p.y, p.z};
      const ProjectionResult r = g.project(q, "auto", Options{}).value();
      Options o;
      o.initial = std::array<double, 3>{r.params[0] + 0.01 * (b.umax - b.umin),
                                        r.params[1] - 0.01 * (b.vmax - b.vmin), 0};
      starts.push_back(o);
    }
    for (const char* m : {"newton", "gsa"}) {
      const Timed t = time_points(g, sets[k].near, m, starts, runs, overhead);
      std::vector<double> its;
      for (const ProjectionResult& r : t.results) its.push_back(r.summary.iterations);
      std::printf(
          "   %s %-7s median %6.2f µs  mean %6.2f µs  batch mean %6.2f µs  iterations median %2.0f mean "
          "%5.1f\n",
          kSurfaces[k].name.c_str(), m, median(t.ns) / 1e3, mean(t.ns) / 1e3, t.batch_ns / 1e3, median(its),
          mean(its));
    }
  }
}

void section_papers(int runs, double overhead) {
  std::printf("3. the papers' cases from their starting values: iterations / status / median CPU µs\n");
  std::printf("   %-14s", "case");
  const char* methods[] = {"gsa", "first_order", "hybrid", "newton", "auto"};
  for (const char* m : methods) std::printf(" | %-26s", m);
  std::printf("\n");
  for (const PaperCase& c : kPaperCases) {
    const auto g = compile({c.name, c.x, c.y, c.z, c.u, c.v});
    std::printf("   %-14s", c.name);
    for (const char* m : methods) {
      Options o;
      o.initial = std::array<double, 3>{c.start[0], c.start[1], 0};
      const Timed t = time_points(*g, {Vec3{c.p[0], c.p[1], c.p[2]}}, m, {o}, std::max(runs, 5), overhead);
      const ProjectionResult& r = t.results[0];
      char cell[64];
      std::snprintf(cell, sizeof cell, "%4d %-14s %6.2f",
                    std::string(m) == "auto" ? r.summary.starts : r.summary.iterations,
                    to_string(r.summary.status), t.ns[0] / 1e3);
      std::printf(" | %-26s", cell);
    }
    std::printf("\n");
  }
  std::printf("   (auto: local solves started instead of iterations)\n");
}

void section_batch(const ParametricSurface& g) {
  std::printf("4. project_batch, auto, 100,000 points of S3 (box and near mixed), wall time\n");
  PointSets ps = make_points(g, 66667, 777);
  std::vector<double> coords;
  for (const auto* set : {&ps.box, &ps.near})
    for (const Vec3& p : *set) coords.insert(coords.end(), {p.x, p.y, p.z});
  const std::size_t count = coords.size() / 3;
  double rate[3] = {0, 0, 0};
  for (unsigned threads : {1u, 2u}) {
    ThreadPool pool(threads);
    BatchRequest req{g.method("auto").value()};
    req.points = coords.data();
    req.count = count;
    std::vector<double> walls;
    for (int r = 0; r < 3; ++r) {
      const auto t0 = Clock::now();
      const auto results = project_batch(pool, req);
      walls.push_back(std::chrono::duration<double>(Clock::now() - t0).count());
      if (results.size() != count) std::abort();
    }
    rate[threads] = static_cast<double>(count) / median(walls);
    std::printf("   %u thread%s: %8.0f points/s (%.2f µs/point)\n", threads, threads > 1 ? "s" : " ",
                rate[threads], 1e6 / rate[threads]);
  }
  std::printf("   speed-up 2 threads / 1 thread: %.2fx\n", rate[2] / rate[1]);
}

// Points as bench/http_bench.sh draws them around the [GSA] Example 1 surface.
std::vector<Vec3> http_points(int n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  std::vector<Vec3> points;
  points.reserve(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) points.push_back({U(rng) * 40 - 20, U(rng) * 6 - 3, U(rng) * 3 - 1.5});
  return points;
}

void section_http(const std::vector<std::shared_ptr<const ParametricSurface>>& surfaces, int n, int runs,
                  double overhead) {
  std::printf(
      "5. auto, http_bench's points (x in [-20,20], y in [-3,3], z in [-1.5,1.5]), CPU time per point\n"
      "                                     median    mean   batch     p90     p99  solves mean median "
      "max  certified\n");
  const std::vector<Vec3> points = http_points(n, 4242);
  for (std::size_t k : {std::size_t{3}, std::size_t{0}}) {  // A1, S1
    const Timed t = time_points(*surfaces[k], points, "auto", {}, runs, overhead);
    std::vector<double> starts;
    for (const ProjectionResult& r : t.results) starts.push_back(r.summary.starts);
    print_row((kSurfaces[k].name + " http points").c_str(), t);
    std::printf("  %5.2f %6.0f %4.0f", mean(starts), median(starts), percentile(starts, 1.0));
    print_certified(t);
    std::printf("\n");
  }
}

void section_warm_start(const std::vector<std::shared_ptr<const ParametricSurface>>& surfaces,
                        const std::vector<PointSets>& sets, int n, int runs, double overhead) {
  std::printf(
      "6. auto on a coherent sequence, cold vs warm (options.initial = the previous answer), batch mean\n"
      "   per point, medians of %d interleaved pairs        cold µs   warm µs  warm/cold  solves cold/warm\n",
      runs);
  for (std::size_t k = 0; k < surfaces.size(); ++k) {
    const ParametricSurface& g = *surfaces[k];
    const ParamBox& b = g.domain();
    // the path: s(u(τ), v(τ)) + 0.2 size (1, 1, 1)/√3, τ over the domain's diagonal band
    std::vector<Vec3> points;
    const double off = 0.2 * sets[k].size / std::sqrt(3.0);
    for (int i = 0; i < n; ++i) {
      const double tau = static_cast<double>(i) / n;
      const double u = b.umin + (b.umax - b.umin) * (0.1 + 0.8 * tau);
      const double v = b.vmin + (b.vmax - b.vmin) * (0.5 + 0.3 * std::sin(6.283185307179586 * tau));
      points.push_back(g.formulas().point(u, v) + Vec3{off, off, off});
    }
    const Timed reference = time_points(g, points, "auto", {}, 1, overhead);
    std::vector<Options> warm(points.size());
    for (std::size_t i = 1; i < points.size(); ++i) {
      const auto& q = reference.results[i - 1].params;
      warm[i].initial = std::array<double, 3>{q[0], q[1], 0.0};
    }
    std::vector<double> cold_ns, warm_ns;
    Timed c, w;
    for (int r = 0; r < runs; ++r) {
      c = time_points(g, points, "auto", {}, 1, overhead);
      w = time_points(g, points, "auto", warm, 1, overhead);
      cold_ns.push_back(c.batch_ns);
      warm_ns.push_back(w.batch_ns);
    }
    std::size_t differ = 0;
    double solves_cold = 0.0, solves_warm = 0.0;
    for (std::size_t i = 0; i < points.size(); ++i) {
      differ +=
          std::abs(c.results[i].distance - w.results[i].distance) > 1e-12 * (1.0 + c.results[i].distance);
      solves_cold += c.results[i].summary.starts;
      solves_warm += w.results[i].summary.starts;
    }
    std::printf("   %-44s %8.2f  %8.2f  %9.3f  %6.2f / %4.2f%s\n", kSurfaces[k].name.c_str(),
                median(cold_ns) / 1e3, median(warm_ns) / 1e3, median(warm_ns) / median(cold_ns),
                solves_cold / n, solves_warm / n, differ ? "  ANSWERS DIFFER" : "");
  }
}

// ---- the point sets of the Open CASCADE comparison (bench/occt/) ----

int comparison_mode(const std::string& dir, int reps, std::vector<std::string> names) {
  if (names.empty()) names = bench::comparison_surface_names(dir);
  const double overhead = timer_overhead();
  std::printf(
      "footpoint auto on the Open CASCADE comparison's point sets (%s/data), %d runs; CPU-timer overhead "
      "%.0f ns (subtracted); %s\n",
      dir.c_str(), reps, overhead, load_average().c_str());
  for (const std::string& name : names) {
    const bench::ComparisonSurface s = bench::read_comparison_surface(dir, name);
    if (!s.footpoint) {
      std::printf("   %-3s footpoint: type not yet measured (%s)\n", s.name.c_str(),
                  s.bspline ? "bspline_surface" : "surfaces.json: \"footpoint\": false");
      continue;
    }
    const auto t0 = Clock::now();
    const auto g = compile({s.name, s.x, s.y, s.z, s.u, s.v});
    const double compile_ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
    for (const bench::PointSet& set : s.sets) {
      std::vector<Vec3> points;
      for (const auto& p : set.points) points.push_back({p[0], p[1], p[2]});
      const Timed t = time_points(*g, points, "auto", {}, reps, overhead);
      std::vector<bench::Answer> answers;
      for (const ProjectionResult& r : t.results)
        answers.push_back({r.summary.status == Status::converged, r.distance});
      const bench::Accuracy a = bench::accuracy(answers, set.references);
      std::printf(
          "   %-3s %-4s %4zu points: median %6.2f µs, mean %6.2f µs, batch mean %6.2f µs; not global %d, "
          "not converged %d, max rel err %.1e (%zu cells, compiled in %.1f ms)\n",
          s.name.c_str(), set.name.c_str(), points.size(), median(t.ns) / 1e3, mean(t.ns) / 1e3,
          t.batch_ns / 1e3, a.not_global, a.no_answer, a.max_relative_error, g->cells().cells().size(),
          compile_ms);
    }
  }
  std::printf("   %s\n", load_average().c_str());
  return 0;
}

constexpr const char* kUsage =
    "usage: surface_bench [points per set, default 2000] [runs, default 5] [--sections 123456]\n"
    "       surface_bench --peer [--peer-dir DIR] [--reps R] [NAME ...]\n"
    "(the sections and the --peer comparison: the comment at the top of bench/surface_bench.cpp)\n";

int run(int argc, char** argv) {
  bench::exit_on_help(argc, argv, kUsage);
  std::vector<std::string> positional;
  std::string comparison, sections = "123456";
  int reps = 5;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--peer")) {
      comparison = FOOTPOINT_OCCT_DIR;
    } else if (!std::strcmp(argv[i], "--peer-dir") && i + 1 < argc) {
      comparison = argv[++i];
    } else if (!std::strcmp(argv[i], "--reps") && i + 1 < argc) {
      reps = static_cast<int>(bench::count_argument(argv[0], argv[++i], kUsage));
    } else if (!std::strcmp(argv[i], "--sections") && i + 1 < argc) {
      sections = argv[++i];
      if (sections.empty() || sections.find_first_not_of("123456") != std::string::npos)
        bench::refuse_argument(argv[0], "sections are digits 1-6, not", argv[i], kUsage);
    } else if (argv[i][0] == '-') {
      bench::refuse_argument(argv[0], "unknown option", argv[i], kUsage);
    } else {
      positional.emplace_back(argv[i]);
    }
  }
  if (!comparison.empty()) return comparison_mode(comparison, reps, positional);
  if (positional.size() > 2)
    bench::refuse_argument(argv[0], "unexpected argument", positional[2].c_str(), kUsage);

  const int n = !positional.empty()
                    ? static_cast<int>(bench::count_argument(argv[0], positional[0].c_str(), kUsage))
                    : 2000;
  const int runs = positional.size() > 1
                       ? static_cast<int>(bench::count_argument(argv[0], positional[1].c_str(), kUsage))
                       : 5;
  const double overhead = timer_overhead();
  std::printf(
      "surface_bench: %d box points + %d near points per surface, %d runs, single thread; "
      "CPU-timer overhead %.0f ns (subtracted)\n",
      n, n / 2, runs, overhead);

  std::vector<std::shared_ptr<const ParametricSurface>> surfaces;
  std::vector<PointSets> sets;
  std::vector<double> compile_ms;
  for (const SurfaceSpec& s : kSurfaces) {
    const auto t0 = Clock::now();
    surfaces.push_back(compile(s));
    compile_ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
    sets.push_back(make_points(*surfaces.back(), n, 12345));
  }
  const auto has = [&](char c) { return sections.find(c) != std::string::npos; };
  if (has('1')) {
    std::printf("\n[%s]\n", load_average().c_str());
    section_auto(surfaces, sets, compile_ms, runs, overhead);
  }
  if (has('2')) {
    std::printf("\n[%s]\n", load_average().c_str());
    section_from_start(surfaces, sets, runs, overhead);
  }
  if (has('3')) {
    std::printf("\n[%s]\n", load_average().c_str());
    section_papers(runs, overhead);
  }
  if (has('4')) {
    std::printf("\n[%s]\n", load_average().c_str());
    section_batch(*surfaces[2]);
  }
  if (has('5')) {
    std::printf("\n[%s]\n", load_average().c_str());
    section_http(surfaces, n, runs, overhead);
  }
  if (has('6')) {
    std::printf("\n[%s]\n", load_average().c_str());
    section_warm_start(surfaces, sets, n, runs, overhead);
  }
  std::printf("\n[%s]\n", load_average().c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "surface_bench: %s\n", e.what());
    return 1;
  }
}
