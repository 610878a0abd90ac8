// Meshes of compiled geometries, for looking at them: a triangulated parameter grid of a
// parametric surface, polylines of a curve (a parametric curve's parameter line; an implicit
// curve's pieces as the `auto` seeding traced them, with its singular points; marching
// tetrahedra for an implicit surface, mesh/implicit_surface_mesh.hpp). Every vertex is a
// point of the geometry (evaluated from the formula tape, or a traced sample on the curve), every
// triangle has positive area, and no coordinate is NaN or infinite (parts of the domain where the
// formulas are not finite are left out).
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "compiled/compiled_geometry.hpp"
#include "geometry/vec.hpp"

namespace footpoint {

// A path through the mesh's vertices; a closed one joins its last vertex to its first.
struct Polyline {
  std::vector<std::int32_t> vertices;
  bool closed = false;
};

struct Mesh {
  int num_params = 0;              // parameters per vertex: 2 surfaces, 1 parametric curves, 0 implicit
  std::vector<Vec3> vertices;      // planar curves have z = 0
  std::vector<Vec3> normals;       // surfaces: unit normal per vertex (empty for curves)
  std::vector<Vec3> tangents;      // curves: unit tangent per vertex along its polyline (empty for surfaces)
  std::vector<double> parameters;  // num_params values per vertex: (u, v) or t
  std::vector<std::array<std::int32_t, 3>> triangles;  // counter-clockwise about the normals
  std::vector<Polyline> polylines;
  std::vector<std::int32_t> singular_points;  // vertices where an implicit curve's branches meet
};

struct MeshOptions {
  // Surfaces: cells along the parameter direction that needs the most (the other direction gets
  // its share, at least 2); curves: segments in all. At least 2.
  int resolution = 128;
};

// The mesh of `geometry` (a ParametricSurface, ParametricCurve, ImplicitCurve or ImplicitSurface). Throws
// std::invalid_argument for a resolution below 2.
Mesh mesh_geometry(const CompiledGeometry& geometry, const MeshOptions& options);

}  // namespace footpoint
