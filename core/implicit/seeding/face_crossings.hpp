// The points where an implicit curve meets one face of a cell, each proved alone in a small box.
//
// On a face (coordinate x_a fixed) the curve's points solve a square system in the face's free
// coordinates: f1 = f2 = 0 in two unknowns (spatial curves), f = 0 in one (planar). The face is
// subdivided; a sub-face Q is
//  - dropped when the interval enclosure of an equation over Q excludes 0 (its range, or the mean
//    value form f(m) + ∇f(Q)·(Q - m) about the centre m: both rigorous, formula/interval_jet.hpp);
//  - decided by Krawczyk's test (geometry/krawczyk.hpp) where the system's Jacobian in the free
//    coordinates is regular over Q: ∂f/∂x_b ≠ 0 (planar), or its determinant, which is ±T_a with
//    T = ∇f1 × ∇f2 ([Curve] eq. (7)), bounded away from 0 (spatial). K(Q) ∩ Q = ∅: no point;
//    K(Q) ⊂ int Q: exactly one, then Newton on the face gives it to rounding and the contraction
//    bound of krawczyk.hpp a tight box around it;
//  - else bisected (a little off its centre, so that a point of the curve on a grid line of
//    nice numbers does not fall on every split).
// Points where the curve touches the face (a double root: the Jacobian is singular there) are not
// decided: the search then fails, and the caller treats the cell as unproved.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "implicit/geometry/implicit_curve.hpp"

namespace footpoint {

struct FaceCrossing {
  Vec3 point;      // a point of the curve on the face (Newton), inside `enclosure`
  Box3 enclosure;  // holds exactly one point of the curve on the face; flat along the face's axis
};

// Appends to `out` every point of the curve on `face` (a box flat along `axis`: lo[axis] ==
// hi[axis]). False when some part of the face could not be decided (a touching point, a formula
// not twice differentiable there, or the sub-face budget); `out` then holds what was found.
// `evaluations` counts the interval evaluations made. A face costs at most a fixed number of
// sub-faces, so the compile budget is checked by the loops over cells that call this, not here.
bool locate_face_crossings(const ImplicitEquations& equations, const Box3& face, int axis,
                           std::vector<FaceCrossing>& out, std::size_t& evaluations);

// The same, remembering every face searched: two cells that share a face (the same box) search
// it once.
class FaceCrossingCache {
 public:
  explicit FaceCrossingCache(const ImplicitEquations& equations) : equations_(equations) {}
  bool locate(const Box3& face, int axis, std::vector<FaceCrossing>& out, std::size_t& evaluations);

 private:
  struct Key {
    std::array<std::uint64_t, 6> bits;
    bool operator==(const Key& k) const { return bits == k.bits; }
  };
  struct Hash {
    std::size_t operator()(const Key& k) const;
  };
  struct Found {
    bool decided = false;
    std::vector<FaceCrossing> crossings;
  };
  const ImplicitEquations& equations_;
  std::unordered_map<Key, Found, Hash> faces_;
};

}  // namespace footpoint
