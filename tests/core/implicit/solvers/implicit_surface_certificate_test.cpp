// The certificate of implicit surfaces against the torus' closed-form distance
// (|hypot(hypot(x, y) - R, z) - r|, the whole torus inside its box): no lower bound exceeds the
// true distance, for the nearest foot and for a foot that is not the nearest, whose certificate
// must then find the nearer part of the surface (a piece of a leaf that the subdivision dropped,
// or bounded with another leaf's enclosures, would show). Each leaf's enclosures, kept after
// first use (implicit/seeding/implicit_surface_cells.hpp, LeafEnclosureCache), are those of a
// direct evaluation whichever threads fill them, and certificates from a cold and a warm cache
// agree.
#include <doctest/doctest.h>

#include <cmath>
#include <random>
#include <thread>
#include <vector>

#include "compiled/implicit_surface_geometry.hpp"
#include "implicit/solvers/implicit_surface_certificate.hpp"

using namespace footpoint;

namespace {

constexpr const char* kTorus = "(x^2+y^2+z^2+3.75)^2-16*(x^2+y^2)";  // R = 2, r = 0.5

std::shared_ptr<const CompiledGeometry> torus() {
  GeometryDefinition def;
  def.type = GeometryType::implicit_surface;
  def.formulas = {{"equation", kTorus}};
  def.domain = {{"x", {-3, 3}}, {"y", {-3, 3}}, {"z", {-1, 1}}};
  return compile_geometry(def);
}

double torus_distance(Vec3 p) { return std::fabs(std::hypot(std::hypot(p.x, p.y) - 2.0, p.z) - 0.5); }

// The point of the torus on p's meridian at angle theta about the core circle.
Vec3 torus_point(Vec3 p, double theta) {
  const double phi = std::atan2(p.y, p.x), radial = 2.0 + 0.5 * std::cos(theta);
  return {radial * std::cos(phi), radial * std::sin(phi), 0.5 * std::sin(theta)};
}

bool same(const Interval& a, const Interval& b) { return a.lo == b.lo && a.hi == b.hi; }

bool same(const LeafEnclosures& a, const LeafEnclosures& b) {
  bool equal = same(a.over.f, b.over.f) && same(a.centre_value, b.centre_value) &&
               same(a.centre_f, b.centre_f) && a.over.lipschitz == b.over.lipschitz &&
               a.over.smooth == b.over.smooth;
  for (int i = 0; i < 3; ++i) {
    equal = equal && same(a.over.grad[i], b.over.grad[i]) && same(a.centre_grad[i], b.centre_grad[i]);
    for (int j = 0; j < 3; ++j) equal = equal && same(a.over.hess[i][j], b.over.hess[i][j]);
  }
  return equal;
}

}  // namespace

TEST_CASE("implicit surface certificate: each leaf's enclosures kept once, from several threads") {
  const auto g = torus();
  const auto& s = dynamic_cast<const ImplicitSurface&>(*g);
  const ImplicitSurfaceCells& cells = s.cells();
  const ImplicitSurfaceEquation& equation = s.equation();
  std::vector<const ImplicitSurfaceCell*> leaves;
  for (const ImplicitSurfaceCell& c : cells.cells)
    if (c.first_child < 0) leaves.push_back(&c);
  REQUIRE(leaves.size() == cells.leaves);
  // Four threads fill the cache at once, each in its own order; every answer is the direct one.
  std::vector<int> mismatches(4, 0);
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t)
    threads.emplace_back([&, t] {
      for (std::size_t k = 0; k < leaves.size(); ++k) {
        const ImplicitSurfaceCell& c = *leaves[t % 2 == 0 ? k : leaves.size() - 1 - k];
        const Vec3 m = c.box.center();
        const ImplicitSurfaceIntervalJet at = equation.interval_gradient({m, m});
        const LeafEnclosures direct{equation.interval_jet(c.box), equation.value_enclosure({m, m}), at.f,
                                    at.grad};
        if (!same(cells.leaf_enclosures.get(equation, c.leaf, c.box), direct))
          ++mismatches[static_cast<std::size_t>(t)];
      }
    });
  for (std::thread& t : threads) t.join();
  for (const int m : mismatches) CHECK(m == 0);
  // The leaves' indices are distinct and dense.
  std::vector<int> seen(cells.leaves, 0);
  for (const ImplicitSurfaceCell* c : leaves) {
    REQUIRE(c->leaf >= 0);
    REQUIRE(static_cast<std::size_t>(c->leaf) < cells.leaves);
    ++seen[static_cast<std::size_t>(c->leaf)];
  }
  for (const int n : seen) CHECK(n == 1);
}

TEST_CASE(
    "implicit surface certificate: no lower bound above the torus' distance, for any foot, cold or warm") {
  const auto g = torus();
  const auto& s = dynamic_cast<const ImplicitSurface&>(*g);
  std::mt19937 rng(29);
  std::uniform_real_distribution<double> xy(-3.0, 3.0), z(-1.0, 1.0), angle(0.0, 6.283185307179586);
  int checked = 0;
  for (int i = 0; i < 70; ++i) {
    const Vec3 p{xy(rng), xy(rng), z(rng)};
    const double reference = torus_distance(p);
    const double q[3] = {p.x, p.y, p.z};
    Options o;
    o.certify = false;
    const auto r = g->project(q, "auto", o);
    REQUIRE(r);
    const Vec3 foot{r->foot[0], r->foot[1], r->foot[2]};
    CAPTURE(i);
    CHECK(std::fabs(r->distance - reference) <= 1e-12 * (1.0 + reference));
    // The nearest foot: certified, the bound at most the true distance; the same from the cache
    // as the first certificate left it.
    const auto nearest =
        surface_implicit::certify_surface_answer(s.equation(), s.cells(), p, foot, r->distance);
    const auto again =
        surface_implicit::certify_surface_answer(s.equation(), s.cells(), p, foot, r->distance);
    CHECK(nearest.certificate.certified);
    CHECK(nearest.certificate.lower_bound <= reference * (1.0 + 1e-15) + 1e-300);
    CHECK(again.certificate.lower_bound == nearest.certificate.lower_bound);
    CHECK(again.certificate.boxes == nearest.certificate.boxes);
    // A point of the torus that is not the nearest (another angle on p's meridian, farther than the
    // true distance by more than the gap): the bound stays at most the true distance, so that
    // answer is not certified.
    const Vec3 other = torus_point(p, angle(rng));
    const double farther = norm(p - other);
    if (farther <= reference * (1.0 + 1e-6) + 1e-9) continue;
    ++checked;
    const auto wrong = surface_implicit::certify_surface_answer(s.equation(), s.cells(), p, other, farther);
    CHECK(wrong.certificate.lower_bound <= reference * (1.0 + 1e-15) + 1e-300);
    CHECK_FALSE(wrong.certificate.certified);
  }
  CHECK(checked >= 40);
}
