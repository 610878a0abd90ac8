// The enclosures of a surface over a sub-box (parametric/geometry/box_enclosure.hpp) that the certificates'
// refinement keeps: the interval enclosure, the one derived from an ancestor's second derivatives,
// and their intersection, against dense sampling of the sub-box. Where the ancestor is not smooth
// (a kink of abs inside it) nothing can be derived: the derived enclosure holds nothing and the
// intersection is the interval enclosure whole.
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <random>

#include "parametric/geometry/box_enclosure.hpp"
#include "parametric/geometry/parametric_surface.hpp"

using namespace footpoint;

namespace {

SurfaceFormulas surface_of(const char* x, const char* y, const char* z) {
  return SurfaceFormulas(formula::Program::compile({{"x", x}, {"y", y}, {"z", z}}, {"u", "v"}, {}));
}

// Every sampled s(u, v) of the box lies in the enclosure (mid ± rad per coordinate).
void check_holds(const SurfaceFormulas& s, const BoxEnclosure<2>& e, const std::array<double, 2>& lo,
                 const std::array<double, 2>& hi) {
  REQUIRE(e.bounded);
  constexpr int kSteps = 64;
  for (int i = 0; i <= kSteps; ++i)
    for (int j = 0; j <= kSteps; ++j) {
      const double u = lo[0] + (hi[0] - lo[0]) * i / kSteps, v = lo[1] + (hi[1] - lo[1]) * j / kSteps;
      const Vec3 x = s.point(u, v);
      for (int k = 0; k < 3; ++k) {
        INFO("u " << u << ", v " << v << ", coordinate " << k << ": " << x[k] << " against " << e.s_mid[k]
                  << " ± " << e.s_rad[k]);
        REQUIRE(std::fabs(x[k] - e.s_mid[k]) <= e.s_rad[k]);
      }
    }
}

BoxEnclosure<2> refined(const SurfaceFormulas& s, const BoxEnclosure<2>& ancestor,
                        const std::array<double, 2>& lo, const std::array<double, 2>& hi) {
  const PointEnclosure<2> centre =
      enclose_point<2>(s.program(), {0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1])});
  return intersect(enclose_box<2>(s.program(), lo, hi), derive_enclosure(ancestor, lo, hi, centre));
}

}  // namespace

TEST_CASE(
    "derive_enclosure: nothing from an ancestor with a kink inside; the refined enclosure holds the "
    "surface") {
  // z = |u^2 + v^2 - 0.5| kinks on the circle of radius sqrt(0.5), which crosses both boxes. The
  // derived enclosure once came back `bounded` with s = 0 ± 0, and the intersection put y and z at
  // 0 over [-0.75, -0.6875] x [-0.125, 0]: a certificate then proved 0.0389 where the surface
  // comes within 0.01498 of (-0.7048, -0.0359, -0.0149), and certified an answer at 0.01510.
  const SurfaceFormulas s = surface_of("u", "v", "abs(u^2+v^2-0.5)");
  const std::array<double, 2> lo{-0.75, -0.25}, hi{-0.6875, 0.0};
  const BoxEnclosure<2> ancestor = enclose_box<2>(s.program(), lo, hi);
  CHECK(ancestor.bounded);
  CHECK(!ancestor.smooth);
  const std::array<double, 2> sub_lo{-0.75, -0.125}, sub_hi{-0.6875, 0.0};
  const PointEnclosure<2> centre = enclose_point<2>(s.program(), {-0.71875, -0.0625});
  CHECK(!derive_enclosure(ancestor, sub_lo, sub_hi, centre).bounded);
  const BoxEnclosure<2> e = refined(s, ancestor, sub_lo, sub_hi);
  CHECK(!e.smooth);
  check_holds(s, e, sub_lo, sub_hi);
}

TEST_CASE(
    "derive_enclosure: the refined enclosures of random sub-boxes hold the surface ([GSA] Ex. 1, a kinked "
    "one)") {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  for (const auto& f : {std::array<const char*, 3>{"u+v", "sin(u)+2*cos(v)", "sin(u+v)"},
                        std::array<const char*, 3>{"u", "v", "abs(u^2+v^2-0.5)"}}) {
    CAPTURE(f[2]);
    const SurfaceFormulas s = surface_of(f[0], f[1], f[2]);
    for (int n = 0; n < 40; ++n) {
      const double w = 0.5 * u01(rng);
      const std::array<double, 2> lo{-1.0 + 1.5 * u01(rng), -1.0 + 1.5 * u01(rng)};
      const std::array<double, 2> hi{lo[0] + w, lo[1] + w};
      const BoxEnclosure<2> ancestor = enclose_box<2>(s.program(), lo, hi);
      // a quarter of the ancestor, at a random corner
      const int cu = static_cast<int>(rng() % 2), cv = static_cast<int>(rng() % 2);
      const std::array<double, 2> sub_lo{lo[0] + 0.5 * w * cu, lo[1] + 0.5 * w * cv};
      const std::array<double, 2> sub_hi{sub_lo[0] + 0.5 * w, sub_lo[1] + 0.5 * w};
      check_holds(s, refined(s, ancestor, sub_lo, sub_hi), sub_lo, sub_hi);
    }
  }
}
