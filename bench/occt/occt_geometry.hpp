// Open CASCADE's side of the comparison (bench/occt/README.md), shared by occt_compare and
// occt_nurbs_refs: NURBS definitions (issue 35's bspline_curve / bspline_surface JSON) as
// Geom_BSplineCurve / Geom_BSplineSurface, and the two ways Open CASCADE is asked for the nearest
// point of a surface.
#pragma once

#include <Extrema_ExtPS.hxx>
#include <GeomAPI_ProjectPointOnCurve.hxx>
#include <GeomAPI_ProjectPointOnSurf.hxx>
#include <GeomAdaptor_Surface.hxx>
#include <Geom_BSplineCurve.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Precision.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColStd_Array2OfReal.hxx>
#include <TColgp_Array1OfPnt.hxx>
#include <TColgp_Array2OfPnt.hxx>

#include <array>
#include <cmath>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "point_sets.hpp"

namespace footpoint::bench {

// One way of answering: its name and the distance it reports for a point.
struct PeerMethod {
  std::string name;
  std::function<Answer(const std::array<double, 3>&)> project;
};

// Open CASCADE's form of the surface and the parameter box it is measured over.
struct OcctSurface {
  Handle(Geom_Surface) surface;
  double s0 = 0, s1 = 0, t0 = 0, t1 = 0;
};

// A full knot vector as Open CASCADE takes it: the distinct knots and their multiplicities.
struct OcctKnots {
  TColStd_Array1OfReal knots;
  TColStd_Array1OfInteger mults;
};

inline OcctKnots occt_knots(const nlohmann::json& full) {
  std::vector<double> knots;
  std::vector<int> mults;
  for (const nlohmann::json& k : full) {
    const double x = k.get<double>();
    if (!knots.empty() && knots.back() == x) {
      ++mults.back();
    } else {
      knots.push_back(x);
      mults.push_back(1);
    }
  }
  OcctKnots out{TColStd_Array1OfReal(1, static_cast<int>(knots.size())),
                TColStd_Array1OfInteger(1, static_cast<int>(knots.size()))};
  for (std::size_t i = 0; i < knots.size(); ++i) {
    out.knots.SetValue(static_cast<int>(i) + 1, knots[i]);
    out.mults.SetValue(static_cast<int>(i) + 1, mults[i]);
  }
  return out;
}

// A bspline_surface definition (control_points[i][j] = P_ij, i along u) as Geom_BSplineSurface:
// poles (i + 1, j + 1), weights where given, non-periodic (a closed net stays a clamped surface).
inline Handle(Geom_BSplineSurface) occt_bspline(const nlohmann::json& d) {
  const nlohmann::json& net = d.at("control_points");
  const int nu = static_cast<int>(net.size()), nv = static_cast<int>(net.at(0).size());
  TColgp_Array2OfPnt poles(1, nu, 1, nv);
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const auto q =
          net[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)].get<std::array<double, 3>>();
      poles.SetValue(i + 1, j + 1, gp_Pnt(q[0], q[1], q[2]));
    }
  const OcctKnots u = occt_knots(d.at("knots").at("u")), v = occt_knots(d.at("knots").at("v"));
  const int p = d.at("degree").at(0), q = d.at("degree").at(1);
  if (!d.contains("weights") || d["weights"].empty())
    return new Geom_BSplineSurface(poles, u.knots, v.knots, u.mults, v.mults, p, q);
  TColStd_Array2OfReal weights(1, nu, 1, nv);
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j)
      weights.SetValue(i + 1, j + 1,
                       d["weights"][static_cast<std::size_t>(i)][static_cast<std::size_t>(j)].get<double>());
  return new Geom_BSplineSurface(poles, weights, u.knots, v.knots, u.mults, v.mults, p, q);
}

// A bspline_curve definition as Geom_BSplineCurve (planar points at z = 0), weights where given.
inline Handle(Geom_BSplineCurve) occt_bspline_curve(const nlohmann::json& d) {
  const nlohmann::json& cps = d.at("control_points");
  const int n = static_cast<int>(cps.size());
  TColgp_Array1OfPnt poles(1, n);
  for (int i = 0; i < n; ++i) {
    const nlohmann::json& q = cps[static_cast<std::size_t>(i)];
    poles.SetValue(i + 1, gp_Pnt(q.at(0).get<double>(), q.at(1).get<double>(),
                                 q.size() > 2 ? q.at(2).get<double>() : 0.0));
  }
  const OcctKnots k = occt_knots(d.at("knots"));
  const int p = d.at("degree");
  if (!d.contains("weights") || d["weights"].empty())
    return new Geom_BSplineCurve(poles, k.knots, k.mults, p);
  TColStd_Array1OfReal weights(1, n);
  for (int i = 0; i < n; ++i)
    weights.SetValue(i + 1, d["weights"][static_cast<std::size_t>(i)].get<double>());
  return new Geom_BSplineCurve(poles, weights, k.knots, k.mults, p);
}

// The distinct interior knots of a full knot vector whose multiplicity is at least the degree:
// where a B-spline may be only C0 (a kink that no derivative-based extremum search stops at).
inline std::vector<double> c0_knots(const nlohmann::json& full, int degree) {
  std::vector<double> out;
  const std::size_t n = full.size() - static_cast<std::size_t>(degree) - 1;
  const double lo = full.at(static_cast<std::size_t>(degree)), hi = full.at(n);
  for (std::size_t i = 0; i < full.size();) {
    std::size_t j = i;
    while (j < full.size() && full[j] == full[i]) ++j;
    const double x = full[i];
    if (x > lo && x < hi && static_cast<int>(j - i) >= degree) out.push_back(x);
    i = j;
  }
  return out;
}

// Open CASCADE's two ways of answering for the surface. u_lines, v_lines: iso-lines (C0 knot
// lines) that ExtPS+boundary searches as it does the edges, their crossings with the edges and
// each other as it does the corners.
inline std::vector<PeerMethod> occt_methods(const OcctSurface& o, const std::vector<double>& u_lines = {},
                                            const std::vector<double>& v_lines = {}) {
  std::vector<PeerMethod> methods;
  auto api = std::make_shared<GeomAPI_ProjectPointOnSurf>();
  api->Init(o.surface, o.s0, o.s1, o.t0, o.t1, Extrema_ExtAlgo_Grad);
  methods.push_back({"OCCT ProjectPointOnSurf", [api](const std::array<double, 3>& p) {
                       api->Perform(gp_Pnt(p[0], p[1], p[2]));
                       if (!api->IsDone() || api->NbPoints() < 1) return Answer{};
                       return Answer{true, api->LowerDistance()};
                     }});

  struct Complete {
    GeomAdaptor_Surface adaptor;
    Extrema_ExtPS interior;
    // Open CASCADE's projectors point into themselves: held where they never move
    std::vector<std::unique_ptr<GeomAPI_ProjectPointOnCurve>> edges;
    std::vector<gp_Pnt> corners;
  };
  auto c = std::make_shared<Complete>();
  c->adaptor.Load(o.surface, o.s0, o.s1, o.t0, o.t1);
  c->interior.Initialize(c->adaptor, o.s0, o.s1, o.t0, o.t1, Precision::PConfusion(),
                         Precision::PConfusion());
  c->interior.SetFlag(Extrema_ExtFlag_MIN);
  std::vector<double> us{o.s0, o.s1}, vs{o.t0, o.t1};
  us.insert(us.end(), u_lines.begin(), u_lines.end());
  vs.insert(vs.end(), v_lines.begin(), v_lines.end());
  for (double s : us) {
    c->edges.push_back(std::make_unique<GeomAPI_ProjectPointOnCurve>());
    c->edges.back()->Init(o.surface->UIso(s), o.t0, o.t1);
  }
  for (double t : vs) {
    c->edges.push_back(std::make_unique<GeomAPI_ProjectPointOnCurve>());
    c->edges.back()->Init(o.surface->VIso(t), o.s0, o.s1);
  }
  for (double s : us)
    for (double t : vs) c->corners.push_back(o.surface->Value(s, t));
  const bool lines = !u_lines.empty() || !v_lines.empty();
  methods.push_back(
      {lines ? "OCCT ExtPS+boundary+C0" : "OCCT ExtPS+boundary", [c](const std::array<double, 3>& p) {
         const gp_Pnt q(p[0], p[1], p[2]);
         Answer a;
         double best2 = 1e300;
         c->interior.Perform(q);
         if (c->interior.IsDone())
           for (int i = 1; i <= c->interior.NbExt(); ++i)
             if (c->interior.SquareDistance(i) < best2) best2 = c->interior.SquareDistance(i), a.ok = true;
         for (const auto& e : c->edges) {
           e->Perform(q);
           if (e->NbPoints() > 0) {
             const double d = e->LowerDistance();
             if (d * d < best2) best2 = d * d, a.ok = true;
           }
         }
         for (const gp_Pnt& k : c->corners)
           if (q.SquareDistance(k) < best2) best2 = q.SquareDistance(k), a.ok = true;
         a.distance = std::sqrt(best2);
         return a;
       }});
  return methods;
}

}  // namespace footpoint::bench
