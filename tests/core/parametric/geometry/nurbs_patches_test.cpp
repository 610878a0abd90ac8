// parametric/geometry/nurbs_patches: a NURBS cut into Bézier pieces, each piece's formula against
// the closed form the NURBS reproduces exactly (B-splines reproduce polynomials: with control
// points at the Greville abscissae ξ_i and the blossoms of t^2, U_{i+1} U_{i+2} for degree 2, the
// curve is (t, t^2, 1 - t); the rational quadratic circle of [PieglTiller] Ex. 7.2, nine points,
// weights 1, √2/2, lies on the unit circle), at the span's local parameters s = (t - a) / (b - a);
// the control-point hull holds every point of its piece.
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <vector>

#include "parametric/geometry/nurbs_patches.hpp"

namespace nurbs = footpoint::nurbs;

namespace {

constexpr std::size_t kPatchNodes = 100000;

// The program of a piece at its local parameters.
std::array<double, 3> patch_value(const footpoint::formula::Program& program,
                                  std::initializer_list<double> at) {
  std::array<double, 3> out{0, 0, 0};
  const std::vector<double> x(at);
  program.values(x.data(), out.data());
  return out;
}

// Degree 2, knots 0 0 0 1 2 4 4 4: Greville abscissae 0, 0.5, 1.5, 3, 4 and blossoms of t^2
// 0, 0, 2, 8, 16, so that the curve is (t, t^2, 1 - t) on [0, 4].
nurbs::Curve greville_parabola() {
  const std::vector<double> knots{0, 0, 0, 1, 2, 4, 4, 4};
  const std::vector<std::vector<double>> points{
      {0, 0, 1}, {0.5, 0, 0.5}, {1.5, 2, -0.5}, {3, 8, -2}, {4, 16, -3}};
  auto made = nurbs::make_curve(2, knots, points, {}, 100);
  REQUIRE(made.curve.has_value());
  return *made.curve;
}

}  // namespace

TEST_CASE("NURBS pieces: a degree-2 B-spline reproducing (t, t^2, 1 - t), one piece per span") {
  const auto pieces = nurbs::bezier_pieces(greville_parabola(), kPatchNodes);
  REQUIRE(pieces.size() == 3);
  const std::array<std::array<double, 2>, 3> spans{{{0, 1}, {1, 2}, {2, 4}}};
  for (std::size_t k = 0; k < pieces.size(); ++k) {
    const auto& piece = pieces[k];
    CHECK(piece.span.tmin == spans[k][0]);
    CHECK(piece.span.tmax == spans[k][1]);
    CHECK(piece.bezier.size() == 3);
    REQUIRE(piece.program.num_inputs() == 1);
    REQUIRE(piece.program.num_outputs() == 3);
    // Not rational: the piece is a sum of monomials (evaluated and enclosed as one).
    CHECK(piece.program.sum_of_monomials());
    for (int j = 0; j <= 16; ++j) {
      const double s = j / 16.0;
      const double t = spans[k][0] + s * (spans[k][1] - spans[k][0]);
      const auto c = patch_value(piece.program, {s});
      CHECK(c[0] == doctest::Approx(t).epsilon(1e-14).scale(1.0));
      CHECK(c[1] == doctest::Approx(t * t).epsilon(1e-14).scale(1.0));
      CHECK(c[2] == doctest::Approx(1 - t).epsilon(1e-14).scale(1.0));
      CHECK(piece.hull.contains(footpoint::Vec3{c[0], c[1], c[2]}));
    }
  }
  // The hull of the first piece is its Bézier points' box: (0, 0, 1), (0.5, 0, 0.5), (1, 1, 0).
  CHECK(pieces[0].hull.lo.x == doctest::Approx(0.0).scale(1.0));
  CHECK(pieces[0].hull.hi.x == doctest::Approx(1.0));
  CHECK(pieces[0].hull.hi.y == doctest::Approx(1.0));
  CHECK(pieces[0].hull.lo.z == doctest::Approx(0.0).scale(1.0));
  CHECK(pieces[0].hull.hi.z == doctest::Approx(1.0));
}

TEST_CASE("NURBS pieces: the rational circle's four quarter arcs lie on the unit circle") {
  const double w = std::sqrt(0.5);
  const std::vector<double> knots{0, 0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 4};
  const std::vector<std::vector<double>> points{{1, 0},   {1, 1},  {0, 1},  {-1, 1}, {-1, 0},
                                                {-1, -1}, {0, -1}, {1, -1}, {1, 0}};
  const auto made = nurbs::make_curve(2, knots, points, {1, w, 1, w, 1, w, 1, w, 1}, 100);
  REQUIRE(made.curve.has_value());
  const auto pieces = nurbs::bezier_pieces(*made.curve, kPatchNodes);
  REQUIRE(pieces.size() == 4);
  for (std::size_t k = 0; k < 4; ++k) {
    const auto& piece = pieces[k];
    REQUIRE(piece.program.num_outputs() == 2);
    CHECK_FALSE(piece.program.sum_of_monomials());
    // The ends and the middle of quarter k: angles kπ/2, (k + 1/2)π/2 (the weights are symmetric),
    // (k + 1)π/2.
    for (const double s : {0.0, 0.5, 1.0}) {
      const double angle = (static_cast<double>(k) + s) * M_PI / 2;
      const auto c = patch_value(piece.program, {s});
      CHECK(c[0] == doctest::Approx(std::cos(angle)).epsilon(1e-14).scale(1.0));
      CHECK(c[1] == doctest::Approx(std::sin(angle)).epsilon(1e-14).scale(1.0));
    }
    for (int j = 0; j <= 32; ++j) {
      const auto c = patch_value(piece.program, {j / 32.0});
      CHECK(std::hypot(c[0], c[1]) == doctest::Approx(1.0).epsilon(4e-16 * 8));
      CHECK(piece.hull.contains(footpoint::Vec3{c[0], c[1], 0.0}));
      // Quarter k stays in its quadrant.
      const double angle = std::atan2(c[1], c[0]);
      const double turned = std::remainder(angle - (static_cast<double>(k) + 0.5) * M_PI / 2, 2 * M_PI);
      CHECK(std::abs(turned) <= M_PI / 4 + 1e-12);
    }
  }
}

TEST_CASE("NURBS pieces: a surface reproducing (u, v, u^2 v), one piece per pair of spans") {
  // u: degree 2, knots 0 0 0 1 3 3 3 (Greville 0, 0.5, 2, 3; blossoms of u^2: 0, 0, 3, 9).
  // v: degree 1, knots -1 -1 0.5 2 2 (Greville -1, 0.5, 2: the control points themselves).
  const std::array<double, 4> xi{0, 0.5, 2, 3}, square{0, 0, 3, 9};
  const std::array<double, 3> eta{-1, 0.5, 2};
  std::vector<std::vector<std::vector<double>>> net(4);
  for (std::size_t i = 0; i < 4; ++i)
    for (std::size_t j = 0; j < 3; ++j) net[i].push_back({xi[i], eta[j], square[i] * eta[j]});
  const auto made = nurbs::make_surface({2, 1}, {0, 0, 0, 1, 3, 3, 3}, {-1, -1, 0.5, 2, 2}, net, {}, 100);
  REQUIRE(made.surface.has_value());
  const auto pieces = nurbs::bezier_pieces(*made.surface, kPatchNodes);
  REQUIRE(pieces.size() == 4);
  // u-major: [0, 1] x [-1, 0.5], [0, 1] x [0.5, 2], [1, 3] x [-1, 0.5], [1, 3] x [0.5, 2].
  CHECK(pieces[1].span.umax == 1.0);
  CHECK(pieces[1].span.vmin == 0.5);
  CHECK(pieces[2].span.umin == 1.0);
  CHECK(pieces[2].span.vmax == 0.5);
  for (const auto& piece : pieces) {
    CHECK(piece.bezier.size() == 3 * 2);
    REQUIRE(piece.program.num_inputs() == 2);
    REQUIRE(piece.program.num_outputs() == 3);
    for (int a = 0; a <= 8; ++a) {
      for (int b = 0; b <= 8; ++b) {
        const double s = a / 8.0, t = b / 8.0;
        const double u = piece.span.umin + s * (piece.span.umax - piece.span.umin);
        const double v = piece.span.vmin + t * (piece.span.vmax - piece.span.vmin);
        const auto c = patch_value(piece.program, {s, t});
        CHECK(c[0] == doctest::Approx(u).epsilon(1e-14).scale(1.0));
        CHECK(c[1] == doctest::Approx(v).epsilon(1e-14).scale(1.0));
        CHECK(c[2] == doctest::Approx(u * u * v).epsilon(1e-14).scale(1.0));
        CHECK(piece.hull.contains(footpoint::Vec3{c[0], c[1], c[2]}));
      }
    }
  }
}

TEST_CASE("NURBS pieces: a formula past the node budget is refused") {
  CHECK_THROWS_AS(nurbs::bezier_pieces(greville_parabola(), 3), footpoint::formula::FormulaError);
}
