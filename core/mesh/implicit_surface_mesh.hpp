// The mesh of an implicit surface clipped to its box: marching tetrahedra (A. Doi, A. Koide, "An
// efficient method of triangulating equi-valued surfaces by using tetrahedral cells", IEICE
// Transactions E74(1), 1991) over a grid of the box, each cube cut into six tetrahedra about its
// main diagonal; a vertex where f changes sign along a tetrahedron's edge is the linear
// interpolation there, moved onto the surface by Newton steps along the gradient (kept when it
// lands within the edge's cube), so that every vertex is a point of the surface. Normals are
// grad f / |grad f|; triangles are ordered counter-clockwise about them.
#pragma once
#include "compiled/implicit_surface_geometry.hpp"
#include "mesh/mesh.hpp"

namespace footpoint {

// Cells along the box's longest edge (the others in proportion, at least 2): at most this many.
inline constexpr int kMaxImplicitSurfaceMeshCells = 128;

Mesh mesh_implicit_surface(const ImplicitSurface& surface, int resolution);

}  // namespace footpoint
