// geometry/krawczyk: Krawczyk's test on small systems whose zeros are known in closed form: a
// unique zero proved and enclosed (with the contraction radius about a good approximation), no zero
// in a far box, two zeros left undecided, and a box a few ulps wide along a coordinate the system
// fixes.
#include <doctest/doctest.h>

#include <cmath>

#include "geometry/krawczyk.hpp"

using namespace footpoint;
using formula::Interval;
namespace iv = formula::interval;

namespace {

// G(x, y) = (x^2 + y^2 - 1, x - y): zeros ±(1/√2, 1/√2); G' = [[2x, 2y], [1, -1]].
IntervalVector<2> circle_line(const Vector<2>& m) {
  const Interval x = iv::point(m[0]), y = iv::point(m[1]);
  return {iv::sub(iv::add(iv::sqr(x), iv::sqr(y)), iv::point(1.0)), iv::sub(x, y)};
}
IntervalMatrix<2> circle_line_jacobian(const IntervalVector<2>& b) {
  return {
      {{iv::mul(iv::point(2.0), b[0]), iv::mul(iv::point(2.0), b[1])}, {iv::point(1.0), iv::point(-1.0)}}};
}
bool encloses(const Interval& a, double v) { return a.lo <= v && v <= a.hi; }

}  // namespace

TEST_CASE("krawczyk: a unique zero is proved and enclosed") {
  const double r = std::sqrt(0.5);
  const IntervalVector<2> box{{{0.6, 0.8}, {0.6, 0.8}}};
  const Vector<2> m{0.7, 0.7};
  const KrawczykResult<2> k = krawczyk<2>(box, m, circle_line(m), circle_line_jacobian(box));
  REQUIRE(k.verdict == KrawczykVerdict::unique_zero);
  CHECK(encloses(k.image[0], r));
  CHECK(encloses(k.image[1], r));
  CHECK(k.contraction < 1.0);
  // About a good approximation the radius bound is a few ulps: the zero is within it.
  const Vector<2> near{r, r};
  const KrawczykResult<2> tight = krawczyk<2>(box, near, circle_line(near), circle_line_jacobian(box));
  REQUIRE(tight.contraction < 1.0);
  CHECK(tight.radius < 1e-15);
  CHECK(std::fabs(near[0] - r) <= tight.radius + 1e-16);
}

TEST_CASE("krawczyk: no zero in a box away from both, two zeros undecided") {
  const IntervalVector<2> far{{{0.1, 0.3}, {0.5, 0.9}}};
  const Vector<2> m{0.2, 0.7};
  CHECK(krawczyk<2>(far, m, circle_line(m), circle_line_jacobian(far)).verdict == KrawczykVerdict::no_zero);
  const IntervalVector<2> both{{{-1.0, 1.0}, {-1.0, 1.0}}};
  const Vector<2> c{0.01, -0.02};
  CHECK(krawczyk<2>(both, c, circle_line(c), circle_line_jacobian(both)).verdict ==
        KrawczykVerdict::undecided);
}

TEST_CASE("krawczyk: a box a few ulps wide along a coordinate the system fixes exactly") {
  // G(x, y) = (x - 0.5, y^2 - 0.25) over 0.5 ± 4 ulps x [0.4, 0.6]: the image is as wide as the
  // outward rounding along x, inside the box.
  const double e = 4.0 * 0x1p-53;
  const IntervalVector<2> box{{{0.5 - e, 0.5 + e}, {0.4, 0.6}}};
  const Vector<2> m{0.5, 0.5};
  const IntervalVector<2> g{iv::point(0.0), iv::sub(iv::sqr(iv::point(0.5)), iv::point(0.25))};
  const IntervalMatrix<2> jac{
      {{iv::point(1.0), iv::point(0.0)}, {iv::point(0.0), iv::mul(iv::point(2.0), box[1])}}};
  const KrawczykResult<2> k = krawczyk<2>(box, m, g, jac);
  CHECK(k.verdict == KrawczykVerdict::unique_zero);
  CHECK(encloses(k.image[1], 0.5));
  CHECK(k.contraction <= 0.21);
}

TEST_CASE("krawczyk: a singular midpoint Jacobian decides nothing") {
  const IntervalVector<1> box{{{-1.0, 1.0}}};
  const IntervalMatrix<1> jac{{{{{0.0, 0.0}}}}};
  const KrawczykResult<1> k = krawczyk<1>(box, {0.0}, {{{-1.0, -1.0}}}, jac);
  CHECK(k.verdict == KrawczykVerdict::undecided);
  CHECK(std::isinf(k.contraction));
}
