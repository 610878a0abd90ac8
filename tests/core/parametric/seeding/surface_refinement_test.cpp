// parametric/seeding/surface_refinement: sub-boxes of a surface's cells with rigorous enclosures,
// halved on demand and published once. Checked against closed forms sampled on a 9 x 9 grid of
// each box:
//  - the torus s = ((2 + cos v/2) cos u, (2 + cos v/2) sin u, sin v/2): s_u, s_v, the second
//    partials and the metric E = (2 + cos v/2)^2, F = 0, G = 1/4 in closed form;
//  - the polynomial s = (u, v, u^2 v - v^3/3) (a sum of monomials): s_u = (1, 0, 2uv),
//    s_v = (0, 1, u^2 - v^2), s_uu = (0, 0, 2v), s_uv = (0, 0, 2u), s_vv = (0, 0, -2v).
// The promises: every enclosure holds the sampled values (s, second partials, metric) and the
// centre's enclosure the exact s, s_u, s_v there; the centred form tightens with the box, and the
// interval jet added (evaluate) only tightens it further; where the ancestor is not smooth (a kink
// crosses it) the half still gets its enclosure; split_u says along which side the box is longer
// on the surface; halves are split at the midpoint; halves() publishes a pair once per slot, shares
// it between threads, counts it, and past max_pairs computes into the caller's scratch.
// The closed forms are evaluated in doubles: containment is checked to 1e-14 of their size.
#include <doctest/doctest.h>

#include <cmath>
#include <functional>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "parametric/geometry/parametric_surface.hpp"
#include "parametric/seeding/surface_refinement.hpp"

using namespace footpoint;

namespace surface_refinement_test {

constexpr double kSlack = 1e-14;

formula::Program program(const std::string& x, const std::string& y, const std::string& z) {
  return formula::Program::compile({{"x", x}, {"y", y}, {"z", z}}, {"u", "v"}, {});
}

formula::Program torus() { return program("(2+0.5*cos(v))*cos(u)", "(2+0.5*cos(v))*sin(u)", "0.5*sin(v)"); }
formula::Program cubic() { return program("u", "v", "u^2*v-v^3/3"); }

SurfaceJet torus_jet(double u, double v) {
  const double w = 2 + 0.5 * std::cos(v), cu = std::cos(u), su = std::sin(u), cv = std::cos(v),
               sv = std::sin(v);
  return {{w * cu, w * su, 0.5 * sv},
          {-w * su, w * cu, 0.0},
          {-0.5 * sv * cu, -0.5 * sv * su, 0.5 * cv},
          {-w * cu, -w * su, 0.0},
          {0.5 * sv * su, -0.5 * sv * cu, 0.0},
          {-0.5 * cv * cu, -0.5 * cv * su, -0.5 * sv}};
}
SurfaceJet cubic_jet(double u, double v) {
  return {{u, v, u * u * v - v * v * v / 3},
          {1, 0, 2 * u * v},
          {0, 1, u * u - v * v},
          {0, 0, 2 * v},
          {0, 0, 2 * u},
          {0, 0, -2 * v}};
}
using Jet = std::function<SurfaceJet(double, double)>;

bool holds(double x, double mid, double rad) {
  return std::abs(x - mid) <= rad + kSlack * (1.0 + std::abs(x));
}
bool holds(const Vec3& x, const Vec3& mid, const Vec3& rad) {
  return holds(x.x, mid.x, rad.x) && holds(x.y, mid.y, rad.y) && holds(x.z, mid.z, rad.z);
}

// The sub-box's enclosures hold the closed form over its box and at its centre.
void check_sub_box(const SubBox& b, const Jet& jet) {
  CAPTURE(b.lo[0]);
  CAPTURE(b.lo[1]);
  const BoxEnclosure<2>& e = b.enclosure;
  REQUIRE(e.bounded);
  REQUIRE(e.smooth);
  for (int i = 0; i <= 8; ++i) {
    for (int j = 0; j <= 8; ++j) {
      const double u = b.lo[0] + (b.hi[0] - b.lo[0]) * i / 8, v = b.lo[1] + (b.hi[1] - b.lo[1]) * j / 8;
      const SurfaceJet s = jet(u, v);
      CHECK(holds(s.s, e.s_mid, e.s_rad));
      CHECK(holds(s.suu, e.d2_mid[0], e.d2_rad[0]));
      CHECK(holds(s.suv, e.d2_mid[1], e.d2_rad[1]));
      CHECK(holds(s.svv, e.d2_mid[2], e.d2_rad[2]));
      const double metric[3] = {dot(s.su, s.su), dot(s.su, s.sv), dot(s.sv, s.sv)};
      for (int k = 0; k < 3; ++k) {
        CHECK(metric[k] >= e.metric_lo[k] - kSlack * (1.0 + std::abs(metric[k])));
        CHECK(metric[k] <= e.metric_hi[k] + kSlack * (1.0 + std::abs(metric[k])));
      }
    }
  }
  REQUIRE(b.centre.valid);
  const SurfaceJet c = jet(0.5 * (b.lo[0] + b.hi[0]), 0.5 * (b.lo[1] + b.hi[1]));
  CHECK(holds(c.s, b.centre.s, b.centre.s_rad));
  CHECK(holds(c.su, b.centre.ds[0], b.centre.ds_rad[0]));
  CHECK(holds(c.sv, b.centre.ds[1], b.centre.ds_rad[1]));
  // longer along u on the surface: |s_u| wu >= |s_v| wv at the centre
  const double wu = b.hi[0] - b.lo[0], wv = b.hi[1] - b.lo[1];
  CHECK(b.split_u == (norm(c.su) * wu >= norm(c.sv) * wv));
}

double largest(const Vec3& r) { return std::max({r.x, r.y, r.z}); }

TEST_CASE(
    "surface_refinement: a sub-box's enclosures hold the torus and the polynomial, tighter than the cell's") {
  struct Case {
    formula::Program program;
    Jet jet;
  };
  for (const Case& k : {Case{torus(), torus_jet}, Case{cubic(), cubic_jet}}) {
    const BoxEnclosure<2> cell = enclose_box<2>(k.program, {0.0, 0.0}, {1.0, 1.0});
    REQUIRE(cell.smooth);
    const SubBox derived(k.program, cell, {0.25, 0.5}, {0.375, 0.625}, false);
    const SubBox evaluated(k.program, cell, {0.25, 0.5}, {0.375, 0.625}, true);
    check_sub_box(derived, k.jet);
    check_sub_box(evaluated, k.jet);
    // the centred form of a box 1/8 the cell's side: s within O(h) of the centre, far tighter than
    // the cell's enclosure; the interval jet intersected in only tightens it
    CHECK(largest(derived.enclosure.s_rad) < 0.25 * largest(cell.s_rad));
    for (int c = 0; c < 3; ++c) CHECK(evaluated.enclosure.s_rad[c] <= derived.enclosure.s_rad[c]);
  }
}

TEST_CASE("surface_refinement: split_u follows the sides' lengths on the surface") {
  // torus: |s_u| = 2 + cos(v)/2 in [1.5, 2.5], |s_v| = 1/2
  const formula::Program p = torus();
  const BoxEnclosure<2> cell = enclose_box<2>(p, {0.0, 0.0}, {1.0, 1.0});
  const SubBox square(p, cell, {0.0, 0.0}, {0.5, 0.5}, false);
  CHECK(square.split_u);  // 2.4 x 0.5 against 0.5 x 0.5
  const SubBox tall(p, cell, {0.0, 0.0}, {0.05, 1.0}, false);
  CHECK_FALSE(tall.split_u);  // 2.4 x 0.05 against 0.5 x 1
  check_sub_box(tall, torus_jet);
}

TEST_CASE("surface_refinement: a pair halves its box at the midpoint, along u or v") {
  const formula::Program p = cubic();
  const BoxEnclosure<2> cell = enclose_box<2>(p, {-1.0, 0.0}, {1.0, 0.5});
  const SubBoxPair along_u(p, cell, {-1.0, 0.0}, {1.0, 0.5}, true, false);
  CHECK(along_u.half[0].lo == Params<2>{-1.0, 0.0});
  CHECK(along_u.half[0].hi == Params<2>{0.0, 0.5});
  CHECK(along_u.half[1].lo == Params<2>{0.0, 0.0});
  CHECK(along_u.half[1].hi == Params<2>{1.0, 0.5});
  const SubBoxPair along_v(p, cell, {-1.0, 0.0}, {1.0, 0.5}, false, true);
  CHECK(along_v.half[0].lo == Params<2>{-1.0, 0.0});
  CHECK(along_v.half[0].hi == Params<2>{1.0, 0.25});
  CHECK(along_v.half[1].lo == Params<2>{-1.0, 0.25});
  CHECK(along_v.half[1].hi == Params<2>{1.0, 0.5});
  for (const SubBoxPair* pair : {&along_u, &along_v})
    for (const SubBox& h : pair->half) check_sub_box(h, cubic_jet);
}

TEST_CASE("surface_refinement: across a kink of the cell the halves off the kink get smooth enclosures") {
  // z = |u - 1/2|: the cell [0, 1]^2 is not smooth, [0, 1/4] x [0, 1] is (z = 1/2 - u there)
  const formula::Program p = program("u", "v", "abs(u-0.5)");
  const BoxEnclosure<2> cell = enclose_box<2>(p, {0.0, 0.0}, {1.0, 1.0});
  REQUIRE_FALSE(cell.smooth);
  const SubBox b(p, cell, {0.0, 0.0}, {0.25, 1.0}, false);
  check_sub_box(b, [](double u, double v) {
    return SurfaceJet{{u, v, 0.5 - u}, {1, 0, -1}, {0, 1, 0}, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
  });
}

TEST_CASE("surface_refinement: halves are published once per slot and counted; past the cap, scratch") {
  const formula::Program p = torus();
  SurfaceRefinement refinement(p, 3, 2);
  CHECK(refinement.reserved_bytes() == 2 * sizeof(SubBoxPair));
  CHECK(refinement.pairs() == 0);
  for (std::size_t i = 0; i < 3; ++i) CHECK(refinement.cell_slot(i).load() == nullptr);
  const BoxEnclosure<2> cell = enclose_box<2>(p, {0.0, 0.0}, {1.0, 1.0});
  std::unique_ptr<SubBoxPair> scratch;

  const SubBoxPair& first =
      refinement.halves(refinement.cell_slot(0), cell, {0.0, 0.0}, {1.0, 1.0}, true, true, scratch);
  CHECK(refinement.cell_slot(0).load() == &first);
  CHECK(refinement.pairs() == 1);
  CHECK(scratch == nullptr);
  CHECK(first.half[0].hi == Params<2>{0.5, 1.0});
  // published: asked again (whatever the split asked), the same pair
  const SubBoxPair& again =
      refinement.halves(refinement.cell_slot(0), cell, {0.0, 0.0}, {1.0, 1.0}, false, true, scratch);
  CHECK(&again == &first);
  CHECK(refinement.pairs() == 1);

  // a half's own halves, published under the half's slot: the second pair
  const SubBox& h = first.half[1];
  const SubBoxPair& deeper = refinement.halves(h.halves, h.enclosure, h.lo, h.hi, h.split_u, false, scratch);
  CHECK(h.halves.load() == &deeper);
  CHECK(refinement.pairs() == 2);
  for (const SubBox& q : deeper.half) check_sub_box(q, torus_jet);

  // the cap reached: computed into scratch, not published, not counted
  const SubBoxPair& spare =
      refinement.halves(refinement.cell_slot(1), cell, {0.0, 0.0}, {1.0, 1.0}, true, true, scratch);
  REQUIRE(scratch != nullptr);
  CHECK(&spare == scratch.get());
  CHECK(refinement.cell_slot(1).load() == nullptr);
  CHECK(refinement.pairs() == 2);
  for (const SubBox& q : spare.half) check_sub_box(q, torus_jet);
}

TEST_CASE("surface_refinement: the halves' enclosure follows the formulas and the box, not the caller") {
  // a cell's halves and other formulas' halves get the interval jet too (evaluate); a sum of
  // monomials' deeper halves only the centred form
  std::unique_ptr<SubBoxPair> scratch;
  for (const bool polynomial : {true, false}) {
    const formula::Program p = polynomial ? cubic() : torus();
    REQUIRE(p.sum_of_monomials() == polynomial);
    const SurfaceRefinement refinement(p, 1, 8);
    const BoxEnclosure<2> cell = enclose_box<2>(p, {0.0, 0.0}, {1.0, 1.0});
    for (const bool of_cell : {true, false}) {
      std::atomic<const SubBoxPair*> slot{nullptr};
      const SubBoxPair& got = refinement.halves(slot, cell, {0.0, 0.0}, {1.0, 1.0}, true, of_cell, scratch);
      const SubBoxPair expected(p, cell, {0.0, 0.0}, {1.0, 1.0}, true, of_cell || !polynomial);
      for (int k = 0; k < 2; ++k)
        for (int c = 0; c < 3; ++c)
          CHECK(got.half[k].enclosure.s_rad[c] == expected.half[k].enclosure.s_rad[c]);
      delete slot.load();  // published into a slot the test owns
    }
  }
}

TEST_CASE("surface_refinement: threads racing on the same slots get one pair each") {
  const formula::Program p = torus();
  constexpr std::size_t kCells = 8;
  const SurfaceRefinement refinement(p, kCells, 64);
  std::vector<BoxEnclosure<2>> cells;
  for (std::size_t i = 0; i < kCells; ++i)
    cells.push_back(
        enclose_box<2>(p, {0.5 * static_cast<double>(i), 0.0}, {0.5 * static_cast<double>(i + 1), 1.0}));
  std::vector<std::vector<const SubBoxPair*>> seen(4, std::vector<const SubBoxPair*>(kCells));
  std::vector<std::thread> threads;
  for (std::size_t t = 0; t < 4; ++t) {
    threads.emplace_back([&, t] {
      std::unique_ptr<SubBoxPair> scratch;
      for (std::size_t i = 0; i < kCells; ++i) {
        const std::size_t c = (i + t) % kCells;
        seen[t][c] = &refinement.halves(refinement.cell_slot(c), cells[c], cells[c].lo, cells[c].hi, true,
                                        true, scratch);
      }
    });
  }
  for (std::thread& t : threads) t.join();
  CHECK(refinement.pairs() == kCells);
  for (std::size_t c = 0; c < kCells; ++c) {
    CHECK(seen[0][c] == refinement.cell_slot(c).load());
    for (std::size_t t = 1; t < 4; ++t) CHECK(seen[t][c] == seen[0][c]);
  }
}

}  // namespace surface_refinement_test
