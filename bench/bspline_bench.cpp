// B-spline and NURBS surfaces projected with `auto` (compiled/bspline_geometry.hpp): the compile
// time, and per point the CPU time (median, 90th percentile, mean), the certified share, the
// boxes the certificates bisected and the local searches started (summary.starts: the pieces'
// Newton starts and restarts, the tail's measure), on two surfaces built here with a fixed seed:
//   B8  a bicubic B-spline of 8 x 8 pieces (11 x 11 control points on [0,4]^2, clamped uniform
//       knots, heights 0.3 sin(x) cos(y) plus noise of 0.05);
//   RS  the rational sphere of radius 1 (degree 2 x 2, the 9 x 5 net, 8 pieces);
// and two point sets each: `box`, uniform in the box of twice the surface's extent, and `near`,
// points of the surface moved along the normal by up to 1 % of its size.
//
//   build/bench/bspline_bench [points per set, default 300] [surface: B8 or RS, default both]
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "compiled/bspline_geometry.hpp"
#include "compiled/compiled_geometry.hpp"
#include "cpu_time.hpp"
#include "parametric/geometry/nurbs_patches.hpp"
#include "parametric/solvers/bezier_patch_nearest.hpp"
#include "solvers/piecewise_nearest.hpp"

using namespace footpoint;

namespace {

std::vector<double> clamped(int n, int p, double length) {
  std::vector<double> U(static_cast<std::size_t>(p + 1), 0.0);
  for (int i = 1; i < n - p; ++i) U.push_back(length * i / (n - p));
  U.insert(U.end(), static_cast<std::size_t>(p + 1), length);
  return U;
}

GeometryDefinition bicubic(std::mt19937& rng) {
  std::uniform_real_distribution<double> noise(-0.05, 0.05);
  GeometryDefinition def;
  def.type = GeometryType::bspline_surface;
  def.bspline.degree = {3, 3};
  def.bspline.knots = {clamped(11, 3, 4.0), clamped(11, 3, 4.0)};
  for (int i = 0; i < 11; ++i) {
    std::vector<std::vector<double>> row;
    for (int j = 0; j < 11; ++j) {
      const double x = 0.4 * i, y = 0.4 * j;
      row.push_back({x, y, 0.3 * std::sin(x) * std::cos(y) + noise(rng)});
    }
    def.bspline.control_points.push_back(row);
  }
  return def;
}

GeometryDefinition sphere() {
  const double h = std::sqrt(0.5);
  const double c[9][2] = {{1, 0}, {1, 1}, {0, 1}, {-1, 1}, {-1, 0}, {-1, -1}, {0, -1}, {1, -1}, {1, 0}};
  const double half[5][2] = {{0, -1}, {1, -1}, {1, 0}, {1, 1}, {0, 1}};
  GeometryDefinition def;
  def.type = GeometryType::bspline_surface;
  def.bspline.degree = {2, 2};
  def.bspline.knots = {{0, 0, 0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1, 1, 1}, {0, 0, 0, 0.5, 0.5, 1, 1, 1}};
  for (int i = 0; i < 9; ++i) {
    std::vector<std::vector<double>> row;
    std::vector<double> w;
    for (int j = 0; j < 5; ++j) {
      row.push_back({c[i][0] * half[j][0], c[i][1] * half[j][0], half[j][1]});
      w.push_back((i % 2 ? h : 1.0) * (j % 2 ? h : 1.0));
    }
    def.bspline.control_points.push_back(row);
    def.bspline.weights.push_back(w);
  }
  return def;
}

struct Set {
  std::string name;
  std::vector<Vec3> points;
};

std::vector<Set> point_sets(const CompiledGeometry& g, int count, std::mt19937& rng) {
  // The surface's box from a grid of evaluations.
  const auto& s = dynamic_cast<const BSplineSurface&>(g).surface();
  Vec3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  for (int i = 0; i <= 40; ++i)
    for (int j = 0; j <= 40; ++j) {
      const double t[2] = {s.umin() + (s.umax() - s.umin()) * i / 40,
                           s.vmin() + (s.vmax() - s.vmin()) * j / 40};
      Evaluation e;
      g.evaluate(t, e);
      lo = min(lo, e.point);
      hi = max(hi, e.point);
    }
  const Vec3 centre = 0.5 * (lo + hi), extent = hi - lo;
  const double size = norm(extent);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), param(0.0, 1.0);
  Set box{"box", {}}, near{"near", {}};
  while (static_cast<int>(box.points.size()) < count)
    box.points.push_back(centre + Vec3{extent.x * unit(rng), extent.y * unit(rng), extent.z * unit(rng)});
  while (static_cast<int>(near.points.size()) < count) {
    const double t[2] = {s.umin() + (s.umax() - s.umin()) * param(rng),
                         s.vmin() + (s.vmax() - s.vmin()) * param(rng)};
    Evaluation e;
    g.evaluate(t, e);
    if (!e.normal_defined) continue;
    near.points.push_back(e.point + e.normal * (0.01 * size * unit(rng)));
  }
  return {box, near};
}

}  // namespace

int main(int argc, char** argv) {
  const int count = argc > 1 ? std::atoi(argv[1]) : 300;
  const std::string only = argc > 2 ? argv[2] : "";
  std::mt19937 rng(2026);
  const double overhead = bench::timer_overhead_ns();
  std::printf("%s\n", bench::load_average().c_str());
  std::printf("%-4s %-5s %8s %8s %8s %8s %9s %7s %7s %9s\n", "surf", "set", "compile", "p50 us", "p90 us",
              "mean us", "certified", "boxes", "starts", "pieces");
  struct Named {
    const char* name;
    GeometryDefinition def;
  };
  for (const Named& n : {Named{"B8", bicubic(rng)}, Named{"RS", sphere()}}) {
    const auto start = std::chrono::steady_clock::now();
    const auto g = compile_geometry(n.def);
    const double compile_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    // A surface left out still draws its points, so that the others' sets are the full run's.
    const std::vector<Set> sets = point_sets(*g, count, rng);
    if (!only.empty() && only != n.name) continue;
    for (const Set& set : sets) {
      std::vector<double> us, distances;
      int certified = 0;
      double boxes = 0.0, solved = 0.0, starts = 0.0;
      const double batch_start = bench::thread_cpu_ns();
      for (const Vec3& p : set.points) {
        const double x[3] = {p.x, p.y, p.z};
        const double t0 = bench::thread_cpu_ns();
        const ProjectionResult r = g->project(x, "auto", {}).value();
        us.push_back((bench::thread_cpu_ns() - t0 - overhead) / 1e3);
        certified += r.summary.certificate.certified;
        distances.push_back(r.distance);
        boxes += r.summary.certificate.boxes;
        starts += r.summary.starts;
      }
      const double mean =
          (bench::thread_cpu_ns() - batch_start) / 1e3 / static_cast<double>(set.points.size());
      // The pieces whose box is within the answer's distance (outside the timing).
      const auto& bspline = dynamic_cast<const BSplineSurface&>(*g);
      for (std::size_t i = 0; i < set.points.size(); ++i)
        for (std::size_t k = 0; k < bspline.pieces(); ++k)
          solved += distance_lower_bound(bspline.hull(k), set.points[i]) <= distances[i] * (1 + 1e-9);
      std::printf("%-4s %-5s %6.1fms %8.1f %8.1f %8.1f %8.1f%% %7.1f %7.2f %9zu\n", n.name, set.name.c_str(),
                  compile_ms, bench::percentile(us, 0.5), bench::percentile(us, 0.9), mean,
                  100.0 * certified / static_cast<double>(set.points.size()),
                  boxes / static_cast<double>(set.points.size()),
                  starts / static_cast<double>(set.points.size()),
                  dynamic_cast<const BSplineSurface&>(*g).pieces());
      std::printf("     pieces solved per point %.2f; compiled %.1f MB\n",
                  solved / static_cast<double>(set.points.size()),
                  static_cast<double>(g->memory_bytes()) / 1e6);
      {
        // The pieces' own branch and bound alone (nearest_on_patch), on the piece whose box is
        // nearest each point.
        const auto& surface = dynamic_cast<const BSplineSurface&>(*g);
        {
          std::vector<BezierPatch> patches;
          for (const nurbs::SurfacePiece& piece : nurbs::bezier_pieces(surface.surface(), 1 << 20)) {
            std::vector<Vec3> net;
            std::vector<double> weights;
            for (const auto& h : piece.bezier) {
              net.push_back({h[0], h[1], h[2]});
              if (surface.surface().rational) weights.push_back(h[3]);
            }
            patches.emplace_back(surface.surface().degree[0], surface.surface().degree[1], std::move(net),
                                 std::move(weights));
          }
          int proved = 0;
          double patch_boxes = 0.0;
          const double t0 = bench::thread_cpu_ns();
          for (const Vec3& p : set.points) {
            std::size_t nearest = 0;
            for (std::size_t k = 1; k < surface.pieces(); ++k)
              if (distance_lower_bound(surface.hull(k), p) < distance_lower_bound(surface.hull(nearest), p))
                nearest = k;
            const PatchNearest n = nearest_on_patch(patches[nearest], p);
            proved += n.proved;
            patch_boxes += n.boxes;
          }
          std::size_t patch_bytes = 0;
          for (const BezierPatch& patch : patches) patch_bytes += patch.memory_bytes();
          std::printf(
              "     nearest_on_patch (nearest box's piece; patches %.1f MB) mean %.2f us, proved %.1f%%, "
              "boxes %.1f\n",
              static_cast<double>(patch_bytes) / 1e6,
              (bench::thread_cpu_ns() - t0) / 1e3 / static_cast<double>(set.points.size()),
              100.0 * proved / static_cast<double>(set.points.size()),
              patch_boxes / static_cast<double>(set.points.size()));
        }
      }
      {
        Options o;
        o.certify = false;
        const double t0 = bench::thread_cpu_ns();
        for (const Vec3& p : set.points) {
          const double x[3] = {p.x, p.y, p.z};
          (void)g->project(x, "auto", o);
        }
        std::printf("     certify:false mean %.1f us\n",
                    (bench::thread_cpu_ns() - t0) / 1e3 / static_cast<double>(set.points.size()));
      }
    }
  }
  return 0;
}
