// Where a parametric surface's parameter box meets itself in 3-D, decided once per geometry at
// compile time, below everything that searches or draws it: seams (a direction whose two edges are
// one curve: a torus in u and v, a sphere's or a cylinder's longitude) and poles (an edge that is
// one point: a sphere's poles, a cone's apex).
//
// How it is decided (detect_surface_closure):
//  - Samples. Each edge is sampled at its two ends and at 32 parameters inside, (k + α)/32 of the
//    way along (k = 0..31) with α = (3 - √5)/2: an irrational offset, so that a gap oscillating a
//    whole number of times along the edge does not hide in zeros between the samples.
//  - One tolerance, at rounding level (`tolerance`): 256 ε (M + S_u U + S_v V), ε = 2^-52, M the
//    largest coordinate magnitude sampled, S_u and S_v the largest |s_u| and |s_v| on the edges, U
//    and V the largest |u| and |v| of the box. The first term is the rounding of the formulas'
//    values, the others that of the parameters themselves: an edge at 2π is at the double nearest
//    2π, and a torus's edges u = 0 and u = 2π are ~1e-16 apart for that reason alone.
//  - Seam of direction u: at every sample |s(umax, v_k) - s(umin, v_k)| <= tolerance (a sample
//    where both edges are undefined, NaN, is skipped; where one is, there is no seam; at least half
//    the samples must be defined). Failing that, the edges reversed: s(umax, v_k) against
//    s(umin, vmin + vmax - v_k). That is a seam too (a Möbius band's), marked `reversed`: the
//    surface closes, but not periodically - s(u + period, v) is the mirrored point, not s(u, v).
//    The same for v.
//  - Crease: positions match and yet the unit normals s_u x s_v / |.| of the two sides differ by
//    more than 1e-6 at a sample where both are well defined (|s_u x s_v| >= 1e-4 |s_u| |s_v|).
//    It is still a seam, with `smooth` false: the surface closes with a kink, like the edge of a
//    solid. For a reversed seam the continuation (u - period, vmin + vmax - v) turns the normal
//    around, so there the normals must be opposite.
//  - Pole: every sample of the edge within `tolerance` of their mean (`point`).
//  - Declared periodic (the definition's "periodic"): accepted when the edges are within
//    max(tolerance, 1e-6 x the size) at every sample, the size being the diagonal of the sampled
//    points' bounding box; then `declared`, and the direction counts as periodic whatever the
//    detection found. A declared direction beyond that throws GeometryError `not_periodic`: its
//    edges visibly do not coincide, and treating them as one would put a jump into the surface.
//    Poles are detected only: an edge is a point or it is not, nothing for a user to force.
//
// What is proven, and what is only sampled:
//  - A pole's `radius_bound` is rigorous: the interval enclosure of s over the whole edge (four
//    pieces, Program::intervals) lies within it of `point`. For the usual poles - a factor that
//    vanishes on the edge (cos v at v = π/2, v at a cone's apex) multiplies all that depends on
//    the other parameter - the enclosure is as tight as the samples: the pole is proven at
//    rounding level.
//  - A seam's `gap_bound` is rigorous too, but not at rounding level: between consecutive samples,
//    the gap d(t) = s(hi, t) - s(lo, σ(t)) (σ the identity, or the reversal) is enclosed by
//    Taylor's theorem from the nearer sample, d(e) + d'(e) (t - e) + ½ d''(ξ) (t - e)^2, with d(e)
//    and d'(e) enclosed by interval jets at the sample and d'' over the piece (formula/
//    interval_jet.hpp; a piece where the formulas are not smooth falls back to first order or to
//    the value enclosure). The enclosure s(hi, T) - s(lo, T) of the two sides taken apart cannot
//    reach rounding level - its width is each side's own variation, |s_t| |T| - while the Taylor
//    form's is ~ |s_ttt| |T|^3 / 4: 2.4e-3 for the torus (2 + cos v / 2) e(u) + sin v / 2 e_z
//    (size 7.1) with 33 pieces. So the bound proves that no separation larger than that hides
//    between the samples; that the edges coincide to rounding level is shown at the samples only.
//    Both bounds are about the formulas' exact values at the double parameters of the edges.
//  - Creases are sampled only.
// Not recognized: edges that are one curve under another correspondence than the identity or the
// reversal (glued with a shift, s(umax, v) = s(umin, v + c), as a torus parametrised along a
// twisted grid): they are reported open, as boundary edges - conservative, not wrong.
// The cost: ~200 second-order jets for a surface without seams, ~130 interval jets more per seam
// found (its gap_bound); bench/closure_bench times it.
#pragma once
#include <array>
#include <limits>

#include "parametric/geometry/parametric_surface.hpp"

namespace footpoint {

// The edges of a parameter box, in this order wherever edges are listed.
enum class BoxEdge { umin, umax, vmin, vmax };
// "u=umin", "u=umax", "v=vmin", "v=vmax".
const char* to_string(BoxEdge edge);

// One parameter direction's edges (u = umin and u = umax, or v = vmin and v = vmax).
struct SurfaceSeam {
  bool closed = false;    // the two edges are one curve in 3-D
  bool reversed = false;  // ... traversed in opposite directions (the other parameter mirrored)
  bool smooth = false;    // closed, and the tangent planes agree across it (else a crease)
  bool declared = false;  // the definition declares the direction periodic (and it is accepted)
  double max_gap = 0.0;   // the largest distance between matched edge points at the samples
  // A rigorous bound of that distance over the whole edges (infinite when there is none).
  double gap_bound = std::numeric_limits<double>::infinity();
  // s(u + period, v) = s(u, v): closed the same way round.
  bool periodic() const { return closed && !reversed; }
};

// One edge of the box.
struct SurfacePole {
  bool collapsed = false;  // the whole edge is one point
  Vec3 point;              // that point (the mean of the edge's samples)
  // A rigorous bound of |s - point| over the whole edge (infinite when there is none).
  double radius_bound = std::numeric_limits<double>::infinity();
};

struct SurfaceClosure {
  std::array<SurfaceSeam, 2> seams{};  // [0]: u, [1]: v
  std::array<SurfacePole, 4> poles{};  // by BoxEdge
  double tolerance = 0.0;              // the rounding-level distance under which points are one
  bool periodic(int direction) const { return seams[static_cast<std::size_t>(direction)].periodic(); }
  bool pole(BoxEdge edge) const { return poles[static_cast<std::size_t>(edge)].collapsed; }
};

// Seams and poles of s over `box`; declared_periodic[0] (u) and [1] (v) are the definition's
// "periodic". Throws GeometryError (code not_periodic, field "periodic") for a declared direction
// whose edges do not coincide.
SurfaceClosure detect_surface_closure(const SurfaceFormulas& formulas, const ParamBox& box,
                                      std::array<bool, 2> declared_periodic = {});

}  // namespace footpoint
