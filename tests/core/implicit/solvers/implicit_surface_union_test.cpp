// implicit/solvers/implicit_surface_union: `auto` on a union of factor surfaces, each given as its
// own piece (an equation and its cells), against the closed form of a union of spheres: the
// distance to a sphere of centre c and radius R is ||p - c| - R|, its foot c + R (p - c) / |p - c|,
// and the union's distance is the least of the pieces' (its foot that piece's foot):
//  - random points: the distance, the foot, certified with a lower bound at most the distance;
//  - a point equidistant from two spheres of different radii (found by bisection along a line):
//    two tied feet; a point whose feet on two touching spheres coincide: one foot, a singular
//    point of the product;
//  - certify_union_answer: certified at the nearest foot, not at the other sphere's foot, the
//    bound at most the union's distance either way;
//  - one piece is that piece's `auto`; max_distance applies to the union; all_minima lists each
//    sphere's one local minimum, nearest first.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "implicit/solvers/implicit_surface_auto.hpp"
#include "implicit/solvers/implicit_surface_union.hpp"
#include "implicit_surface_truths.hpp"

using namespace footpoint;
using namespace footpoint::surface_implicit;

namespace implicit_surface_union_test {

struct Sphere {
  Vec3 c;
  double r;
  std::string equation() const {
    char f[200];
    std::snprintf(f, sizeof f, "(x-(%.17g))^2+(y-(%.17g))^2+(z-(%.17g))^2-%.17g", c.x, c.y, c.z, r * r);
    return f;
  }
  double distance(Vec3 p) const { return std::fabs(norm(p - c) - r); }
  Vec3 foot(Vec3 p) const { return c + (r / norm(p - c)) * (p - c); }
};

std::vector<SurfacePiece> pieces_of(const std::vector<Sphere>& spheres, const Box3& box) {
  std::vector<SurfacePiece> pieces;
  for (const Sphere& s : spheres) {
    ImplicitSurfaceEquation f = test::surface_equation(s.equation());
    ImplicitSurfaceCells cells = test::surface_cells(f, box);
    pieces.push_back({std::move(f), std::move(cells)});
  }
  return pieces;
}

Vec3 foot_of(const ProjectionResult& r) { return {r.foot[0], r.foot[1], r.foot[2]}; }

// Two disjoint spheres of different radii.
const Sphere kA{{1.5, 0.0, 0.0}, 1.0}, kB{{-1.0, 0.5, 0.0}, 0.7};
const Box3 kBox{{-3, -3, -3}, {3, 3, 3}};

TEST_CASE("implicit surface union: the nearest of two spheres, certified") {
  const std::vector<SurfacePiece> pieces = pieces_of({kA, kB}, kBox);
  std::mt19937 rng(53);
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  for (int i = 0; i < 30; ++i) {
    const Vec3 p{u(rng), u(rng), u(rng)};
    const bool a = kA.distance(p) < kB.distance(p);
    const double d = a ? kA.distance(p) : kB.distance(p);
    const Vec3 foot = a ? kA.foot(p) : kB.foot(p);
    CAPTURE(i);
    const ProjectionResult r = implicit_surface_union_auto(pieces, p, {});
    CHECK(r.summary.status == Status::converged);
    CHECK(std::fabs(r.distance - d) <= 1e-13);
    CHECK(norm(foot_of(r) - foot) <= 1e-12);
    CHECK(r.summary.certificate.certified);
    CHECK(r.summary.certificate.lower_bound <= d * (1.0 + 1e-15));
    CHECK(r.summary.multiplicity.kind == Multiplicity::unique);
    CHECK(r.summary.starts >= 2);  // both pieces searched
  }
}

TEST_CASE("implicit surface union: a tie across pieces, and one foot on two pieces") {
  // p = (t, 0.2, 0.1) with |p - c_A| - 1 = |p - c_B| - 0.7 (p outside both): the difference of
  // the distances changes sign once on [-0.2, 0.6] (between t = 0 and 0.2, where p nears A and
  // leaves B); bisection to the last bit.
  const std::vector<SurfacePiece> pieces = pieces_of({kA, kB}, kBox);
  auto gap = [](double t) {
    const Vec3 p{t, 0.2, 0.1};
    return kA.distance(p) - kB.distance(p);
  };
  double lo = -0.2, hi = 0.6;  // gap(lo) > 0 > gap(hi)
  REQUIRE(gap(lo) > 0.0);
  REQUIRE(gap(hi) < 0.0);
  for (int n = 0; n < 200; ++n) {
    const double mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi) break;
    (gap(mid) > 0.0 ? lo : hi) = mid;
  }
  const Vec3 p{lo, 0.2, 0.1};
  const ProjectionResult tie = implicit_surface_union_auto(pieces, p, {});
  CHECK(std::fabs(tie.distance - kA.distance(p)) <= 1e-14);
  CHECK(tie.summary.multiplicity.kind == Multiplicity::tied);
  REQUIRE(tie.summary.multiplicity.feet.size() == 2);
  for (const Vec3 foot : {kA.foot(p), kB.foot(p)}) {
    double nearest = 1e300;
    for (const auto& f : tie.summary.multiplicity.feet)
      nearest = std::min(nearest, norm(Vec3{f[0], f[1], f[2]} - foot));
    CHECK(nearest <= 1e-12);
  }
  // Spheres of radii 1 and 2 about (1, 0, 0) and (-2, 0, 0) touch at the origin; from (-0.5, 0, 0)
  // both feet are the origin, at 0.5: one foot, where the product's gradient vanishes.
  const std::vector<SurfacePiece> touching =
      pieces_of({{{1, 0, 0}, 1.0}, {{-2, 0, 0}, 2.0}}, {{-4, -3, -3}, {3, 3, 3}});
  const ProjectionResult both = implicit_surface_union_auto(touching, {-0.5, 0.0, 0.0}, {});
  CHECK(std::fabs(both.distance - 0.5) <= 1e-15);
  CHECK(norm(foot_of(both)) <= 1e-15);
  CHECK(both.summary.location == Location::singular_point);
  CHECK(both.summary.multiplicity.kind == Multiplicity::unique);
}

TEST_CASE("implicit surface union: certify_union_answer at the nearest foot and at another") {
  const std::vector<SurfacePiece> pieces = pieces_of({kA, kB}, kBox);
  for (const Vec3 p : {Vec3{0.2, -1.0, 0.5}, Vec3{-2.5, 1.5, -0.4}, Vec3{1.0, 0.3, 0.2}}) {
    CAPTURE(p.x);
    const double da = kA.distance(p), db = kB.distance(p), d = std::min(da, db);
    const Certificate nearest = certify_union_answer(pieces, p, da < db ? kA.foot(p) : kB.foot(p), d);
    CHECK(nearest.computed);
    CHECK(nearest.certified);
    CHECK(nearest.lower_bound <= d * (1.0 + 1e-15));
    // The other sphere's foot is farther than the union by more than the gap: refuted.
    const Certificate other =
        certify_union_answer(pieces, p, da < db ? kB.foot(p) : kA.foot(p), std::max(da, db));
    CHECK(other.computed);
    CHECK(!other.certified);
    CHECK(other.lower_bound <= d * (1.0 + 1e-15));
  }
}

TEST_CASE("implicit surface union: one piece, max_distance and all_minima") {
  // One piece is that piece's own `auto`.
  const std::vector<SurfacePiece> one = pieces_of({kA}, kBox);
  const Vec3 p{-0.3, 0.8, 0.4};
  const ProjectionResult u = implicit_surface_union_auto(one, p, {});
  const ProjectionResult a = implicit_surface_auto(one[0].equation, one[0].cells, p, {});
  CHECK(u.distance == a.distance);
  CHECK(u.foot == a.foot);
  CHECK(std::fabs(u.distance - kA.distance(p)) <= 1e-14);
  // max_distance between the two spheres' distances: the nearer answers; below both: withheld.
  const std::vector<SurfacePiece> pieces = pieces_of({kA, kB}, kBox);
  const double da = kA.distance(p), db = kB.distance(p);
  REQUIRE(db < da);
  Options between;
  between.max_distance = 0.5 * (da + db);
  const ProjectionResult in = implicit_surface_union_auto(pieces, p, between);
  CHECK(in.summary.status == Status::converged);
  CHECK(std::fabs(in.distance - db) <= 1e-14);
  Options below;
  below.max_distance = 0.5 * db;
  const ProjectionResult out = implicit_surface_union_auto(pieces, p, below);
  CHECK(out.summary.status == Status::beyond_max_distance);
  CHECK(std::isnan(out.distance));
  // Each sphere has one local minimum of the distance (its far point is a maximum): two, nearest
  // first.
  Options all;
  all.all_minima = true;
  const ProjectionResult m = implicit_surface_union_auto(pieces, p, all);
  REQUIRE(m.minima.size() == 2);
  CHECK(std::fabs(m.minima[0].distance - db) <= 1e-14);
  CHECK(std::fabs(m.minima[1].distance - da) <= 1e-14);
  CHECK(norm(Vec3{m.minima[1].foot[0], m.minima[1].foot[1], m.minima[1].foot[2]} - kA.foot(p)) <= 1e-12);
}

}  // namespace implicit_surface_union_test
