// Surface projection timings (single thread unless stated), medians over points and runs:
//  1. `auto` per point on S1, S2, S3 (shared/peers/surfaces.txt): box points uniform in the box
//     centred on the surface's bounding box with twice its extent, and points within 1% of it;
//  2. `newton` and `gsa` per point from a given start (the auto answer's parameters moved by 1% of
//     the domain) on the near points;
//  3. the papers' methods and `auto` side by side from the papers' starting values;
//  4. project_batch over the thread pool, 100,000 points, 2 threads against 1.
// Usage: surface_bench [points per set, default 2000] [runs, default 5]
#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "batch/batch.hpp"
#include "batch/thread_pool.hpp"
#include "geometry/geometry.hpp"
#include "geometry/parametric_surface_geometry.hpp"

using namespace footpoint;
using Clock = std::chrono::steady_clock;

namespace {

struct SurfaceSpec {
  const char* name;
  const char *x, *y, *z;
  std::array<double, 2> u, v;
};

const SurfaceSpec kSurfaces[] = {
    {"S1", "u+v", "sin(u)+2*cos(v)", "sin(u+v)", {-3, 3}, {-3, 3}},
    {"S2", "u^4*v^3+u*v+u", "u^3+v^3", "u+v", {-2, 2}, {-2, 2}},
    {"S3", "u^6+u^5*v+v^6-u^2*v^3+u*v^4-v^5+u^4+u^3*v+v^4+u^3-u*v^2+v^3+u*v+v^2+1",
     "u^6+2*u^4*v^2-v^6+u^5+u^2*v^3+v^5+u^4-u*v^3+u^3-2*u*v^2+v^3+4*u*v+2*v^2+2*u+2*v+1",
     "u^6+u*v^5+u^4*v+u^2*v^3+u^3*v+2*u^2*v^2+v^4+u^3+2*u*v+u", {0, 2}, {0, 2}},
};

std::shared_ptr<const ParametricSurface> compile(const char* x, const char* y, const char* z, std::array<double, 2> u,
                                                 std::array<double, 2> v) {
  GeometryDefinition def;
  def.type = GeometryType::parametric_surface;
  def.formulas = {{"x", x}, {"y", y}, {"z", z}};
  def.domain = {{"u", u}, {"v", v}};
  return std::dynamic_pointer_cast<const ParametricSurface>(compile_parametric_surface(def, {}));
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

// Per-point times (ns) of `method` over the points, `runs` times; returns the median per point
// (of each point's median over runs) and fills the mean.
double time_points(const ParametricSurface& g, const std::vector<Vec3>& points, const char* method,
                   const std::vector<Options>& options, int runs, double* mean_ns) {
  std::vector<std::vector<double>> per_point(points.size());
  double total = 0.0;
  for (int r = 0; r < runs; ++r) {
    for (std::size_t i = 0; i < points.size(); ++i) {
      const double p[3] = {points[i].x, points[i].y, points[i].z};
      const auto t0 = Clock::now();
      const ProjectionResult res = g.project(p, method, options.empty() ? Options{} : options[i]);
      const auto t1 = Clock::now();
      const double ns = std::chrono::duration<double, std::nano>(t1 - t0).count();
      per_point[i].push_back(ns);
      total += ns;
      if (res.distance < 0) std::abort();  // keeps the call
    }
  }
  std::vector<double> medians;
  for (auto& v : per_point) medians.push_back(median(v));
  *mean_ns = total / (static_cast<double>(runs) * static_cast<double>(points.size()));
  return median(medians);
}

struct PointSets {
  std::vector<Vec3> box, near;
};

PointSets make_points(const ParametricSurface& g, int n, unsigned seed) {
  const ParamBox& b = g.domain();
  Vec3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  for (int i = 0; i <= 200; ++i)
    for (int j = 0; j <= 200; ++j) {
      const Vec3 s = g.formulas().point(b.umin + (b.umax - b.umin) * i / 200.0, b.vmin + (b.vmax - b.vmin) * j / 200.0);
      for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], s[k]), hi[k] = std::max(hi[k], s[k]);
    }
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  PointSets ps;
  for (int i = 0; i < n; ++i) {
    Vec3 p;
    for (int k = 0; k < 3; ++k) p[k] = lo[k] + (hi[k] - lo[k]) * (2.0 * U(rng) - 0.5);
    ps.box.push_back(p);
  }
  const double size = norm(hi - lo);
  std::normal_distribution<double> N(0.0, 1.0);
  for (int i = 0; i < n / 2; ++i) {
    const Vec3 s = g.formulas().point(b.umin + (b.umax - b.umin) * U(rng), b.vmin + (b.vmax - b.vmin) * U(rng));
    Vec3 d{N(rng), N(rng), N(rng)};
    ps.near.push_back(s + d * (0.01 * size * U(rng) / norm(d)));
  }
  return ps;
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
    {"B ex2 (1,1)", kSurfaces[2].x, kSurfaces[2].y, kSurfaces[2].z, {0, 2}, {0, 2}, {15, 20, 25}, {1, 1}},
    {"B C1 (1,1)", "u", "v", "1+u^2+v^2", {-2, 2}, {-2, 2}, {0, 0, 0}, {1, 1}},
    {"B C2 (1,1)", "u", "v", "sin(u+v)", {0, 2}, {0, 2}, {3, 4, 5}, {1, 1}},
    {"B C3 (1,1)", "u", "v", "cos(u+v)", {0, 2}, {0, 2}, {4, 5, 6}, {1, 1}},
    {"B C4 (1,1)", "u", "v", "sin(u^2+v^2)", {0, 2}, {0, 2}, {4, 5, 6}, {1, 1}},
    {"B C5 (1,1)", "u", "v", "cos(u^2+v^2)", {0, 2}, {0, 2}, {4, 5, 6}, {1, 1}},
};

}  // namespace

int main(int argc, char** argv) {
  const int n = argc > 1 ? std::atoi(argv[1]) : 2000;
  const int runs = argc > 2 ? std::atoi(argv[2]) : 5;
  std::printf("surface_bench: %d box points + %d near points per surface, %d runs, single thread\n\n", n, n / 2, runs);

  std::printf("1. auto (global), per point        median    mean    cells  compile\n");
  std::vector<std::shared_ptr<const ParametricSurface>> surfaces;
  std::vector<PointSets> sets;
  for (const SurfaceSpec& s : kSurfaces) {
    const auto t0 = Clock::now();
    auto g = compile(s.x, s.y, s.z, s.u, s.v);
    const double compile_ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
    surfaces.push_back(g);
    sets.push_back(make_points(*g, n, 12345));
    double mean_box, mean_near;
    const double box = time_points(*g, sets.back().box, "auto", {}, runs, &mean_box);
    const double near = time_points(*g, sets.back().near, "auto", {}, runs, &mean_near);
    std::printf("   %s box  (2x bounding box)      %7.2f µs %6.2f µs  %5zu  %6.1f ms\n", s.name, box / 1e3,
                mean_box / 1e3, g->cells().cells().size(), compile_ms);
    std::printf("   %s near (within 1%%)            %7.2f µs %6.2f µs\n", s.name, near / 1e3, mean_near / 1e3);
  }

  std::printf("\n2. from a given start (auto's answer + 1%% of the domain), near points\n");
  for (std::size_t k = 0; k < surfaces.size(); ++k) {
    const ParametricSurface& g = *surfaces[k];
    const ParamBox& b = g.domain();
    std::vector<Options> starts;
    for (const Vec3& p : sets[k].near) {
      const double q[3] = {p.x, p.y, p.z};
      const ProjectionResult r = g.project(q, "auto", Options{});
      Options o;
      o.initial = std::array<double, 3>{r.params[0] + 0.01 * (b.umax - b.umin), r.params[1] - 0.01 * (b.vmax - b.vmin), 0};
      starts.push_back(o);
    }
    for (const char* m : {"newton", "gsa"}) {
      double mean;
      const double med = time_points(g, sets[k].near, m, starts, runs, &mean);
      std::printf("   %s %-7s median %6.2f µs  mean %6.2f µs\n", kSurfaces[k].name, m, med / 1e3, mean / 1e3);
    }
  }

  std::printf("\n3. the papers' cases from their starting values: iterations / status / median µs\n");
  std::printf("   %-14s", "case");
  const char* methods[] = {"gsa", "first_order", "hybrid", "newton", "auto"};
  for (const char* m : methods) std::printf(" | %-26s", m);
  std::printf("\n");
  for (const PaperCase& c : kPaperCases) {
    auto g = compile(c.x, c.y, c.z, c.u, c.v);
    std::printf("   %-14s", c.name);
    for (const char* m : methods) {
      Options o;
      o.initial = std::array<double, 3>{c.start[0], c.start[1], 0};
      std::vector<double> times;
      ProjectionResult r;
      for (int k = 0; k < std::max(runs, 5); ++k) {
        const auto t0 = Clock::now();
        r = g->project(c.p.data(), m, o);
        times.push_back(std::chrono::duration<double, std::micro>(Clock::now() - t0).count());
      }
      char cell[64];
      std::snprintf(cell, sizeof cell, "%4d %-14s %6.2f", std::string(m) == "auto" ? r.summary.starts : r.summary.iterations,
                    to_string(r.summary.status), median(times));
      std::printf(" | %-26s", cell);
    }
    std::printf("\n");
  }
  std::printf("   (auto: local solves started instead of iterations)\n");

  std::printf("\n4. project_batch, auto, 100,000 points of S3 (box and near mixed), wall time\n");
  {
    const ParametricSurface& g = *surfaces[2];
    PointSets ps = make_points(g, 66667, 777);
    std::vector<double> coords;
    for (const auto* set : {&ps.box, &ps.near})
      for (const Vec3& p : *set) coords.insert(coords.end(), {p.x, p.y, p.z});
    const std::size_t count = coords.size() / 3;
    double rate[3] = {0, 0, 0};
    for (unsigned threads : {1u, 2u}) {
      ThreadPool pool(threads);
      BatchRequest req;
      req.geometry = &g;
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
      std::printf("   %u thread%s: %8.0f points/s (%.2f µs/point)\n", threads, threads > 1 ? "s" : " ", rate[threads],
                  1e6 / rate[threads]);
    }
    std::printf("   speed-up 2 threads / 1 thread: %.2fx\n", rate[2] / rate[1]);
  }
  return 0;
}
