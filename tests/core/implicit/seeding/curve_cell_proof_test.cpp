// implicit/seeding/curve_cell_proof: what one cell holds, against the closed forms of the circle, two
// circles 1e-3 apart and the lemniscate: one monotone arc with its two ends on the faces, two
// arcs in one cell, empty cells (by an equation's range, or by no crossing at all), and no proof
// at a singular point (T = 0) or where the enclosures are looser than asked.
#include <doctest/doctest.h>

#include <cmath>

#include "implicit/seeding/curve_cell_proof.hpp"
#include "implicit_fixtures.hpp"

using namespace footpoint;
using namespace footpoint::test;

TEST_CASE("prove_cell: one arc of the circle, its ends on the faces") {
  const ImplicitEquations eq = planar_equations("x^2+y^2-1");
  // The top of the circle: T = (2y, -2x) has T_x > 0, the arc is a graph over x, through the
  // left and right faces at x = ±0.1.
  const CellProof top = prove_cell(eq, {{-0.1, 0.95, 0.0}, {0.1, 1.05, 0.0}});
  REQUIRE(top.verdict == CellVerdict::arcs);
  CHECK(top.axis == 0);
  REQUIRE(top.crossings.size() == 2);
  const double y = std::sqrt(1.0 - 0.01);
  CHECK(norm(top.crossings[0].point - Vec3{-0.1, y, 0.0}) <= 1e-15);
  CHECK(norm(top.crossings[1].point - Vec3{0.1, y, 0.0}) <= 1e-15);
  // The enclosures hold ∇f and T at the centre and over the cell.
  CHECK(top.bounds.tangent[0].lo > 0.0);
  CHECK(looseness(top.bounds, 0.2) < 0.5);
}

TEST_CASE("prove_cell: empty cells") {
  const ImplicitEquations eq = planar_equations("x^2+y^2-1");
  CHECK(prove_cell(eq, {{0.1, 0.1, 0.0}, {0.2, 0.2, 0.0}}).verdict == CellVerdict::empty);
  // Both spheres pass through the cell, their circle does not: {|X| = 2} ∩ {z = 1} near (0, 0, 2).
  const CellProof above = prove_cell(circle(), {{-0.05, -0.05, 0.95}, {0.05, 0.05, 1.05}});
  CHECK(above.verdict == CellVerdict::empty);
}

TEST_CASE("prove_cell: two circles 1e-3 apart, two arcs in one cell") {
  const ImplicitEquations eq = planar_equations("(x^2+y^2-1)*((x-2.001)^2+y^2-1)");
  // At height y = 0.11 the circles are at x ≈ 0.99393 and 1.00707: both cross the cell, each
  // monotone in x (T_x = f_y > 0 there), with disjoint x-ranges.
  const CellProof two = prove_cell(eq, {{0.99, 0.1, 0.0}, {1.011, 0.12, 0.0}});
  REQUIRE(two.verdict == CellVerdict::arcs);
  CHECK(two.axis == 0);
  CHECK(two.crossings.size() == 4);
  // Around the gap at y = 0 the tangent turns both ways within the cell: no proof at this size.
  CHECK(prove_cell(eq, {{0.99, -0.01, 0.0}, {1.011, 0.01, 0.0}}).verdict == CellVerdict::unproved);
}

TEST_CASE("prove_cell: no proof at a singular point, nor where looser than asked") {
  const ImplicitEquations lemniscate = planar_equations("(x^2+y^2)^2-2*(x^2-y^2)");
  const CellProof node = prove_cell(lemniscate, {{-0.01, -0.013, 0.0}, {0.012, 0.011, 0.0}});
  CHECK(node.verdict == CellVerdict::unproved);
  CHECK(node.reason == UnprovedReason::tangent_may_vanish);
  const ImplicitEquations eq = planar_equations("x^2+y^2-1");
  const CellProof loose = prove_cell(eq, {{-0.1, 0.95, 0.0}, {0.1, 1.05, 0.0}}, 1e-3);
  CHECK(loose.verdict == CellVerdict::unproved);
  CHECK(loose.reason == UnprovedReason::loose);
  const CellProof kink = prove_cell(planar_equations("abs(x)+abs(y)-1"), {{-0.1, 0.9, 0.0}, {0.1, 1.1, 0.0}});
  CHECK(kink.verdict == CellVerdict::unproved);
  CHECK(kink.reason == UnprovedReason::not_smooth);
}
