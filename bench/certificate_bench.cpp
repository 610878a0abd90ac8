// The price of the proof: certified `auto` against `certify: false` on the same points, per point,
// interleaved point by point (each point is answered both ways, in alternating order, so that the
// machine's noise falls on both alike). Single thread, the thread's CPU time per call.
// Surfaces: S1, S2, S3 (bench/occt/surfaces.json), [GSA] Example 1 over [-25,25]^2 (A1), torus,
// sphere (bench/surface_points.hpp); parametric curves: a helix and a trefoil. Point sets as
// bench/surface_bench.cpp makes them: box points uniform in twice the surface's bounding box, near points
// within 1 % of its diagonal. Each set is answered twice in full: the first pass is what a new batch of
// distinct points costs (the refinement keeps sub-boxes the certificates bisect, for later points), the
// second the same points again. Printed per set and pass: the certified share, the mean certificate boxes
// (run-time sub-boxes bounded), mean, median and p99 per point of both, and the ratio of the means.
//
// With --classes, a line per surface set says where the boxes go, by the kind of foot point the
// answer is: on the domain's edge; where the parametrisation is nearly singular (the smaller
// singular value of J = [s_u s_v] below 0.1 of the larger); near the focal distance (the least
// eigenvalue of <s_ij, s - p> in the metric's orthonormal frame below -0.5: the distance's
// Hessian there is less than half the metric's); the rest.
//
// Usage: certificate_bench [points per set, default 1000] [--near | --box] [--classes] [names ...]
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "compiled/parametric_curve_geometry.hpp"
#include "compiled_surface.hpp"
#include "cpu_time.hpp"
#include "surface_points.hpp"

using namespace footpoint;

namespace {

double mean(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x;
  return v.empty() ? 0.0 : s / static_cast<double>(v.size());
}

bool g_classes = false;

// The kind of foot point at (u, v) for p (see above): 0 edge, 1 nearly singular J, 2 near the
// focal distance, 3 the rest.
int foot_class(const ParametricSurface& s, const Vec3& p, double u, double v) {
  const ParamBox& b = s.domain();
  if (u <= b.umin || u >= b.umax || v <= b.vmin || v >= b.vmax) return 0;
  const SurfaceJet j = s.formulas().jet(u, v);
  const double E = dot(j.su, j.su), F = dot(j.su, j.sv), G = dot(j.sv, j.sv);
  const double tr = E + G, root = std::sqrt(std::max(0.0, (E - G) * (E - G) + 4.0 * F * F));
  if (std::sqrt(std::max(0.0, 0.5 * (tr - root)) / (0.5 * (tr + root))) < 0.1) return 1;
  // <s_ij, s - p> in the frame w = Lᵀ h (G = L Lᵀ), its least eigenvalue
  const Vec3 r = j.s - p;
  const double l00 = std::sqrt(E), l10 = F / l00, l11 = std::sqrt(G - l10 * l10);
  const double c00 = 1.0 / l00, c01 = -l10 / (l00 * l11), c11 = 1.0 / l11;
  const double a = dot(r, j.suu), bb = dot(r, j.suv), c = dot(r, j.svv);
  const double n00 = c00 * c00 * a, n01 = c00 * c01 * a + c00 * c11 * bb,
               n11 = c01 * c01 * a + 2.0 * c01 * c11 * bb + c11 * c11 * c;
  const double lambda = 0.5 * (n00 + n11) - std::sqrt(0.25 * (n00 - n11) * (n00 - n11) + n01 * n01);
  return lambda < -0.5 ? 2 : 3;
}

void run_set(const CompiledGeometry& g, const char* surface, const char* set, const std::vector<Vec3>& points,
             double overhead) {
  const GeometryMethod m = g.method("auto").value();
  Options certified, plain;
  plain.certify = false;
  for (int pass = 1; pass <= 2; ++pass) {
    std::vector<double> tc, tp;
    double boxes = 0.0;
    int share = 0;
    std::array<double, 4> class_points{}, class_boxes{};
    const auto* parametric = dynamic_cast<const ParametricSurface*>(&g);
    for (std::size_t i = 0; i < points.size(); ++i) {
      const double p[3] = {points[i].x, points[i].y, points[i].z};
      double c = 0.0, u = 0.0;
      ProjectionResult r;
      for (int order = 0; order < 2; ++order) {
        const bool cert_now = ((i + static_cast<std::size_t>(order)) % 2) == 0;
        const double t0 = bench::thread_cpu_ns();
        ProjectionResult q = m.project(p, cert_now ? certified : plain);
        const double t1 = std::max(0.0, bench::thread_cpu_ns() - t0 - overhead);
        if (cert_now) {
          c = t1;
          r = std::move(q);
        } else {
          u = t1;
        }
      }
      tc.push_back(c);
      tp.push_back(u);
      boxes += r.summary.certificate.boxes;
      if (g_classes && parametric && std::isfinite(r.distance)) {
        const int k = foot_class(*parametric, points[i], r.params[0], r.params[1]);
        class_points[static_cast<std::size_t>(k)] += 1.0;
        class_boxes[static_cast<std::size_t>(k)] += r.summary.certificate.boxes;
      }
      share += r.summary.certificate.certified ? 1 : 0;
    }
    const double mc = mean(tc), mp = mean(tp);
    std::printf(
        "%-7s %-5s pass %d  certified %5.1f %%  boxes %6.1f  certified mean %7.2f p50 %7.2f p99 %8.2f µs"
        "  | certify:false mean %6.2f p99 %7.2f µs  | ratio %5.2f\n",
        surface, set, pass, 100.0 * share / static_cast<double>(points.size()),
        boxes / static_cast<double>(points.size()), mc / 1e3, bench::percentile(tc, 0.5) / 1e3,
        bench::percentile(tc, 0.99) / 1e3, mp / 1e3, bench::percentile(tp, 0.99) / 1e3, mc / mp);
    if (g_classes && parametric && pass == 2) {
      static const char* const names[] = {"edge", "singular J", "focal", "rest"};
      std::printf("%-7s %-5s classes:", surface, set);
      for (std::size_t k = 0; k < 4; ++k)
        std::printf("  %s %.1f %% of points, %.1f %% of boxes", names[k],
                    100.0 * class_points[k] / static_cast<double>(points.size()),
                    boxes > 0.0 ? 100.0 * class_boxes[k] / boxes : 0.0);
      std::printf("\n");
    }
    std::fflush(stdout);
  }
}

struct CurveSpec {
  const char *name, *x, *y, *z;
  double t1;
};

// Parametric curves on [0, t1]: box points uniform in [-4, 4]^3, near points within 1 % of the
// box's diagonal of a point at a uniformly random parameter (as the surfaces' near points).
const CurveSpec kCurves[] = {
    {"helix", "cos(t)", "sin(t)", "0.2*t", 4.0 * 3.141592653589793},
    {"trefoil", "sin(t)+2*sin(2*t)", "cos(t)-2*cos(2*t)", "-sin(3*t)", 2.0 * 3.141592653589793},
};

void run_curve(const CurveSpec& c, int n, double overhead) {
  GeometryDefinition def;
  def.type = GeometryType::parametric_curve;
  def.formulas = {{"x", c.x}, {"y", c.y}, {"z", c.z}};
  def.domain = {{"t", {0.0, c.t1}}};
  const auto g = compile_parametric_curve(def, {});
  const auto& curve = dynamic_cast<const ParametricCurve&>(*g);
  std::mt19937_64 rng(12345);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  std::normal_distribution<double> N(0.0, 1.0);
  std::vector<Vec3> box, near;
  for (int i = 0; i < n; ++i) box.push_back({8.0 * U(rng) - 4.0, 8.0 * U(rng) - 4.0, 8.0 * U(rng) - 4.0});
  const double size = std::sqrt(3.0) * 8.0;
  for (int i = 0; i < n; ++i) {
    const Vec3 s = curve.formulas().point(c.t1 * U(rng));
    const Vec3 d{N(rng), N(rng), N(rng)};
    near.push_back(s + d * (0.01 * size * U(rng) / norm(d)));
  }
  run_set(*g, c.name, "near", near, overhead);
  run_set(*g, c.name, "box", box, overhead);
}

}  // namespace

int main(int argc, char** argv) {
  int n = 1000;
  bool near = true, box = true;
  std::vector<std::string> names;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--help") || !std::strcmp(argv[i], "-h")) {
      std::printf(
          "usage: certificate_bench [points per set, default 1000] [--near | --box] [--classes] [geometry "
          "...]\n"
          "geometries: S1 S2 S3 A1 torus sphere helix trefoil (default: all)\n");
      return 0;
    }
    if (!std::strcmp(argv[i], "--near"))
      box = false;
    else if (!std::strcmp(argv[i], "--box"))
      near = false;
    else if (!std::strcmp(argv[i], "--classes"))
      g_classes = true;
    else if (argv[i][0] >= '0' && argv[i][0] <= '9')
      n = std::atoi(argv[i]);
    else
      names.emplace_back(argv[i]);
  }
  const double overhead = bench::timer_overhead_ns();
  for (const bench::SurfaceSpec& s : bench::kSurfaces) {
    if (!names.empty() && std::find(names.begin(), names.end(), s.name) == names.end()) continue;
    const auto g = bench::compile_surface(s.x, s.y, s.z, s.u, s.v);
    const bench::SurfacePoints ps = bench::make_surface_points(*g, n, n, 12345);
    if (near) run_set(*g, s.name.c_str(), "near", ps.near, overhead);
    if (box) run_set(*g, s.name.c_str(), "box", ps.box, overhead);
  }
  for (const CurveSpec& c : kCurves)
    if (names.empty() || std::find(names.begin(), names.end(), c.name) != names.end())
      run_curve(c, n, overhead);
  return 0;
}
