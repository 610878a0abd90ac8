// An implicit surface f = g_1 ... g_r = 0 whose equation is a product of factors defined
// everywhere (formula::Program::factor_systems) is the union of the factor surfaces {g_i = 0},
// each regular where the product is singular only because two of them meet (a sphere and a plane
// crossing it: grad f = 0 on the circle they share). `auto` projects onto each factor surface as a
// surface of its own (implicit_surface_auto.hpp) and answers the nearest foot; the nearest point
// of a union is the nearest of the nearest points of its parts, and the union's distance is the
// least of the parts', so its certified lower bound is the least of theirs. Feet of different
// factor surfaces at the same distance (within the certificate's gap) are a tie, by the rule of
// every search (solvers/answer_multiplicity.hpp, tied_feet); a foot on two factor surfaces at
// once is a singular point of f.
#pragma once
#include <span>

#include "implicit/seeding/implicit_surface_cells.hpp"
#include "projection/projection_result.hpp"

namespace footpoint::surface_implicit {

// One factor surface: its equation and what `auto` precomputes for it in the box.
struct SurfacePiece {
  ImplicitSurfaceEquation equation;
  ImplicitSurfaceCells cells;
};

// `auto` on the union of the pieces (one piece: implicit_surface_auto on it).
ProjectionResult implicit_surface_union_auto(std::span<const SurfacePiece> pieces, Vec3 p,
                                             const Options& options);

// The certificate of an answer at `foot`, `distance` from p, on the union: each piece's branch
// and bound (implicit_surface_certificate.hpp; its Lagrangian bound holds about any point, on the
// piece or not), the least of their lower bounds.
Certificate certify_union_answer(std::span<const SurfacePiece> pieces, Vec3 p, Vec3 foot, double distance);

}  // namespace footpoint::surface_implicit
