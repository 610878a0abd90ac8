// footpoint's `auto` and Open CASCADE 7.6 projecting the same points onto the same surfaces, side
// by side: per-point CPU time and accuracy against the 50-digit references (bench/occt/README.md).
//
// Open CASCADE gets each surface in its exact form: the polynomial surfaces S2 and S3 as Bezier
// patches (bench/occt/make_data.py converts them exactly), the torus T as its Geom_ToroidalSurface.
// Its two ways of answering:
//  - GeomAPI_ProjectPointOnSurf, initialised once per surface (its sampling grid reused), which
//    returns the nearest of the interior extrema it finds;
//  - Extrema_ExtPS (minima only) with the four boundary curves (GeomAPI_ProjectPointOnCurve on
//    the iso-curves of the domain's edges) and the four corners: the nearest of all of them, the
//    global answer over the closed domain when each part finds its own.
// S1 (trigonometric) has no exact Open CASCADE form: footpoint only. The B-spline surfaces (B8, RS:
// bspline_surface definitions) are Open CASCADE's Geom_BSplineSurface from the same control net,
// weights and knots (the full knot vector as distinct knots and multiplicities); footpoint's side
// of a surface is measured where surfaces.json does not say "footpoint": false.
//
// Usage: occt_compare [--reps R] [--data DIR] [NAME ...]
//   R repetitions of every point (default 5; the time of a point is the median), DIR the folder
//   with surfaces.json and data/ (default: this folder in the source tree), NAMEs of
//   surfaces.json (default all).
#include <Geom_BezierSurface.hxx>
#include <Geom_ToroidalSurface.hxx>
#include <Standard_Failure.hxx>
#include <Standard_Version.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <gp_Ax3.hxx>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "compiled_surface.hpp"
#include "cpu_time.hpp"
#include "geometry_json.hpp"
#include "json_reader.hpp"
#include "occt_geometry.hpp"
#include "point_sets.hpp"

using namespace footpoint;
using namespace footpoint::bench;

namespace {

bool make_occt(const ComparisonSurface& s, OcctSurface& out) {
  if (s.bspline) {
    out = {occt_bspline(*s.bspline), s.u[0], s.u[1], s.v[0], s.v[1]};
    return true;
  }
  if (!s.bezier_poles.empty()) {
    const int n = static_cast<int>(s.bezier_poles.size()), m = static_cast<int>(s.bezier_poles[0].size());
    TColgp_Array2OfPnt poles(1, n, 1, m);
    for (int k = 0; k < n; ++k)
      for (int l = 0; l < m; ++l) {
        const auto& q = s.bezier_poles[static_cast<std::size_t>(k)][static_cast<std::size_t>(l)];
        poles.SetValue(k + 1, l + 1, gp_Pnt(q[0], q[1], q[2]));
      }
    out = {new Geom_BezierSurface(poles), 0.0, 1.0, 0.0, 1.0};
    return true;
  }
  if (s.torus_major > 0) {
    // (R + r cos v)(cos u, sin u, 0) + r sin v (0, 0, 1): the formulas' parameters
    out = {new Geom_ToroidalSurface(gp_Ax3(gp::Origin(), gp::DZ(), gp::DX()), s.torus_major, s.torus_minor),
           s.u[0], s.u[1], s.v[0], s.v[1]};
    return true;
  }
  return false;
}

struct Timing {
  std::vector<double> ns;  // per point: median over the repetitions
  double batch_ns = 0.0;   // one timer around all points: the mean per point, median over repetitions
  std::vector<Answer> answers;
};

// Every repetition runs each method over all points, the methods in turn, so that a change of the
// machine's load falls on all of them alike.
std::vector<Timing> time_methods(const std::vector<PeerMethod>& methods, const PointSet& set, int reps,
                                 double overhead) {
  const std::size_t n = set.points.size();
  std::vector<std::vector<std::vector<double>>> cpu(methods.size(), std::vector<std::vector<double>>(n));
  std::vector<std::vector<double>> batch(methods.size());
  std::vector<Timing> out(methods.size());
  for (Timing& t : out) t.answers.resize(n);
  for (int r = 0; r < reps; ++r)
    for (std::size_t m = 0; m < methods.size(); ++m) {
      for (std::size_t i = 0; i < n; ++i) {
        const double c0 = thread_cpu_ns();
        Answer a;
        try {
          a = methods[m].project(set.points[i]);
        } catch (const Standard_Failure&) {
          a = Answer{};
        }
        const double c1 = thread_cpu_ns();
        cpu[m][i].push_back(std::max(0.0, c1 - c0 - overhead));
        out[m].answers[i] = a;
      }
      const double b0 = thread_cpu_ns();
      double sink = 0.0;
      for (std::size_t i = 0; i < n; ++i) {
        try {
          sink += methods[m].project(set.points[i]).distance;
        } catch (const Standard_Failure&) {
        }
      }
      batch[m].push_back((thread_cpu_ns() - b0) / static_cast<double>(n));
      if (sink == -1.0) std::printf(" ");
    }
  for (std::size_t m = 0; m < methods.size(); ++m) {
    for (std::size_t i = 0; i < n; ++i) out[m].ns.push_back(percentile(cpu[m][i], 0.5));
    out[m].batch_ns = percentile(batch[m], 0.5);
  }
  return out;
}

// footpoint's `auto` on the surface: its formulas compiled, or its B-spline definition read as the
// server reads a posted one.
PeerMethod footpoint_auto(const ComparisonSurface& s) {
  std::shared_ptr<const CompiledGeometry> g;
  if (s.bspline) {
    const std::string text = s.bspline->dump();
    server::JsonReader reader(text);
    g = compile_geometry(server::read_geometry(reader, ""));
  } else {
    g = compile_surface(s.x, s.y, s.z, s.u, s.v);
  }
  return {"footpoint auto", [g, method = g->method("auto").value()](const std::array<double, 3>& p) {
            const ProjectionResult r = method.project(p.data(), Options{});
            return Answer{r.summary.status == Status::converged, r.distance};
          }};
}

int run(int argc, char** argv) {
  std::string dir = FOOTPOINT_OCCT_DIR;
  int reps = 5;
  std::vector<std::string> names;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--reps") && i + 1 < argc) {
      reps = std::max(1, std::atoi(argv[++i]));
    } else if (!std::strcmp(argv[i], "--data") && i + 1 < argc) {
      dir = argv[++i];
    } else {
      names.emplace_back(argv[i]);
    }
  }
  if (names.empty()) names = comparison_surface_names(dir);
  const double overhead = timer_overhead_ns();
  std::printf(
      "occt_compare: footpoint auto and Open CASCADE %s on the same points, one thread, %d repetitions; "
      "thread CPU time per point less the timer's overhead (%.0f ns); %s\n",
      OCC_VERSION_COMPLETE, reps, overhead, load_average().c_str());
  std::printf(
      "not global: distance more than 1e-9 relative above the 50-digit reference; max rel err over the "
      "others\n\n");
  std::printf("%-4s %-5s %6s  %-24s %10s %9s %12s %12s %9s %12s\n", "surf", "set", "points", "method",
              "median µs", "p90 µs", "batch µs/pt", "not global", "no answer", "max rel err");
  for (const std::string& name : names) {
    const ComparisonSurface s = read_comparison_surface(dir, name);
    std::vector<PeerMethod> methods;
    if (s.footpoint)
      methods.push_back(footpoint_auto(s));
    else
      std::printf("%-4s footpoint: type not yet measured (%s; surfaces.json \"footpoint\": false)\n",
                  s.name.c_str(), s.bspline ? "bspline_surface" : "formulas");
    OcctSurface occt;
    if (make_occt(s, occt))
      for (PeerMethod& m : occt_methods(occt)) methods.push_back(std::move(m));
    for (const PointSet& set : s.sets) {
      const std::vector<Timing> t = time_methods(methods, set, reps, overhead);
      for (std::size_t m = 0; m < methods.size(); ++m) {
        const Accuracy a = accuracy(t[m].answers, set.references);
        std::printf("%-4s %-5s %6zu  %-24s %10.2f %9.2f %12.2f %5d (%4.1f%%) %9d %12.1e\n", s.name.c_str(),
                    set.name.c_str(), set.points.size(), methods[m].name.c_str(),
                    percentile(t[m].ns, 0.5) / 1e3, percentile(t[m].ns, 0.9) / 1e3, t[m].batch_ns / 1e3,
                    a.not_global, 100.0 * a.not_global / std::max(a.points, 1), a.no_answer,
                    a.max_relative_error);
      }
    }
    if (occt.surface.IsNull())
      std::printf("%-4s (no exact Open CASCADE form: footpoint only)\n", s.name.c_str());
  }
  std::printf("\n%s\n", load_average().c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "occt_compare: %s\n", e.what());
  } catch (const Standard_Failure& e) {
    std::fprintf(stderr, "occt_compare: Open CASCADE: %s\n", e.GetMessageString());
  }
  return 1;
}
