#include "step_import.hpp"

#include <BRepTools.hxx>
#include <BRep_Tool.hxx>
#include <GeomConvert.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Geom_RectangularTrimmedSurface.hxx>
#include <Geom_Surface.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <STEPControl_Reader.hxx>
#include <Standard_Failure.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Face.hxx>
#include <stdexcept>

namespace footpoint::import {

namespace {

// The full (flat) knot vector of one direction: every knot repeated by its multiplicity, n + p + 1
// of them for n control points of degree p.
nlohmann::json flat_knots(const Geom_BSplineSurface& s, bool u) {
  const int count = u ? s.NbUPoles() + s.UDegree() + 1 : s.NbVPoles() + s.VDegree() + 1;
  TColStd_Array1OfReal knots(1, count);
  if (u)
    s.UKnotSequence(knots);
  else
    s.VKnotSequence(knots);
  nlohmann::json out = nlohmann::json::array();
  for (int i = knots.Lower(); i <= knots.Upper(); ++i) out.push_back(knots(i));
  return out;
}

// The definition of a (non-periodic) B-spline surface: control_points[i][j] is P_ij, i along u.
nlohmann::json definition(const Geom_BSplineSurface& s) {
  nlohmann::json points = nlohmann::json::array(), weights = nlohmann::json::array();
  for (int i = 1; i <= s.NbUPoles(); ++i) {
    nlohmann::json row = nlohmann::json::array(), row_weights = nlohmann::json::array();
    for (int j = 1; j <= s.NbVPoles(); ++j) {
      const gp_Pnt p = s.Pole(i, j);
      row.push_back({p.X(), p.Y(), p.Z()});
      row_weights.push_back(s.Weight(i, j));
    }
    points.push_back(std::move(row));
    weights.push_back(std::move(row_weights));
  }
  nlohmann::json d = {{"type", "bspline_surface"},
                      {"degree", {s.UDegree(), s.VDegree()}},
                      {"knots", {{"u", flat_knots(s, true)}, {"v", flat_knots(s, false)}}},
                      {"control_points", std::move(points)}};
  if (s.IsURational() || s.IsVRational()) d["weights"] = std::move(weights);
  return d;
}

}  // namespace

nlohmann::json import_step(const std::string& path) {
  STEPControl_Reader reader;
  if (reader.ReadFile(path.c_str()) != IFSelect_RetDone)
    throw std::runtime_error(path + ": not a STEP file Open CASCADE can read");
  reader.TransferRoots();
  const TopoDS_Shape shape = reader.OneShape();
  nlohmann::json faces = nlohmann::json::array(), skipped = nlohmann::json::array();
  int index = 0;
  for (TopExp_Explorer faces_of(shape, TopAbs_FACE); faces_of.More(); faces_of.Next(), ++index) {
    const TopoDS_Face& face = TopoDS::Face(faces_of.Current());
    // The surface with the face's location applied (a copy when it is not the identity).
    const Handle(Geom_Surface) surface = BRep_Tool::Surface(face);
    if (surface.IsNull()) {
      skipped.push_back({{"index", index}, {"surface", nullptr}, {"reason", "the face has no surface"}});
      continue;
    }
    const std::string type = surface->DynamicType()->Name();
    try {
      Standard_Real u1 = 0, u2 = 0, v1 = 0, v2 = 0;
      BRepTools::UVBounds(face, u1, u2, v1, v2);
      if (!(u1 < u2) || !(v1 < v2)) throw std::runtime_error("the face's parameter rectangle is empty");
      const Handle(Geom_BSplineSurface) bspline =
          GeomConvert::SurfaceToBSplineSurface(new Geom_RectangularTrimmedSurface(surface, u1, u2, v1, v2));
      if (bspline->IsUPeriodic()) bspline->SetUNotPeriodic();
      if (bspline->IsVPeriodic()) bspline->SetVNotPeriodic();
      faces.push_back({{"index", index},
                       {"surface", type},
                       {"parameter_range", {{"u", {u1, u2}}, {"v", {v1, v2}}}},
                       {"definition", definition(*bspline)}});
    } catch (const Standard_Failure& e) {
      skipped.push_back({{"index", index}, {"surface", type}, {"reason", e.GetMessageString()}});
    } catch (const std::exception& e) {
      skipped.push_back({{"index", index}, {"surface", type}, {"reason", e.what()}});
    }
  }
  return {{"file", path}, {"faces", std::move(faces)}, {"skipped", std::move(skipped)}, {"trimmed", false}};
}

}  // namespace footpoint::import
