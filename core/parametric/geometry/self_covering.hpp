// A parametrisation that covers its image several times over its parameter box, as [GSA] Ex. 1
// s = (u + v, sin u + 2 cos v, sin(u + v)) over [-25,25]^2 does (about 16 times: the translation
// (2π, -2π) and a fold in each period): translations δ with s(t + δ) = s(t) for every t, read
// from the formulas' structure (formula::Program::invariant_translations; proven in real
// arithmetic, not sampled), found once per geometry at compile time.
//
// What it buys: a part of the box that is a translate of another part of the box adds no point
// of the surface. With the translations taken lexicographically positive, every t in the box
// lies in box + δ for some δ, and then t - δ is in the box and lexicographically lower; from t,
// stepping down that way ends (the box is bounded, the translations finitely many) at a point
// lying in no box + δ. So the surface is the image of the rectangles that do not lie wholly in
// some box + δ; the others (covered()) need neither search nor certificate: their points are
// the same points of the surface as the rest's. For Ex. 1 over [-25,25]^2 the rest is an L-shaped
// strip of width 2π along u = -25 and v = 25, a quarter of the box.
#pragma once
#include <array>
#include <vector>

#include "parametric/geometry/parametric_surface.hpp"
#include "parametric/geometry/params.hpp"

namespace footpoint {

struct SelfCovering {
  // lexicographically positive (δu > 0, or δu = 0 and δv > 0), shortest first
  std::vector<Params<2>> translations;
  // The rectangle [u0, u1] x [v0, v1] lies in box + δ for one of the translations, by a margin
  // of 1e-12 (|δ| + the box's largest coordinate) for the rounding of δ's double value.
  bool covered(const ParamBox& box, double u0, double u1, double v0, double v1) const;

  // The parameter copies of the points `seeds` in the box: every t ± δ_1 ± δ_2 ... reached from a
  // seed by steps along the translations that stay in the box (within the margin above; such a
  // copy is moved onto the box's edge), the seeds included, in increasing u, then v. Points within
  // 1e-9 (1 + |t|) of each other are one. At most `cap` (*truncated when more were reached).
  // Complete when `translations` holds every translation that fits in the box (at most 64 do,
  // detect_self_covering): two copies in the box differ by one of them, one step.
  std::vector<Params<2>> copies(const ParamBox& box, const std::vector<Params<2>>& seeds, std::size_t cap,
                                bool* truncated) const;
};

// At most 64 translations, the shortest (any subset serves the argument above).
SelfCovering detect_self_covering(const SurfaceFormulas& formulas, const ParamBox& box);

}  // namespace footpoint
