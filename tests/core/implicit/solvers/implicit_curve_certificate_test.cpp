// The certificates of `auto` on implicit curves (implicit/solvers/implicit_curve_certificate) against
// a dense brute force over a parametrisation of each reference curve (the classes of issue 16:
// tiny ovals and loops in 2-D and 3-D at a grid corner, on a cell's edge and at a cell's centre,
// a tacnode, a cusp, nodes, circles 1e-3 apart, nearly tangent spheres; and Viviani's curve, an
// ellipse and [Curve] Example 1): on 360 random points each, in the box and near the curve,
//  - the lower bound L is at most the brute-force minimum, which is at most the answer d (to the
//    rounding of the brute force), and a certified answer meets the gap;
//  - at least 99 % of the answers whose foot point is away from the singular points are certified;
//  - a farther local minimum swapped in for the answer is not certified (the certificate does not
//    take the answer's word for it), and its L still holds;
//  - options.certify = false leaves the certificate out; the papers' methods get one when asked.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdlib>
#include <functional>
#include <iomanip>
#include <limits>
#include <map>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "compiled/implicit_curve_geometry.hpp"
#include "implicit/solvers/implicit_curve_certificate.hpp"
#include "sweep_length.hpp"

using namespace footpoint;
using footpoint::test::sweep_length;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// A piece of the curve: t -> c(t) on [t0, t1] (the part inside the box counts).
struct Piece {
  std::function<Vec3(double)> at;
  double t0, t1;
};

struct Reference {
  std::string id;
  std::vector<std::string> equations;  // one (planar) or two
  Box3 box;
  std::vector<Piece> pieces;
};

Piece circle(Vec3 c, double r, Vec3 u = {1, 0, 0}, Vec3 v = {0, 1, 0}) {
  return {[=](double t) { return c + r * std::cos(t) * u + r * std::sin(t) * v; }, 0.0,
          2.0 * std::numbers::pi};
}

std::vector<Reference> references() {
  std::vector<Reference> r;
  const Box3 square{{-2, -2, 0}, {2, 2, 0}};
  const Vec3 corner{1.5246, 1.221575, 0}, edge{1.5246, 1.2538375, 0}, middle{1.5565375, 1.2538375, 0};
  auto oval = [&](const char* id, Vec3 c) {
    char f[160];
    std::snprintf(f, sizeof f, "(x^2+y^2-1)*((x-%.17g)^2+(y-%.17g)^2-0.0016)", c.x, c.y);
    r.push_back({id, {f}, square, {circle({0, 0, 0}, 1.0), circle(c, 0.04)}});
  };
  oval("tiny_oval_corner", corner);
  oval("tiny_oval_edge", edge);
  oval("tiny_oval_cell", middle);
  const double a = 0.04;
  const Piece nodal{[=](double t) { return Vec3{t * t - a, t * (t * t - a), 0.0}; }, -1.1, 1.1};
  r.push_back({"nodal_loop", {"y^2-x^2*(x+0.04)"}, {{-1, -1, 0}, {1, 1, 0}}, {nodal}});
  r.push_back({"tacnode_quartic",
               {"y^2-x^4"},
               {{-1, -1.2, 0}, {1.1, 1, 0}},
               {{[](double t) {
                   return Vec3{t, t * t, 0.0};
                 },
                 -1.0, 1.1},
                {[](double t) {
                   return Vec3{t, -t * t, 0.0};
                 },
                 -1.0, 1.1}}});
  r.push_back({"cusp_offset",
               {"(y-0.13)^2-(x+0.07)^3"},
               {{-1, -1, 0}, {1, 1, 0}},
               {{[](double t) {
                   return Vec3{t * t - 0.07, t * t * t + 0.13, 0.0};
                 },
                 -1.1, 1.1}}});
  r.push_back({"circles_gap",
               {"(x^2+y^2-1)*((x-2.001)^2+y^2-1)"},
               {{-2, -2, 0}, {4, 2, 0}},
               {circle({0, 0, 0}, 1.0), circle({2.001, 0, 0}, 1.0)}});
  r.push_back({"lemniscate",
               {"(x^2+y^2)^2-2*(x^2-y^2)"},
               {{-2, -2, 0}, {2, 2, 0}},
               {{[](double t) {
                   const double s = std::sin(t), c = std::cos(t), q = 1.0 + s * s;
                   return Vec3{std::sqrt(2.0) * c / q, std::sqrt(2.0) * s * c / q, 0.0};
                 },
                 0.0, 2.0 * std::numbers::pi}}});
  r.push_back({"ellipse",
               {"x^2/9+y^2/4-1"},
               {{-4, -4, 0}, {4, 4, 0}},
               {circle({0, 0, 0}, 1.0, {3, 0, 0}, {0, 2, 0})}});
  // Spatial: a tiny circle beside a big one (in the plane z = z0, centred on a vertical grid edge).
  const double z0 = 0.705120625;
  char f1[160];
  std::snprintf(f1, sizeof f1, "(x^2+y^2+z^2-4)*((x-1.13715)^2+(y-0.8644875)^2+(z-%.17g)^2-0.0036)", z0);
  char f2[64];
  std::snprintf(f2, sizeof f2, "z-%.17g", z0);
  r.push_back({"tiny_oval_3d",
               {f1, f2},
               {{-3, -3, -3}, {3, 3, 3}},
               {circle({0, 0, z0}, std::sqrt(4.0 - z0 * z0)), circle({1.13715, 0.8644875, z0}, 0.06)}});
  r.push_back({"tiny_loop_3d",
               {"y^2-x^2*(x+0.04)", "z-0.5*x-0.3*y"},
               {{-1, -1, -1}, {1, 1, 1}},
               {{[=](double t) {
                   const double x = t * t - a, y = t * (t * t - a);
                   return Vec3{x, y, 0.5 * x + 0.3 * y};
                 },
                 -1.1, 1.1}}});
  // Spheres of radius 1 whose centres are 1.9999 apart: a circle of radius ~0.01.
  const double xc = 0.5 * 1.9999, rc = std::sqrt(1.0 - xc * xc);
  r.push_back({"near_tangent_spheres",
               {"x^2+y^2+z^2-1", "(x-1.9999)^2+y^2+z^2-1"},
               {{-1.5, -1.5, -1.5}, {3.5, 1.5, 1.5}},
               {circle({xc, 0, 0}, rc, {0, 1, 0}, {0, 0, 1})}});
  r.push_back({"viviani",
               {"x^2+y^2+z^2-4", "(x-1)^2+y^2-1"},
               {{-3, -3, -3}, {3, 3, 3}},
               {{[](double t) {
                   return Vec3{1.0 + std::cos(t), std::sin(t), 2.0 * std::sin(0.5 * t)};
                 },
                 0.0, 4.0 * std::numbers::pi}}});
  // [Curve] Example 1: x = ρ cos θ, y = ρ sin θ, z = ρ^2 / 4 with ρ^2 (cos^2/9 + sin^2/16) + ρ^4/144 = 1.
  r.push_back({"paper_example_1",
               {"x^2/9+y^2/16+z^2/9-1", "x^2+y^2-4*z"},
               {{-10, -10, -10}, {10, 10, 10}},
               {{[](double t) {
                   const double c = std::cos(t), s = std::sin(t), b = c * c / 9.0 + s * s / 16.0;
                   const double q = 72.0 * (-b + std::sqrt(b * b + 1.0 / 36.0));  // ρ^2
                   const double rho = std::sqrt(q);
                   return Vec3{rho * c, rho * s, q / 4.0};
                 },
                 0.0, 2.0 * std::numbers::pi}}});
  return r;
}

std::shared_ptr<const CompiledGeometry> compile(const Reference& ref) {
  GeometryDefinition def;
  def.type = GeometryType::implicit_curve;
  for (std::size_t i = 0; i < ref.equations.size(); ++i)
    def.formulas.push_back({"equations[" + std::to_string(i) + "]", ref.equations[i]});
  const char* axes[3] = {"x", "y", "z"};
  for (int k = 0; k < (ref.equations.size() == 1 ? 2 : 3); ++k)
    def.domain.push_back({axes[k], {ref.box.lo[k], ref.box.hi[k]}});
  return compile_implicit_curve(def, {});
}

// The least distance from p to the pieces inside the box: 40001 samples per piece, the crossings of
// the box's faces by bisection, every discrete local minimum (the ends' included) polished by
// golden-section search.
double brute_force(const Reference& ref, Vec3 p) {
  auto inside = [&](Vec3 x) { return ref.box.contains(x); };
  auto dist = [&](const Piece& c, double t) { return norm(p - c.at(t)); };
  double best = kInf;
  constexpr int kSamples = 40001;
  for (const Piece& c : ref.pieces) {
    std::vector<double> t(kSamples), d(kSamples);
    std::vector<bool> in(kSamples);
    for (int i = 0; i < kSamples; ++i) {
      t[i] = c.t0 + (c.t1 - c.t0) * i / (kSamples - 1);
      in[i] = inside(c.at(t[i]));
      d[i] = dist(c, t[i]);
      if (in[i]) best = std::min(best, d[i]);
    }
    for (int i = 0; i + 1 < kSamples; ++i)
      if (in[i] != in[i + 1]) {  // the box face between: bisect to the crossing
        double a = t[i], b = t[i + 1];
        for (int k = 0; k < 80; ++k) {
          const double m = 0.5 * (a + b);
          (inside(c.at(m)) == in[i] ? a : b) = m;
        }
        best = std::min(best, dist(c, in[i] ? a : b));
      }
    // The ends too, with a bracket one step beyond them: every piece parametrises its whole
    // algebraic curve (a circle's t = 0 is its t = 2 pi), so c(t) is a point of the curve there.
    const double dt = (c.t1 - c.t0) / (kSamples - 1);
    for (int i = 0; i < kSamples; ++i) {
      const double before = i > 0 ? d[i - 1] : dist(c, t[i] - dt),
                   after = i + 1 < kSamples ? d[i + 1] : dist(c, t[i] + dt);
      if (!in[i] || d[i] > before || d[i] > after) continue;
      double a = t[i] - dt, b = t[i] + dt;
      const double g = 0.5 * (std::sqrt(5.0) - 1.0);
      for (int k = 0; k < 120; ++k) {
        const double x1 = b - g * (b - a), x2 = a + g * (b - a);
        (dist(c, x1) < dist(c, x2) ? b : a) = (dist(c, x1) < dist(c, x2) ? x2 : x1);
      }
      const double m = 0.5 * (a + b);
      if (inside(c.at(m))) best = std::min(best, dist(c, m));
    }
  }
  return best;
}

// Points per reference curve: `standard`, or FOOTPOINT_STRESS_POINTS for a longer sweep, with the
// seed FOOTPOINT_STRESS_SEED added to the standard one for other points (e.g.
// FOOTPOINT_STRESS_POINTS=3000 build/tests/test_curve -tc='certificate: L <= *': ~3 min).
int stress_points(int standard) {
  const char* env = std::getenv("FOOTPOINT_STRESS_POINTS");
  const int n = env ? std::atoi(env) : 0;
  return n > 0 ? n : standard;
}
unsigned stress_seed(unsigned standard) {
  const char* env = std::getenv("FOOTPOINT_STRESS_SEED");
  return standard + (env ? static_cast<unsigned>(std::strtoul(env, nullptr, 10)) : 0u);
}

// Random points: half uniform in the box grown by a fifth, half next to the curve.
std::vector<Vec3> random_points(const Reference& ref, int n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const bool planar = ref.equations.size() == 1;
  const double size = ref.box.diagonal();
  std::vector<Vec3> out;
  while (static_cast<int>(out.size()) < n) {
    Vec3 p;
    if (out.size() % 2 == 0) {
      for (int k = 0; k < (planar ? 2 : 3); ++k) {
        const double w = ref.box.hi[k] - ref.box.lo[k];
        p[k] = ref.box.lo[k] - 0.1 * w + 1.2 * w * u(rng);
      }
    } else {
      const Piece& c = ref.pieces[rng() % ref.pieces.size()];
      const Vec3 x = c.at(c.t0 + (c.t1 - c.t0) * u(rng));
      if (!ref.box.contains(x)) continue;
      Vec3 dir{u(rng) - 0.5, u(rng) - 0.5, planar ? 0.0 : u(rng) - 0.5};
      const double r = 0.05 * size * std::pow(u(rng), 2.0);
      p = x + (r / std::max(norm(dir), 1e-12)) * dir;
    }
    out.push_back(p);
  }
  return out;
}

}  // namespace

TEST_CASE("certificate: L <= brute-force minimum <= d on every reference curve; >= 99 % certified") {
  for (const Reference& ref : references()) {
    CAPTURE(ref.id);
    const auto g = compile(ref);
    const auto& curve = dynamic_cast<const ImplicitCurve&>(*g);
    std::vector<Vec3> singular;
    const CurveSamples& s = curve.discovery().samples;
    for (std::size_t i = 0; i < s.size(); ++i)
      if (s.kind[i] == SampleKind::singular_point) singular.push_back(s.points[i]);
    const double near = 1e-3 * curve.discovery().scale;
    int away = 0, away_certified = 0;
    for (const Vec3& p : random_points(ref, stress_points(sweep_length(360)), stress_seed(61))) {
      INFO("p = (" << std::setprecision(17) << p.x << ", " << p.y << ", " << p.z << ")");
      const double q[3] = {p.x, p.y, p.z};
      const ProjectionResult r = g->project(q, "auto", {}).value();
      const Certificate& c = r.summary.certificate;
      REQUIRE(c.computed);
      const double bf = brute_force(ref, p);
      CAPTURE(bf);
      CAPTURE(r.distance);
      CAPTURE(c.lower_bound);
      const Vec3 foot{r.foot[0], r.foot[1], r.foot[2]};
      bool near_singular = false;
      for (const Vec3& x : singular) near_singular = near_singular || norm(foot - x) <= near;
      CHECK(c.lower_bound <= bf * (1.0 + 1e-12) + 1e-14);
      // The foot is on the curve to the rounding of its equations, which near a singular point
      // (gradients nearly dependent) moves it by that rounding over the angle between them: a
      // Viviani point 5e-4 from the double point had its distance 3.5e-11 below the true minimum.
      CHECK(bf <= r.distance * (1.0 + (near_singular ? 1e-9 : 1e-12)) + 1e-14);
      CHECK(r.distance <= bf * (1.0 + 1e-9) + 1e-12);  // the global minimum
      if (c.certified) {
        CHECK(Certificate::meets_gap(r.distance, c.lower_bound, c.absolute_gap));
        CHECK(c.reason == CertificateReason::gap_met);
      }
      if (!near_singular) {
        ++away;
        away_certified += c.certified ? 1 : 0;
      }
    }
    CHECK(away_certified >= 0.99 * away);
  }
}

TEST_CASE("auto: a minimum just inside the box, nearer than the box-face crossing beside it") {
  // Found by a 3000-point sweep: the crossing was the nearest sample, the next sample inside
  // farther, so the minimum between them had no candidate and the crossing (not a minimum: the
  // distance falls into the box) was answered, `degenerate`, up to 30 % too far.
  const std::map<std::string, std::vector<Vec3>> points{
      {"nodal_loop", {{0.987228, 0.998758, 0.0}}},
      {"tacnode_quartic", {{-1.06113, -0.964113, 0.0}, {1.07334, -1.2057, 0.0}, {1.18532, -1.15783, 0.0}}},
      {"cusp_offset", {{0.656506, -1.19563, 0.0}}}};
  for (const Reference& ref : references()) {
    if (!points.count(ref.id)) continue;
    CAPTURE(ref.id);
    const auto g = compile(ref);
    for (const Vec3& p : points.at(ref.id)) {
      CAPTURE(p.x);
      CAPTURE(p.y);
      const double q[3] = {p.x, p.y, p.z};
      const ProjectionResult r = g->project(q, "auto", {}).value();
      const double bf = brute_force(ref, p);
      CHECK(r.distance <= bf * (1.0 + 1e-9) + 1e-12);
      CHECK(r.summary.status == Status::converged);
      CHECK(r.summary.location == Location::interior);
      CHECK(r.summary.certificate.certified);
    }
  }
}

TEST_CASE("auto: next to a singular point, the minimum on the last stretch of a piece") {
  // A piece of curve ends next to the unproved box of a singular point. Where its samples were
  // thinned up to that end, the distance fell all along the last ones, the last was the only
  // candidate there, and its solve fell into the cusp (the Lagrange system is degenerate there),
  // past the minimum before it: an 800-point sweep found (-0.0704164, 0.1763856) answered 0.046387
  // from the cusp of cusp_offset, the minimum being 0.046343. Points within 1/40 of the box's
  // diagonal of each singular point, against the brute force (4 of them failed so).
  for (const Reference& ref : references()) {
    if (ref.id != "cusp_offset" && ref.id != "tacnode_quartic") continue;
    CAPTURE(ref.id);
    const auto g = compile(ref);
    const auto& curve = dynamic_cast<const ImplicitCurve&>(*g);
    const CurveSamples& s = curve.discovery().samples;
    const double reach = 0.025 * ref.box.diagonal();
    std::mt19937_64 rng(19);
    std::uniform_real_distribution<double> u(-reach, reach);
    int checked = 0;
    for (std::size_t i = 0; i < s.size(); ++i) {
      if (s.kind[i] != SampleKind::singular_point) continue;
      for (int k = 0; k < sweep_length(1000); ++k) {
        const Vec3 p{s.points[i].x + u(rng), s.points[i].y + u(rng), 0.0};
        INFO("p = (" << std::setprecision(17) << p.x << ", " << p.y << ")");
        const double q[3] = {p.x, p.y, 0.0};
        const ProjectionResult r = g->project(q, "auto", {}).value();
        CHECK(r.distance <= brute_force(ref, p) * (1.0 + 1e-9) + 1e-12);
        ++checked;
      }
    }
    CHECK(checked >= sweep_length(1000));
  }
}

TEST_CASE("certificate: a farther local minimum swapped in for the answer is not certified") {
  int swapped = 0;
  Options all;
  all.all_minima = true;
  for (const Reference& ref : references()) {
    CAPTURE(ref.id);
    const auto g = compile(ref);
    const auto& curve = dynamic_cast<const ImplicitCurve&>(*g);
    for (const Vec3& p : random_points(ref, stress_points(60), stress_seed(62))) {
      const double q[3] = {p.x, p.y, p.z};
      const ProjectionResult r = g->project(q, "auto", all).value();
      if (r.minima.size() < 2) continue;
      const Minimum& second = r.minima[1];
      if (!(second.distance > r.distance * (1.0 + 1e-6) + 1e-9)) continue;
      const Vec3 wrong{second.foot[0], second.foot[1], second.foot[2]};
      const Certificate c = curve::certify_implicit_curve_answer(
          curve.equations(), curve.box(), curve.discovery(), p, wrong, second.distance);
      CAPTURE(p.x);
      CAPTURE(p.y);
      CAPTURE(p.z);
      CHECK(c.computed);
      CHECK(!c.certified);
      CHECK(c.lower_bound <= brute_force(ref, p) * (1.0 + 1e-12) + 1e-14);
      ++swapped;
    }
  }
  CHECK(swapped >= 50);
}

TEST_CASE("certificate: left out when options.certify is false; the papers' methods get one when asked") {
  const Reference ref = references()[0];
  const auto g = compile(ref);
  const double p[2] = {1.6, 1.3};
  Options off;
  off.certify = false;
  CHECK(!g->project(p, "auto", off).value().summary.certificate.computed);
  const ProjectionResult r = g->project(p, "auto", {}).value();
  CHECK(r.summary.certificate.certified);
  Options on;
  on.certify = true;
  on.initial = std::array<double, 3>{1.6, 1.3, 0.0};
  const ProjectionResult t = g->project(p, "tangent_foot", on).value();
  CHECK(t.summary.certificate.computed);
  CHECK(t.summary.certificate.lower_bound <= brute_force(ref, {1.6, 1.3, 0.0}) * (1.0 + 1e-12));
  CHECK(!g->project(p, "tangent_foot", {}).value().summary.certificate.computed);
}

TEST_CASE("certificate: a point on the curve, and the gap") {
  const Reference ref = references()[8];  // the ellipse
  REQUIRE(ref.id == "ellipse");
  const auto g = compile(ref);
  const double p[2] = {3.0, 0.0};
  const ProjectionResult r = g->project(p, "auto", {}).value();
  CHECK(r.distance <= 1e-15);
  CHECK(r.summary.certificate.certified);
  CHECK(r.summary.certificate.absolute_gap > 0.0);
  CHECK(r.summary.certificate.absolute_gap < 1e-12);
  CHECK(curve::implicit_absolute_gap({1, 0, 0}, {1, 0, 0}) <
        curve::implicit_absolute_gap({1e6, 0, 0}, {1, 0, 0}));
}
