// The nearest point of a geometry made of pieces (a NURBS cut at its knots into Bézier pieces,
// parametric/geometry/nurbs_patches.hpp), each with a box that holds it: a branch and bound over
// the pieces. The distance from p to a piece's box is a lower bound of the distance to the piece;
// the pieces are visited nearest box first, each solved by its own global method, and a piece is
// left out once its box is farther than the best distance found plus the certificate's gap
// (geometry/certificate.hpp): no point of it can be nearer, nor tie. The answer's certificate is
// the pieces': its lower bound is the smallest of the solved pieces' lower bounds and the boxes
// of the pieces left out, so it is as rigorous as theirs; a foot on two pieces (their shared edge)
// or on several at the same distance is one answer with the multiplicity of the distinct feet.
//
// With options.all_minima every piece within options.max_distance is solved, and the minima are
// the pieces' merged (a minimum on a shared edge once), best first.
#pragma once
#include <cstddef>
#include <functional>
#include <vector>

#include "geometry/box3.hpp"
#include "geometry/projection_result.hpp"

namespace footpoint {

// A lower bound of the distance from p to any point of the box (0 inside), rounded down.
double distance_lower_bound(const Box3& box, const Vec3& p);

struct PiecewiseNearest {
  ProjectionResult result;  // the answer, from the nearest piece's answer
  std::size_t piece = 0;    // that piece (meaningless without a finite answer)
  int pieces_solved = 0;
};

// `solve(k, options)` projects p onto piece k with its global method (the options passed on; the
// caller decides what options.initial means for piece k).
PiecewiseNearest nearest_over_pieces(
    const std::vector<Box3>& hulls, const Vec3& p, const Options& options,
    const std::function<ProjectionResult(std::size_t, const Options&)>& solve);

}  // namespace footpoint
