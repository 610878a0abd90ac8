// `auto` for implicit surfaces: the global nearest point of S = {f = 0} clipped to the box B.
// Candidates: the points where S meets B's edges and corners and the singular points of S (all
// precomputed, implicit/seeding/implicit_surface_cells.hpp); the local minimum that Newton on the
// Lagrange system reaches from the sample of the nearest leaf (implicit/solvers/
// implicit_surface_lagrange.hpp), and where that leaves B or the leaf touches a face, the minimum
// on the face (the curve where S meets it, by the face's Lagrange system). The certificate
// (implicit_surface_certificate.hpp) then bounds the distance over all of S ∩ B; a leaf whose
// sample is nearer than the answer becomes a start, and the certificate is redone, a few times.
// With options.all_minima, every sample nearer to p than the samples around it (within two leaf
// diagonals) starts a solve too, and the ends that are local minima of the distance on the
// surface in the box (second-order conditions, the faces' multiplier signs) are listed with the
// answer first.
#pragma once
#include "implicit/seeding/implicit_surface_cells.hpp"
#include "projection/projection_result.hpp"

namespace footpoint::surface_implicit {

ProjectionResult implicit_surface_auto(const ImplicitSurfaceEquation& equation,
                                       const ImplicitSurfaceCells& cells, Vec3 p, const Options& options);

}  // namespace footpoint::surface_implicit
