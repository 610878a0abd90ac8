// parametric/geometry/surface_closure: seams and poles of surfaces. The references are what each shape is in
// closed form: a torus closes both ways, a sphere's longitude closes and its latitude ends in two poles, a
// cylinder closes one way with two boundary circles, a cone's apex is a pole, a Möbius band closes with its
// width reversed, a teardrop's profile closes with a crease; a plane and the papers' surfaces do not close,
// and edges 1e-6 apart, or apart only between uniform samples, are no seam. Declared periodic directions are
// accepted near rounding level and refused when the edges visibly differ.
#include <doctest/doctest.h>

#include <numbers>
#include <string>

#include "closure_refusal.hpp"
#include "parametric/geometry/surface_closure.hpp"

using namespace footpoint;

namespace {

constexpr double kPi = std::numbers::pi;

SurfaceFormulas surface(const std::string& x, const std::string& y, const std::string& z) {
  return SurfaceFormulas(formula::Program::compile({{"x", x}, {"y", y}, {"z", z}}, {"u", "v"}, {}));
}

bool no_pole(const SurfaceClosure& c) {
  for (const SurfacePole& p : c.poles)
    if (p.collapsed) return false;
  return true;
}

const ParamBox kFullTurns{0, 2 * kPi, 0, 2 * kPi};

}  // namespace

TEST_CASE("a torus closes smoothly both ways, without poles") {
  const SurfaceFormulas torus = surface("(2+0.5*cos(v))*cos(u)", "(2+0.5*cos(v))*sin(u)", "0.5*sin(v)");
  const SurfaceClosure c = detect_surface_closure(torus, kFullTurns);
  for (const SurfaceSeam& seam : c.seams) {
    CHECK(seam.periodic());
    CHECK(seam.smooth);
    CHECK(!seam.declared);
    CHECK(seam.max_gap <= c.tolerance);
    // Rigorous and above what the samples saw; not at rounding level (surface_closure.hpp).
    CHECK(seam.gap_bound >= seam.max_gap);
    CHECK(seam.gap_bound <= 5e-3);  // 3e-4 of the torus's size, 7.1
  }
  CHECK(no_pole(c));
  // 256 ulps of the magnitudes: ~1e-13 for a torus of size ~5.
  CHECK(c.tolerance > 1e-14);
  CHECK(c.tolerance < 1e-11);
}

TEST_CASE("a sphere: the longitude closes, the latitude ends in two poles, proven at rounding level") {
  SUBCASE("u longitude, v latitude (tests/data/surface_sphere.json)") {
    const SurfaceFormulas sphere = surface("cos(u)*cos(v)", "sin(u)*cos(v)", "sin(v)");
    const SurfaceClosure c = detect_surface_closure(sphere, {0, 2 * kPi, -kPi / 2, kPi / 2});
    CHECK(c.periodic(0));
    CHECK(c.seams[0].smooth);
    CHECK(!c.seams[1].closed);
    CHECK(!c.pole(BoxEdge::umin));
    CHECK(!c.pole(BoxEdge::umax));
    REQUIRE(c.pole(BoxEdge::vmin));
    REQUIRE(c.pole(BoxEdge::vmax));
    CHECK(norm(c.poles[2].point - Vec3{0, 0, -1}) <= 1e-15);
    CHECK(norm(c.poles[3].point - Vec3{0, 0, 1}) <= 1e-15);
    CHECK(c.poles[2].radius_bound <= 1e-14);
    CHECK(c.poles[3].radius_bound <= 1e-14);
  }
  SUBCASE("u polar angle over [0, pi], v azimuth") {
    const SurfaceFormulas sphere = surface("2*sin(u)*cos(v)", "2*sin(u)*sin(v)", "2*cos(u)");
    const SurfaceClosure c = detect_surface_closure(sphere, {0, kPi, 0, 2 * kPi});
    CHECK(!c.seams[0].closed);
    CHECK(c.periodic(1));
    CHECK(c.pole(BoxEdge::umin));
    CHECK(c.pole(BoxEdge::umax));
    CHECK(!c.pole(BoxEdge::vmin));
    CHECK(norm(c.poles[0].point - Vec3{0, 0, 2}) <= 1e-15);
    CHECK(c.poles[1].radius_bound <= 1e-14);
  }
}

TEST_CASE("a cylinder closes one way and keeps two boundary circles") {
  const SurfaceFormulas cylinder = surface("cos(u)", "sin(u)", "v");
  const SurfaceClosure c = detect_surface_closure(cylinder, {0, 2 * kPi, -1, 1});
  CHECK(c.periodic(0));
  CHECK(c.seams[0].smooth);
  CHECK(!c.seams[1].closed);
  CHECK(no_pole(c));
}

TEST_CASE("a cone's apex is a pole, its rim is not") {
  const SurfaceFormulas cone = surface("v*cos(u)", "v*sin(u)", "v");
  const SurfaceClosure c = detect_surface_closure(cone, {0, 2 * kPi, 0, 1});
  CHECK(c.periodic(0));
  REQUIRE(c.pole(BoxEdge::vmin));
  CHECK(norm(c.poles[2].point) == 0.0);
  CHECK(c.poles[2].radius_bound == 0.0);  // 0 x [-1, 1] is exactly 0
  CHECK(!c.pole(BoxEdge::vmax));
  CHECK(!c.seams[1].closed);
}

TEST_CASE("a Möbius band closes with its width reversed: a seam, not a period") {
  const SurfaceFormulas moebius = surface("(1+v*cos(u/2))*cos(u)", "(1+v*cos(u/2))*sin(u)", "v*sin(u/2)");
  const ParamBox box{0, 2 * kPi, -0.5, 0.5};
  const SurfaceClosure c = detect_surface_closure(moebius, box);
  CHECK(c.seams[0].closed);
  CHECK(c.seams[0].reversed);
  CHECK(!c.periodic(0));
  CHECK(c.seams[0].smooth);  // the band continues smoothly across, with its normal turned around
  CHECK(c.seams[0].gap_bound <= 1e-2);
  CHECK(!c.seams[1].closed);
  CHECK(no_pole(c));
  // Declaring u periodic claims s(u + 2 pi, v) = s(u, v): refused, saying what it is instead.
  const std::string why = test::closure_refusal([&] { detect_surface_closure(moebius, box, {true, false}); });
  CHECK(why.find("reversed") != std::string::npos);
}

TEST_CASE("positions that meet with different tangent planes: a seam with a crease") {
  // A teardrop profile (2 sin(u/2), sin u) swept along z: at u = 0 the tangent is (1, 1), at
  // u = 2 pi it is (-1, 1).
  const SurfaceFormulas teardrop = surface("2*sin(u/2)", "sin(u)", "v");
  const SurfaceClosure c = detect_surface_closure(teardrop, {0, 2 * kPi, 0, 1});
  CHECK(c.periodic(0));
  CHECK(!c.seams[0].smooth);
}

TEST_CASE("a plane and the papers' surfaces do not close") {
  struct Case {
    const char *x, *y, *z;
    ParamBox box;
  };
  const Case cases[] = {
      {"1+2*u+v", "u-v", "3*u+0.5*v", {0, 1, 0, 1}},
      {"u+v", "sin(u)+2*cos(v)", "sin(u+v)", {-25, 25, -25, 25}},  // [GSA] Example 1
      {"u^4*v^3+u*v+u", "u^3+v^3", "u+v", {-5, 5, -5, 5}},         // [GSA] Example 2
      {"u+2*v", "cos(u+v)", "sin(u+v)", {-2, 2, -2, 2}},           // [Hybrid] Example 1
      {"u", "v", "cos(u+v)", {0, 2, 0, 2}},                        // [Hybrid] C3
      {"u", "v", "sqrt(1-u^2-v^2)", {-1, 1, -1, 1}},               // undefined outside the disc
  };
  for (const Case& k : cases) {
    CAPTURE(k.x);
    const SurfaceClosure c = detect_surface_closure(surface(k.x, k.y, k.z), k.box);
    CHECK(!c.seams[0].closed);
    CHECK(!c.seams[1].closed);
    CHECK(no_pole(c));
  }
}

TEST_CASE("edges that nearly coincide are no seam") {
  SUBCASE("1e-6 apart everywhere") {
    const SurfaceFormulas near = surface("cos(u)+1e-6*u/(2*_pi)", "sin(u)", "v");
    const SurfaceClosure c = detect_surface_closure(near, {0, 2 * kPi, 0, 1});
    CHECK(!c.seams[0].closed);
    // Declared, a gap of 1e-6 of the size (~2.4 here) is accepted: the user says it is one curve.
    const SurfaceClosure declared = detect_surface_closure(near, {0, 2 * kPi, 0, 1}, {true, false});
    CHECK(declared.periodic(0));
    CHECK(declared.seams[0].declared);
    CHECK(declared.seams[0].max_gap == doctest::Approx(1e-6).epsilon(1e-6));
  }
  SUBCASE("apart only between uniform samples: 1e-3 sin(32 v) vanishes at v = 2 pi k / 32") {
    const SurfaceFormulas aliased = surface("cos(u)+1e-3*sin(32*v)*u/(2*_pi)", "sin(u)", "v");
    const SurfaceClosure c = detect_surface_closure(aliased, {0, 2 * kPi, 0, 2 * kPi});
    CHECK(!c.seams[0].closed);
  }
}

TEST_CASE(
    "declared periodic: accepted where the edges coincide, refused with where and how far they do not") {
  const SurfaceFormulas torus = surface("(2+0.5*cos(v))*cos(u)", "(2+0.5*cos(v))*sin(u)", "0.5*sin(v)");
  const SurfaceClosure c = detect_surface_closure(torus, kFullTurns, {true, true});
  CHECK(c.seams[0].declared);
  CHECK(c.seams[1].declared);
  CHECK(c.periodic(0));
  CHECK(c.periodic(1));

  const SurfaceFormulas plane = surface("1+2*u+v", "u-v", "3*u+0.5*v");
  const std::string u = test::closure_refusal([&] {
    detect_surface_closure(plane, {0, 1, 0, 1}, {true, false});
  });
  CHECK(u.find("u is declared periodic") != std::string::npos);
  CHECK(u.find("apart at v = ") != std::string::npos);
  const std::string v = test::closure_refusal([&] {
    detect_surface_closure(plane, {0, 1, 0, 1}, {false, true});
  });
  CHECK(v.find("v = vmin and v = vmax") != std::string::npos);
  // A domain typed with too few digits of 2 pi: the edges are ~2e-5 apart, 3 x the limit.
  test::closure_refusal([&] { detect_surface_closure(torus, {0, 6.2832, 0, 2 * kPi}, {true, false}); });
}
