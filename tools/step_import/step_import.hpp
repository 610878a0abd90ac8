// footpoint-import's library: the faces of a STEP file as footpoint geometry definitions.
//
// Each face of the file's shape (STEP read by Open CASCADE's STEPControl_Reader, located) gives
// its underlying surface over the face's parameter rectangle (BRepTools::UVBounds), converted
// to a B-spline surface (GeomConvert::SurfaceToBSplineSurface, exact for Open CASCADE's
// elementary and swept surfaces: planes, cylinders, cones, spheres and tori become rational
// B-splines; periodic ones are made non-periodic) and written as a `bspline_surface` definition
// (docs/nurbs.md): degrees, full knot vectors, control points u first, weights when rational.
//
// Limits, honestly: the faces are NOT trimmed. A face's boundary curves are not applied: a disk
// cut from a plane becomes the square around it, a face with holes the surface without them, so
// the distance to a definition is at most the distance to its face (the face lies in it) and
// equals it where the foot lies inside the face. Faces whose surface cannot be converted (an
// offset of a non-smooth surface, a surface without a parameter range) are listed as skipped
// with Open CASCADE's reason. Curves and points of the file are not imported.
#pragma once
#include <nlohmann/json.hpp>
#include <string>

namespace footpoint::import {

// {"file": path, "faces": [{"index", "surface" (Open CASCADE's type), "parameter_range":
// {"u": [u1, u2], "v": [v1, v2]}, "definition"}], "skipped": [{"index", "surface", "reason"}],
// "trimmed": false}. Throws std::runtime_error when the file cannot be read as STEP.
nlohmann::json import_step(const std::string& path);

}  // namespace footpoint::import
