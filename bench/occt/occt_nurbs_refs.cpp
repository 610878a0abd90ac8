// Open CASCADE 7.6 as a second opinion on the NURBS nearest-point references
// (tests/data/nurbs_projection_cases.json, tests/tools/gen_nurbs_projection_refs.py): every
// geometry as Geom_BSplineCurve / Geom_BSplineSurface from the same definition, every point
// projected by
//  - curves: GeomAPI_ProjectPointOnCurve over the domain and the two end points, the nearest;
//  - surfaces: GeomAPI_ProjectPointOnSurf, and Extrema_ExtPS with the four boundary curves and the
//    corners (occt_geometry.hpp, as occt_compare asks it);
// and where the geometry has knots of multiplicity >= degree (possible kinks), once more with the
// curve's points there, or the surface's iso-lines there searched like its edges.
// Per geometry and method: how many answers agree with the reference (|d - d_ref| <= 1e-9 max(1,
// d_ref)), how many are farther (Open CASCADE missed the global point), the largest disagreement
// of the agreeing ones, and how many are nearer than the reference by more than 1e-12 max(1,
// d_ref): a reference that is not the global minimum. Exit status 1 if there is any such point.
// Points whose reference is a continuum tie (the circle's centre) are skipped.
//
// Usage: occt_nurbs_refs [FILE]   (default: tests/data/nurbs_projection_cases.json of the source tree)
#include <Standard_Failure.hxx>
#include <Standard_Version.hxx>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "occt_geometry.hpp"

using namespace footpoint::bench;

namespace {

struct Tally {
  int points = 0, agree = 0, farther = 0, nearer = 0, no_answer = 0;
  double max_agree = 0.0, worst_nearer = 0.0;
};

void count(Tally& t, const Answer& a, double ref) {
  ++t.points;
  if (!a.ok) {
    ++t.no_answer;
    return;
  }
  const double scale = std::max(1.0, ref), diff = a.distance - ref;
  if (diff < -1e-12 * scale) {
    ++t.nearer;
    t.worst_nearer = std::min(t.worst_nearer, diff / scale);
  } else if (diff > 1e-9 * scale) {
    ++t.farther;
  } else {
    ++t.agree;
    t.max_agree = std::max(t.max_agree, std::fabs(diff) / scale);
  }
}

// The nearest of GeomAPI_ProjectPointOnCurve's extrema over the domain and the given points of the
// curve (its ends; with `knots`, also the points at those parameters).
PeerMethod curve_method(const Handle(Geom_BSplineCurve) & c, const std::vector<double>& knots) {
  auto api = std::make_shared<GeomAPI_ProjectPointOnCurve>();
  api->Init(c, c->FirstParameter(), c->LastParameter());
  std::vector<gp_Pnt> vertices{c->StartPoint(), c->EndPoint()};
  for (double t : knots) vertices.push_back(c->Value(t));
  return {knots.empty() ? "ProjectPointOnCurve+ends" : "ProjectPointOnCurve+ends+C0",
          [api, vertices](const std::array<double, 3>& p) {
            const gp_Pnt q(p[0], p[1], p[2]);
            double best = 1e300;
            for (const gp_Pnt& v : vertices) best = std::min(best, q.Distance(v));
            api->Perform(q);
            if (api->NbPoints() > 0) best = std::min(best, api->LowerDistance());
            return Answer{true, best};
          }};
}

int run(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path);
  const nlohmann::json data = nlohmann::json::parse(in);
  std::printf("occt_nurbs_refs: Open CASCADE %s on %s\n", OCC_VERSION_COMPLETE, path.c_str());
  std::printf(
      "agree: |d - ref| <= 1e-9 max(1, ref); nearer: d < ref - 1e-12 max(1, ref) (a reference that is "
      "not global)\n\n");
  std::printf("%-44s %-30s %6s %6s %7s %6s %9s %11s\n", "geometry", "method", "points", "agree", "farther",
              "nearer", "no answer", "max |diff|");
  int nearer = 0;
  for (const nlohmann::json& c : data.at("cases")) {
    const nlohmann::json& d = c.at("definition");
    std::vector<PeerMethod> methods;
    if (d.at("type") == "bspline_curve") {
      const Handle(Geom_BSplineCurve) curve = occt_bspline_curve(d);
      const std::vector<double> kinks = c0_knots(d.at("knots"), d.at("degree"));
      methods.push_back(curve_method(curve, {}));
      if (!kinks.empty()) methods.push_back(curve_method(curve, kinks));
    } else {
      const auto degree = d.at("degree").get<std::array<int, 2>>();
      const nlohmann::json &ku = d.at("knots").at("u"), &kv = d.at("knots").at("v");
      const std::size_t nu = d.at("control_points").size(), nv = d.at("control_points").at(0).size();
      const OcctSurface o{occt_bspline(d), ku.at(static_cast<std::size_t>(degree[0])).get<double>(),
                          ku.at(nu).get<double>(), kv.at(static_cast<std::size_t>(degree[1])).get<double>(),
                          kv.at(nv).get<double>()};
      methods = occt_methods(o);
      const std::vector<double> us = c0_knots(ku, degree[0]), vs = c0_knots(kv, degree[1]);
      if (!us.empty() || !vs.empty()) methods.push_back(occt_methods(o, us, vs).back());
    }
    for (const PeerMethod& m : methods) {
      Tally t;
      for (const nlohmann::json& r : c.at("points")) {
        if (r.value("tie", "") == "continuum") continue;
        std::array<double, 3> p{0.0, 0.0, 0.0};
        for (std::size_t k = 0; k < r.at("p").size(); ++k) p[k] = r["p"][k].get<double>();
        Answer a;
        try {
          a = m.project(p);
        } catch (const Standard_Failure&) {
          a = Answer{};
        }
        count(t, a, r.at("distance").get<double>());
      }
      std::printf("%-44s %-30s %6d %6d %7d %6d %9d %11.1e\n", c.at("name").get<std::string>().c_str(),
                  m.name.c_str(), t.points, t.agree, t.farther, t.nearer, t.no_answer, t.max_agree);
      if (t.nearer) std::printf("   NEARER than the reference by up to %.1e (relative)\n", -t.worst_nearer);
      nearer += t.nearer;
    }
  }
  std::printf("\n%s\n", nearer ? "FAILED: Open CASCADE found points nearer than references"
                               : "no reference is beaten by Open CASCADE");
  return nearer ? 1 : 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc > 1 ? argv[1] : FOOTPOINT_NURBS_REFS);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "occt_nurbs_refs: %s\n", e.what());
  } catch (const Standard_Failure& e) {
    std::fprintf(stderr, "occt_nurbs_refs: Open CASCADE: %s\n", e.GetMessageString());
  }
  return 2;
}
