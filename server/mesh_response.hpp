// The mesh of a geometry as a response body: JSON for the page and programs, or Wavefront OBJ for
// 3-D tools. OBJ rather than PLY: curves are polylines, and OBJ has a standard element for them
// (`l`, and `p` for the singular points) where PLY has none (its optional `edge` element joins two
// vertices, and readers differ on it); vertex normals (`vn`) are standard too, and every 3-D tool
// (Blender, MeshLab, ParaView, three.js's OBJLoader) reads it. Coordinates are written in the
// shortest form that reads back as the same double, in both formats.
#pragma once
#include <string>

#include "compiled/compiled_geometry.hpp"
#include "mesh/mesh.hpp"

namespace footpoint::server {

// {"geometry_id", "type", "point_dim", "resolution", "vertices": [x0, y0, z0, x1, ...],
//  "normals" (surfaces) or "tangents" (curves): flat like vertices, "parameters" (u, v or t per
//  vertex, flat; not for implicit curves), "triangles": [a0, b0, c0, a1, ...] (vertex indices,
//  counter-clockwise about the normals), "polylines": [{"vertices": [...], "closed"}],
//  "singular_points": [vertex indices]}
std::string mesh_json(const CompiledGeometry& geometry, const Mesh& mesh, int resolution);

// v, vn (surfaces), f a//a b//b c//c, l (a closed polyline repeats its first vertex), p; 1-based.
std::string mesh_obj(const CompiledGeometry& geometry, const Mesh& mesh, int resolution);

}  // namespace footpoint::server
