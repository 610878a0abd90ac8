// What the certificate of a parametric curve's answer precomputes
// (parametric/solvers/parametric_curve_certificate.hpp): the parameter interval cut into cells at the curve's
// samples (parametric/seeding/curve_parametric_samples.hpp: a few sample gaps per cell), each with its
// rigorous enclosures (parametric/geometry/box_enclosure.hpp: c, c'' and |c'|^2 over the cell), the jet at
// its centre with its rounding radii (a ball jet), and the tangent-line model's error proved from them; and a
// binary hierarchy over the cells in parameter order whose nodes hold the boxes of c over their
// cells (the union of their children's), walked nearest box first.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "geometry/compile_budget.hpp"
#include "parametric/geometry/box_enclosure.hpp"
#include "parametric/geometry/parametric_curve.hpp"

namespace footpoint {

struct ParametricCurveCell {
  double t0 = 0.0, t1 = 0.0;
  CurveJet centre;            // c, c', c'' at (t0 + t1)/2 (point jet)
  BoxEnclosure<1> enclosure;  // c, c'' and |c'|^2 over [t0, t1]
  // |exact - centre| per coordinate for c and c' (from a ball jet at the centre)
  Vec3 c_rad, d1_rad;
  // |c(t) - (centre.c + centre.d1 (t - tc))| <= rho over the cell (+inf where not smooth)
  double rho = 0.0;
  bool centre_valid = false;
  double tc() const { return 0.5 * (t0 + t1); }
};

struct ParametricCurveCellNode {
  Vec3 lo, hi;                       // the box of c over the node's cells
  std::int32_t child[2] = {-1, -1};  // >= 0: a node; < 0: the cell ~child
};

class ParametricCurveCells {
 public:
  // `breaks`: the samples' parameters (any order); every `per_cell` consecutive gaps make a cell.
  // Built within `budget` (geometry/compile_budget.hpp).
  ParametricCurveCells(const CurveFormulas& formulas, const ParamInterval& domain, std::vector<double> breaks,
                       CompileBudget& budget, int per_cell = 4);
  const std::vector<ParametricCurveCell>& cells() const { return cells_; }
  // nodes()[0] is the root; empty for a single cell
  const std::vector<ParametricCurveCellNode>& nodes() const { return nodes_; }
  std::size_t memory_bytes() const {
    return cells_.capacity() * sizeof(ParametricCurveCell) +
           nodes_.capacity() * sizeof(ParametricCurveCellNode);
  }

 private:
  std::int32_t build(std::size_t begin, std::size_t end, Vec3* lo, Vec3* hi);
  std::vector<ParametricCurveCell> cells_;
  std::vector<ParametricCurveCellNode> nodes_;
};

}  // namespace footpoint
