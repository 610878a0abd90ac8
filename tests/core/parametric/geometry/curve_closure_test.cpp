// parametric/geometry/curve_closure: whether a parametric curve closes, c(tmin) = c(tmax), smoothly
// (equal unit tangents at the ends) or with a corner, against what each curve is in closed form: a
// circle, an ellipse and a trefoil close smoothly, a teardrop with a corner; a helix, a parabola, half
// a circle and a circle 1e-6 short of its turn do not close (the helix's gap |c(4π) - c(0)| is its
// rise 0.2 x 4π). Declared periodic curves are accepted near rounding level and refused otherwise.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "closure_refusal.hpp"
#include "parametric/geometry/curve_closure.hpp"

using namespace footpoint;

namespace {

constexpr double kClosurePi = std::numbers::pi;

CurveFormulas closure_curve(const std::string& x, const std::string& y, const std::string& z = "") {
  std::vector<formula::NamedFormula> f = {{"x", x}, {"y", y}};
  if (!z.empty()) f.push_back({"z", z});
  return CurveFormulas(formula::Program::compile(f, {"t"}, {}));
}

}  // namespace

TEST_CASE("curves: a circle, an ellipse and a trefoil close smoothly; a helix and a parabola do not") {
  const CurveClosure circle = detect_curve_closure(closure_curve("cos(t)", "sin(t)"), {0, 2 * kClosurePi});
  CHECK(circle.closed);
  CHECK(circle.smooth);
  CHECK(circle.gap <= circle.tolerance);
  CHECK(circle.gap_bound <= 1e-14);
  CHECK(detect_curve_closure(closure_curve("3*cos(t)", "2*sin(t)"), {0, 2 * kClosurePi}).smooth);
  const CurveClosure trefoil = detect_curve_closure(
      closure_curve("sin(t)+2*sin(2*t)", "cos(t)-2*cos(2*t)", "-sin(3*t)"), {0, 2 * kClosurePi});
  CHECK(trefoil.closed);
  CHECK(trefoil.smooth);
  CHECK(!detect_curve_closure(closure_curve("cos(t)", "sin(t)", "0.2*t"), {0, 4 * kClosurePi}).closed);
  CHECK(!detect_curve_closure(closure_curve("t", "t^2"), {-1, 2}).closed);
  // Half a circle, and a circle 1e-6 short of closing.
  CHECK(!detect_curve_closure(closure_curve("cos(t)", "sin(t)"), {0, kClosurePi}).closed);
  CHECK(!detect_curve_closure(closure_curve("cos(t)", "sin(t)"), {0, 2 * kClosurePi - 1e-6}).closed);
}

TEST_CASE("curves: a teardrop closes with a corner; declared periodic curves") {
  const CurveClosure teardrop =
      detect_curve_closure(closure_curve("2*sin(t/2)", "sin(t)"), {0, 2 * kClosurePi});
  CHECK(teardrop.closed);
  CHECK(!teardrop.smooth);
  const CurveClosure declared =
      detect_curve_closure(closure_curve("cos(t)", "sin(t)"), {0, 2 * kClosurePi - 1e-7}, true);
  CHECK(declared.closed);
  CHECK(declared.declared);
  const std::string why = test::closure_refusal([&] {
    detect_curve_closure(closure_curve("cos(t)", "sin(t)", "0.2*t"), {0, 4 * kClosurePi}, true);
  });
  CHECK(why.find("t is declared periodic") != std::string::npos);
}

TEST_CASE("curves: the gap is |c(tmax) - c(tmin)|, bounded rigorously where the curve closes") {
  // A helix over two turns: the ends are (1, 0, 0) and (1, 0, 0.8π).
  const CurveClosure helix =
      detect_curve_closure(closure_curve("cos(t)", "sin(t)", "0.2*t"), {0, 4 * kClosurePi});
  CHECK(helix.gap == doctest::Approx(0.8 * kClosurePi).epsilon(1e-14));
  // An open curve has no bound of its gap to prove: it stays infinite.
  CHECK(std::isinf(helix.gap_bound));
  // A circle of radius 1e6 twice round: closed, the tolerance grows with the coordinates (256 ε M
  // with M = 1e6, and more for the parameters' rounding), and the gap stays under it.
  const CurveClosure big =
      detect_curve_closure(closure_curve("1e6*cos(t)", "1e6*sin(t)"), {0, 4 * kClosurePi});
  CHECK(big.closed);
  CHECK(big.smooth);
  CHECK(big.tolerance >= 256 * 0x1p-52 * 1e6);
  CHECK(big.gap <= big.tolerance);
  // The rigorous bound holds the gap evaluated, and is at rounding level too.
  CHECK(big.gap_bound >= big.gap);
  CHECK(big.gap_bound <= big.tolerance);
  // A parabola's ends (-1, 1) and (2, 4): gap 3√2, not closed.
  const CurveClosure parabola = detect_curve_closure(closure_curve("t", "t^2"), {-1, 2});
  CHECK(parabola.gap == doctest::Approx(3 * std::sqrt(2.0)).epsilon(1e-15));
  CHECK_FALSE(parabola.smooth);
}
