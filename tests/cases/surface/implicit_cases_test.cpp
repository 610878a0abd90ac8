// Implicit surfaces f(x, y, z) = 0 in a box (compiled/implicit_surface_geometry): `auto` against
// references computed independently (tests/tools/gen_surface_implicit_reference.py: sympy, scipy's
// brentq on dense lines, mpmath at 50 digits; tests/data/surface_implicit_cases.json): sphere,
// ellipsoid, torus, a cone clipped at its apex, hyperboloids of one and two sheets, a sphere and a
// plane clipped so that answers lie on faces, edges and corners, Goursat's surface, a gyroid
// (sin x cos y + sin y cos z + sin z cos x, several sheets in its box), a blend of two spheres
// (f1 f2 = 0.2), far points and points on the surface. The local methods on closed forms (a sphere's foot is
// p / |p|), and the errors.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <vector>

#include "compiled/implicit_surface_geometry.hpp"

using namespace footpoint;
using nlohmann::json;

namespace {

std::shared_ptr<const CompiledGeometry> implicit_surface_of(const std::string& equation, double lo, double hi,
                                                            double zlo, double zhi) {
  GeometryDefinition def;
  def.type = GeometryType::implicit_surface;
  def.formulas = {{"equation", equation}};
  def.domain = {{"x", {lo, hi}}, {"y", {lo, hi}}, {"z", {zlo, zhi}}};
  return compile_geometry(def);
}

std::shared_ptr<const CompiledGeometry> implicit_surface_case(const json& c) {
  GeometryDefinition def;
  def.type = GeometryType::implicit_surface;
  def.formulas = {{"equation", c["equation"]}};
  const json& d = c["domain"];
  def.domain = {{"x", {d["x"][0], d["x"][1]}}, {"y", {d["y"][0], d["y"][1]}}, {"z", {d["z"][0], d["z"][1]}}};
  return compile_geometry(def);
}

Location implicit_surface_location(const std::string& type) {
  if (type == "interior") return Location::interior;
  if (type == "box-face") return Location::box_face;
  if (type == "box-edge") return Location::box_edge;
  if (type == "box-corner") return Location::box_corner;
  return Location::singular_point;
}

double foot_gap(const ProjectionResult& r, const json& foot) {
  return std::hypot(r.foot[0] - foot[0].get<double>(), r.foot[1] - foot[1].get<double>(),
                    r.foot[2] - foot[2].get<double>());
}

}  // namespace

TEST_CASE("implicit surface auto: the references' distances, feet and locations") {
  std::ifstream in(std::string(FOOTPOINT_TESTS_DIR) + "/data/surface_implicit_cases.json");
  REQUIRE(in.good());
  const json data = json::parse(in);
  int points = 0, certified = 0;
  for (const json& c : data["cases"]) {
    const auto g = implicit_surface_case(c);
    for (const json& q : c["points"]) {
      const double p[3] = {q["p"][0], q["p"][1], q["p"][2]};
      const auto r = g->project(p, "auto", {});
      REQUIRE(r);
      const double reference = q["distance"];
      CAPTURE(c["id"].get<std::string>());
      CAPTURE(q["p"].dump());
      CAPTURE(r->distance);
      CAPTURE(reference);
      CHECK(r->summary.status == Status::converged);
      CHECK(std::fabs(r->distance - reference) <= 1e-12 * std::max(1.0, reference));
      if (!q["ambiguous"].get<bool>()) {
        CHECK(foot_gap(*r, q["foot"]) <= 1e-9 * std::max(1.0, reference));
        CHECK(r->summary.location == implicit_surface_location(q["type"]));
      }
      // a tie of the reference's is reported as one (or, on an axis, as a continuum)
      REQUIRE(r->summary.multiplicity.computed);
      if (q["ambiguous"].get<bool>()) CHECK(r->summary.multiplicity.kind != Multiplicity::unique);
      const Certificate& cert = r->summary.certificate;
      REQUIRE(cert.computed);
      // No lower bound above the reference distance.
      CHECK(cert.lower_bound <= reference * (1.0 + 1e-15) + 1e-300);
      ++points;
      certified += cert.certified ? 1 : 0;
    }
  }
  MESSAGE("certified " << certified << " of " << points);
  CHECK(points >= 59);
  CHECK(certified == points);
}

TEST_CASE("implicit surface auto: a nearer minimum close to the answer on Goursat's surface") {
  // Two local minima of the distance 0.46 apart, at 0.41917 and 0.42064: the samples nearest to p
  // lead to the second; the certificate fails with no sample nearer, and the rivals near the
  // answer find the first. Reference: mpmath at 40 digits, Newton on the Lagrange system from 300
  // random starts in the box; the nearest stationary points at 0.4191690698513278259,
  // 0.4206358274150170143 and 0.4277582910754676146.
  const auto goursat = implicit_surface_of("x^4+y^4+z^4-5*(x^2+y^2+z^2)+11.8", -3, 3, -3, 3);
  const double p[3] = {1.5664, 1.4012, 0.7571};
  const auto r = goursat->project(p, "auto", {});
  REQUIRE(r);
  CHECK(std::fabs(r->distance - 0.4191690698513278259) <= 1e-14);
  CHECK(std::fabs(r->foot[0] - 1.8700491683908192016) <= 1e-10);
  CHECK(std::fabs(r->foot[1] - 1.1916092632958823766) <= 1e-10);
  CHECK(std::fabs(r->foot[2] - 0.55817384600456250503) <= 1e-10);
  CHECK(r->summary.certificate.certified);
}

TEST_CASE("implicit surface certificate: points inside a torus' tube near its core circle") {
  // The distance to the torus of radii 2 and 0.5 is |rho - 0.5|, rho the distance to its core
  // circle. Inside the tube near the core the Lagrangian's Hessian I + l H is indefinite along the
  // normal at the foot; the augmented Lagrangian's is not, and these answers are certified.
  const auto torus = implicit_surface_of("(x^2+y^2+z^2+3.75)^2-16*(x^2+y^2)", -3, 3, -1, 1);
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> angle(0.0, 6.283185307179586), offset(0.03, 0.15);
  for (int i = 0; i < 12; ++i) {
    const double phi = angle(rng), theta = angle(rng), rho = offset(rng);
    const double radial = 2.0 + rho * std::cos(theta);
    const double p[3] = {radial * std::cos(phi), radial * std::sin(phi), rho * std::sin(theta)};
    const double reference = 0.5 - std::hypot(std::hypot(p[0], p[1]) - 2.0, p[2]);
    const auto r = torus->project(p, "auto", {});
    REQUIRE(r);
    CAPTURE(rho);
    CHECK(std::fabs(r->distance - reference) <= 1e-14);
    CHECK(r->summary.certificate.certified);
    CHECK(r->summary.certificate.lower_bound <= reference * (1.0 + 1e-15));
  }
}

TEST_CASE("implicit surface multiplicity: continua at centres of curvature, ties, unique feet") {
  struct Case {
    const char* equation;
    double lo, hi, zlo, zhi;
    Vec3 p;
    Multiplicity kind;
    int feet;
  };
  const Case cases[] = {
      {"x^2+y^2+z^2-1", -2, 2, -2, 2, {0, 0, 0}, Multiplicity::continuum, 0},     // the centre
      {"x^2+y^2+z^2-1", -2, 2, -2, 2, {0.3, 0.2, 0.1}, Multiplicity::unique, 1},  // p / |p|
      {"(x^2+y^2+z^2+3.75)^2-16*(x^2+y^2)", -3, 3, -1, 1, {0, 0, 0.3}, Multiplicity::continuum, 0},  // axis
      {"(x^2+y^2+z^2+3.75)^2-16*(x^2+y^2)", -3, 3, -1, 1, {2, 0, 0}, Multiplicity::continuum, 0},    // core
      {"(x^2+y^2+z^2+3.75)^2-16*(x^2+y^2)", -3, 3, -1, 1, {2.1, 0.1, 0.05}, Multiplicity::unique, 1},
      {"x^2/4+y^2+4*z^2-1", -3, 3, -3, 3, {0, 0, 0}, Multiplicity::tied, 2},  // (0, 0, ±0.5)
      {"x^2/4+y^2+4*z^2-1", -3, 3, -3, 3, {0, 0.1, 0}, Multiplicity::tied, 2},
      {"((x-2)^2+y^2+z^2-1)*((x+2)^2+y^2+z^2-1)", -4, 4, -4, 4, {0, 0.3, 0.2}, Multiplicity::tied, 2},
      {"((x-2)^2+y^2+z^2-1)*((x+2)^2+y^2+z^2-1)", -4, 4, -4, 4, {0.1, 0.3, 0.2}, Multiplicity::unique, 1},
  };
  for (const Case& c : cases) {
    CAPTURE(c.equation);
    CAPTURE(c.p.x);
    CAPTURE(c.p.y);
    CAPTURE(c.p.z);
    const auto g = implicit_surface_of(c.equation, c.lo, c.hi, c.zlo, c.zhi);
    const double p[3] = {c.p.x, c.p.y, c.p.z};
    const auto r = g->project(p, "auto", {});
    REQUIRE(r);
    const AnswerMultiplicity& m = r->summary.multiplicity;
    REQUIRE(m.computed);
    CHECK(m.kind == c.kind);
    if (c.kind == Multiplicity::tied) {
      CHECK(m.count == c.feet);
      // mirror images of each other: equal distances, feet apart
      REQUIRE(m.feet.size() == 2);
      const Vec3 a{m.feet[0][0], m.feet[0][1], m.feet[0][2]}, b{m.feet[1][0], m.feet[1][1], m.feet[1][2]};
      CHECK(std::fabs(norm(a - c.p) - norm(b - c.p)) <= 1e-12);
      CHECK(norm(a - b) > 0.5);
    }
  }
}

namespace {

using ImplicitBox = std::array<std::array<double, 2>, 3>;

std::shared_ptr<const CompiledGeometry> implicit_surface_in(const std::string& equation,
                                                            const ImplicitBox& box) {
  GeometryDefinition def;
  def.type = GeometryType::implicit_surface;
  def.formulas = {{"equation", equation}};
  def.domain = {{"x", box[0]}, {"y", box[1]}, {"z", box[2]}};
  return compile_geometry(def);
}

// A configuration whose nearest points are known in closed form: `feet` (two or more: a tie),
// or none (a continuum at `distance`).
struct KnownTie {
  std::string equation;
  ImplicitBox box;
  Vec3 p;
  double distance;
  std::vector<Vec3> feet;
};

// auto's answer, multiplicity and all_minima against the closed form: the distance within 1e-12
// relative, each tied foot listed within 1e-9, the certificate's lower bound not above the distance
// (certified, for a tie); all_minima lists each tied foot once, a continuum once.
void check_known_tie(const KnownTie& c) {
  CAPTURE(c.equation);
  CAPTURE(c.box[0][0]);
  CAPTURE(c.box[0][1]);
  CAPTURE(c.box[1][0]);
  CAPTURE(c.box[1][1]);
  CAPTURE(c.box[2][0]);
  CAPTURE(c.box[2][1]);
  CAPTURE(c.p.x);
  CAPTURE(c.p.y);
  CAPTURE(c.p.z);
  const auto g = implicit_surface_in(c.equation, c.box);
  const double p[3] = {c.p.x, c.p.y, c.p.z};
  const auto r = g->project(p, "auto", {});
  REQUIRE(r);
  CHECK(std::fabs(r->distance - c.distance) <= 1e-12 * c.distance);
  CHECK(r->summary.certificate.lower_bound <= c.distance * (1.0 + 1e-15));
  const AnswerMultiplicity& m = r->summary.multiplicity;
  REQUIRE(m.computed);
  auto listed = [](const std::vector<std::array<double, 3>>& feet, Vec3 x) {
    return std::count_if(feet.begin(), feet.end(), [&](const std::array<double, 3>& f) {
      return norm(Vec3{f[0], f[1], f[2]} - x) <= 1e-9;
    });
  };
  Options o;
  o.all_minima = true;
  const auto a = g->project(p, "auto", o);
  REQUIRE(a);
  std::vector<std::array<double, 3>> nearest;  // all_minima's entries at the nearest distance
  for (const Minimum& k : a->minima)
    if (std::fabs(k.distance - c.distance) <= 1e-12 * c.distance) nearest.push_back(k.foot);
  if (c.feet.empty()) {
    CHECK(m.kind == Multiplicity::continuum);
    CHECK(nearest.size() == 1);
    return;
  }
  CHECK(r->summary.certificate.certified);
  CHECK(m.kind == Multiplicity::tied);
  CHECK(m.count == static_cast<int>(c.feet.size()));
  CHECK(nearest.size() == c.feet.size());
  for (const Vec3& x : c.feet) {
    CAPTURE(x.x);
    CAPTURE(x.y);
    CAPTURE(x.z);
    CHECK(listed(m.feet, x) == 1);
    CHECK(listed(nearest, x) == 1);
  }
}

// The nearest points of the ellipsoid x^2/a^2 + y^2/b^2 + z^2/c^2 = 1 (a > b > c) from p = (x0, y0, 0)
// on its plane of symmetry z = 0 where x = a^2 x0 / (a^2 - c^2), y = b^2 y0 / (b^2 - c^2) has
// x^2/a^2 + y^2/b^2 < 1: the pair (x, y, +-c sqrt(1 - x^2/a^2 - y^2/b^2)) (D. Eberly, "Distance from a
// point to an ellipse, an ellipsoid, or a hyperellipsoid", Geometric Tools, 2013, Sec. 3.3: the
// degenerate case of the secular equation, multiplier c^2).
KnownTie ellipsoid_pair(double a, double b, double c, double x0, double y0, const ImplicitBox& box) {
  const double x = a * a * x0 / (a * a - c * c), y = b * b * y0 / (b * b - c * c);
  const double z = c * std::sqrt(1.0 - x * x / (a * a) - y * y / (b * b));
  char equation[160];
  std::snprintf(equation, sizeof equation, "x^2/%.17g+y^2/%.17g+z^2/%.17g-1", a * a, b * b, c * c);
  return {equation, box, {x0, y0, 0.0}, std::hypot(x - x0, y - y0, z), {{x, y, z}, {x, y, -z}}};
}

}  // namespace

TEST_CASE("implicit surface multiplicity: the ellipsoid's two feet from its centre in a box cut at them") {
  // x^2/4 + y^2 + 4 z^2 = 1 from its centre: (0, 0, +-1/2), tied at 1/2. The box [-3,3]x[-2,2]x[-1,1]
  // puts both feet on faces of its leaves (z = +-1/2 is a plane of the octree's second level),
  // where a leaf's box meets the ball of radius 1/2 about p at the foot alone.
  for (const ImplicitBox& box :
       {ImplicitBox{{{-3, 3}, {-2, 2}, {-1, 1}}}, ImplicitBox{{{-3, 3}, {-3, 3}, {-3, 3}}}})
    check_known_tie({"x^2/4+y^2+4*z^2-1", box, {0, 0, 0}, 0.5, {{0, 0, 0.5}, {0, 0, -0.5}}});
}

TEST_CASE("implicit surface multiplicity: symmetric ties and continua in closed form, in many boxes") {
  const ImplicitBox boxes[] = {{{{-3, 3}, {-3, 3}, {-3, 3}}},
                               {{{-3, 3}, {-2, 2}, {-1, 1}}},
                               {{{-2.5, 3.1}, {-1.3, 2.2}, {-0.9, 1.7}}},
                               {{{-4, 2}, {-1.1, 3}, {-2.6, 0.8}}},
                               {{{-2.2, 2.2}, {-1.2, 1.2}, {-0.6, 0.6}}},
                               {{{-3, 3}, {-2, 2}, {-0.75, 0.75}}},
                               {{{-2.25, 3}, {-1.5, 1.5}, {-1.25, 0.75}}}};
  std::vector<KnownTie> cases;
  for (const ImplicitBox& box : boxes) {
    // the ellipsoid (2, 1, 1/2) from points of its plane z = 0: two feet
    for (const Vec3 q :
         {Vec3{0, 0, 0}, Vec3{0, 0.1, 0}, Vec3{0.3, 0, 0}, Vec3{-0.2, 0.15, 0}, Vec3{0.45, -0.2, 0}})
      cases.push_back(ellipsoid_pair(2.0, 1.0, 0.5, q.x, q.y, box));
    // a sphere from its centre, a torus (R = 1, r = 1/2) from its axis: continua at 1/2 and
    // sqrt(1 + z0^2) - 1/2
    cases.push_back({"x^2+y^2+z^2-0.25", box, {0, 0, 0}, 0.5, {}});
    for (const double z0 : {0.0, 0.2, -0.35})
      cases.push_back({"(x^2+y^2+z^2+0.75)^2-4*(x^2+y^2)", box, {0, 0, z0}, std::hypot(1.0, z0) - 0.5, {}});
  }
  // y^4 + z^4 + x^2/4 = 1 from the origin: four feet (0, +-1, 0), (0, 0, +-1) at 1 (on x = 0,
  // y^2 + z^2 >= sqrt(y^4 + z^4) = 1; elsewhere |x|^2 = 4 (1 - y^4 - z^4) adds more), on the box's
  // faces in the last box
  for (const ImplicitBox& box :
       {ImplicitBox{{{-3, 3}, {-2, 2}, {-2, 2}}}, ImplicitBox{{{-2.5, 3}, {-1.5, 1.25}, {-1.1, 2}}},
        ImplicitBox{{{-2, 2}, {-1, 1}, {-1, 1}}}})
    cases.push_back({"y^4+z^4+x^2/4-1", box, {0, 0, 0}, 1.0, {{0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}}});
  // four unit spheres about (+-2, 0, 0), (0, +-2, 0) from the origin: four feet at 1
  for (const ImplicitBox& box :
       {ImplicitBox{{{-4, 4}, {-4, 4}, {-4, 4}}}, ImplicitBox{{{-3.5, 4}, {-3.2, 3.1}, {-1.3, 2}}}})
    cases.push_back({"((x-2)^2+y^2+z^2-1)*((x+2)^2+y^2+z^2-1)*(x^2+(y-2)^2+z^2-1)*(x^2+(y+2)^2+z^2-1)",
                     box,
                     {0, 0, 0},
                     1.0,
                     {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}}});
  // two unit spheres about (+-2, 0, 0) from points of the plane x = 0: feet c + (p - c) / |p - c|
  for (const ImplicitBox& box :
       {ImplicitBox{{{-4, 4}, {-4, 4}, {-4, 4}}}, ImplicitBox{{{-3.5, 4}, {-3.2, 3.1}, {-1.3, 2}}},
        ImplicitBox{{{-3.3, 3.3}, {-1, 1}, {-1, 1}}}})
    for (const Vec3 q : {Vec3{0, 0, 0}, Vec3{0, 0.3, 0.2}, Vec3{0, -0.5, 0.4}}) {
      const Vec3 right{2, 0, 0}, left{-2, 0, 0};
      cases.push_back({"((x-2)^2+y^2+z^2-1)*((x+2)^2+y^2+z^2-1)",
                       box,
                       q,
                       norm(q - right) - 1.0,
                       {right + (q - right) / norm(q - right), left + (q - left) / norm(q - left)}});
    }
  for (const KnownTie& c : cases) check_known_tie(c);
}

TEST_CASE("implicit surface multiplicity: random ellipsoids from their plane of symmetry, random boxes") {
  // Triaxial ellipsoids, p on z = 0 inside the region of Eberly's tied pair, boxes that hold both
  // feet at random margins (none symmetric about p; every fifth with a foot on the box's top face).
  std::mt19937_64 rng(34);
  auto uniform = [&](double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); };
  for (int n = 0; n < 40; ++n) {
    const double a = uniform(1.5, 3.0), b = uniform(0.8, a - 0.3), c = uniform(0.3, b - 0.3);
    const double radius = 0.9 * std::sqrt(uniform(0.0, 1.0)), angle = uniform(0.0, 2.0 * M_PI);
    const double x = a * radius * std::cos(angle), y = b * radius * std::sin(angle);
    const double x0 = x * (a * a - c * c) / (a * a), y0 = y * (b * b - c * c) / (b * b);
    const double z = c * std::sqrt(1.0 - x * x / (a * a) - y * y / (b * b));
    auto margin = [&]() { return uniform(0.05, 1.5); };
    const ImplicitBox box{{{std::min(x, x0) - margin(), std::max(x, x0) + margin()},
                           {std::min(y, y0) - margin(), std::max(y, y0) + margin()},
                           {-z - margin(), z + (n % 5 == 4 ? 0.0 : margin())}}};
    check_known_tie(ellipsoid_pair(a, b, c, x0, y0, box));
  }
}

TEST_CASE("implicit surface: the foot's normal and the signed distance") {
  // the unit sphere written squared: the normal is the square-free equation's, outwards
  const auto sphere = implicit_surface_of("(x^2+y^2+z^2-1)^2", -2, 2, -2, 2);
  for (const double scale : {2.0, 0.5}) {
    const double p[3] = {0.6 * scale, 0.0, 0.8 * scale};
    const auto r = sphere->project(p, "auto", {});
    REQUIRE(r);
    REQUIRE(r->has_normal());
    CHECK(std::fabs(r->normal[0] - 0.6) <= 1e-15);
    CHECK(std::fabs(r->normal[1]) <= 1e-15);
    CHECK(std::fabs(r->normal[2] - 0.8) <= 1e-15);
    CHECK(std::fabs(r->signed_distance - (scale - 1.0)) <= 1e-15);
  }
  // none at a cone's apex (a singular point)
  const auto cone = implicit_surface_of("x^2+y^2-z^2", -1, 1, 0, 1);
  const double below[3] = {0.0, 0.0, -1.0};
  const auto r = cone->project(below, "auto", {});
  REQUIRE(r);
  CHECK(r->summary.location == Location::singular_point);
  CHECK_FALSE(r->has_normal());
  CHECK(std::isnan(r->signed_distance));
}

TEST_CASE("implicit surface: a repeated factor counts once, and the sphere's foot is p / |p|") {
  const auto squared = implicit_surface_of("(x^2+y^2+z^2-1)^2", -2, 2, -2, 2);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  for (int i = 0; i < 50; ++i) {
    const double p[3] = {u(rng), u(rng), u(rng)};
    const double r = std::hypot(p[0], p[1], p[2]);
    for (const char* method : {"auto", "lagrange_newton"}) {
      const auto a = squared->project(p, method, {});
      REQUIRE(a);
      CAPTURE(method);
      CHECK(a->summary.status == Status::converged);
      CHECK(std::fabs(a->distance - std::fabs(r - 1.0)) <= 1e-14);
      for (int k = 0; k < 3; ++k) CHECK(std::fabs(a->foot[static_cast<std::size_t>(k)] - p[k] / r) <= 1e-13);
    }
  }
}

namespace {

// A local method from p itself on 200 random points about the ellipsoid x^2/4 + y^2 + 4 z^2 = 1 and
// the torus of radii 2 and 0.5 (index 0 and 1): how many converged, their iterations sorted.
struct FromP {
  int total = 0;
  std::vector<int> iterations;  // of the converged, ascending
  int converged() const { return static_cast<int>(iterations.size()); }
  int sum() const {
    int s = 0;
    for (const int i : iterations) s += i;
    return s;
  }
};

std::array<FromP, 2> from_p_on_ellipsoid_and_torus(const char* method) {
  const auto ellipsoid = implicit_surface_of("x^2/4+y^2+4*z^2-1", -3, 3, -3, 3);
  const auto torus = implicit_surface_of("(x^2+y^2+z^2+3.75)^2-16*(x^2+y^2)", -3, 3, -1, 1);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  std::array<FromP, 2> out;
  for (std::size_t s = 0; s < 2; ++s) {
    const auto& g = s == 0 ? ellipsoid : torus;
    for (int i = 0; i < 200; ++i) {
      const double p[3] = {u(rng), u(rng), u(rng) / 3.0};
      const auto r = g->project(p, method, {});
      REQUIRE(r);
      ++out[s].total;
      if (r->summary.status != Status::converged) continue;
      out[s].iterations.push_back(r->summary.iterations);
      // A stationary point of the distance: on the surface and p - x along the normal.
      CHECK(r->summary.residual() <= 1e-10);
    }
    std::sort(out[s].iterations.begin(), out[s].iterations.end());
    MESSAGE(std::string(method)
            << " converged on " << out[s].converged() << " of " << out[s].total << ", mean iterations "
            << static_cast<double>(out[s].sum()) / std::max(1, out[s].converged()) << ", median "
            << (out[s].iterations.empty() ? 0 : out[s].iterations[out[s].iterations.size() / 2]) << ", max "
            << (out[s].iterations.empty() ? 0 : out[s].iterations.back()));
  }
  return out;
}

}  // namespace

TEST_CASE("implicit surface lagrange_newton: 6-7 iterations from p on an ellipsoid and a torus") {
  for (const FromP& f : from_p_on_ellipsoid_and_torus("lagrange_newton")) {
    CHECK(f.converged() >= f.total * 9 / 10);
    CHECK(f.sum() <= 9 * f.converged());
  }
}

TEST_CASE("implicit surface first_order (Hartmann): where it converges on an ellipsoid") {
  // A linear iteration whose rate is the distance over the radius of curvature: it converges
  // where that is below 1 and stalls (max_iterations) or wanders elsewhere; every converged
  // answer is a foot point (residuals at rounding level).
  const auto ellipsoid = implicit_surface_of("x^2/4+y^2+4*z^2-1", -3, 3, -3, 3);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  int converged = 0;
  const int total = 200;
  for (int i = 0; i < total; ++i) {
    const double p[3] = {u(rng), u(rng), u(rng)};
    const auto r = ellipsoid->project(p, "first_order", {});
    REQUIRE(r);
    if (r->summary.status != Status::converged) continue;
    ++converged;
    CHECK(r->summary.residual() <= 1e-8);
    const auto best = ellipsoid->project(p, "auto", {});
    CHECK(r->distance >= best->distance * (1.0 - 1e-12));
  }
  MESSAGE("first_order converged on " << converged << " of " << total);
  CHECK(converged > 0);
}

namespace {

// The errors |x_k - x*| of a traced local method's surface points, x* its end (the trace holds
// the steps x_{k+1} - x_k).
std::vector<double> trace_errors(const ProjectionResult& r) {
  std::vector<double> errors(r.trace.size() + 1, 0.0);
  double d[3] = {0.0, 0.0, 0.0};
  for (std::size_t k = r.trace.size(); k-- > 0;) {
    for (int c = 0; c < 3; ++c) d[c] += r.trace[k][static_cast<std::size_t>(c)];
    errors[k] = std::hypot(d[0], d[1], d[2]);
  }
  return errors;
}

Options traced_from(double x, double y, double z) {
  Options o;
  o.initial = std::array<double, 3>{x, y, z};
  o.trace = true;
  return o;
}

}  // namespace

TEST_CASE("implicit surface hu_wallner: exact on a sphere, quadratic in a normal section") {
  // A sphere's normal sections are its great circles: the curvature circle through the start
  // toward p is the one holding the foot, which the first step reaches; Hartmann's first-order
  // step does not.
  const auto sphere = implicit_surface_of("x^2+y^2+z^2-4", -3, 3, -3, 3);
  const double p[3] = {1.0, 2.5, -0.5};
  const double r = std::hypot(p[0], p[1], p[2]);
  const auto hw = sphere->project(p, "hu_wallner", traced_from(2.0, 0.0, 0.0));
  REQUIRE(hw);
  CHECK(hw->summary.status == Status::converged);
  CHECK(hw->summary.iterations <= 2);
  for (int k = 0; k < 3; ++k)
    CHECK(std::fabs(hw->foot[static_cast<std::size_t>(k)] - 2.0 * p[k] / r) <= 1e-14);
  const auto fo = sphere->project(p, "first_order", traced_from(2.0, 0.0, 0.0));
  CHECK(fo->summary.iterations >= 5 * hw->summary.iterations);
  // On the ellipsoid x^2/4 + y^2 + 4 z^2 = 1 with p in its plane of symmetry z = 0 the iterates
  // stay in that plane, whose section is a principal normal section: e_{k+1} / e_k^2 stays bounded
  // (a first-order step has e_{k+1} / e_k bounded away from 0 there and the ratio grows without
  // bound); the first-order iteration from the same start needs several times the steps.
  const auto ellipsoid = implicit_surface_of("x^2/4+y^2+4*z^2-1", -3, 3, -3, 3);
  for (const auto& q :
       std::vector<std::array<double, 3>>{{2.5, 1.2, 0.0}, {0.3, 0.2, 0.0}, {-1.0, 2.0, 0.0}}) {
    CAPTURE(q[0]);
    CAPTURE(q[1]);
    const auto a = ellipsoid->project(q.data(), "hu_wallner", traced_from(0.0, -1.0, 0.0));
    REQUIRE(a);
    CHECK(a->summary.status == Status::converged);
    const auto e = trace_errors(*a);
    double worst = 0.0;
    for (std::size_t k = 0; k + 1 < e.size(); ++k)
      if (e[k + 1] > 1e-12) worst = std::max(worst, e[k + 1] / (e[k] * e[k]));
    MESSAGE("hu_wallner in the plane z = 0: " << a->summary.iterations << " iterations, max e_{k+1}/e_k^2 "
                                              << worst);
    CHECK(worst <= 10.0);
    const auto f = ellipsoid->project(q.data(), "first_order", traced_from(0.0, -1.0, 0.0));
    MESSAGE("first_order from the same start: " << f->summary.iterations << " iterations");
    CHECK(f->summary.iterations >= 3 * a->summary.iterations);
  }
  // p on the surface (the inversion problem), off every plane of symmetry: p - X is tangent to
  // second order, the normal section toward p holds p, and the convergence is quadratic too.
  for (const double angle : {0.3, 1.1, 2.0}) {
    const double q[3] = {2.0 * std::cos(angle) * std::cos(0.4), std::sin(angle) * std::cos(0.4),
                         0.5 * std::sin(0.4)};
    CAPTURE(angle);
    const auto a = ellipsoid->project(q, "hu_wallner", traced_from(q[0] + 0.3, q[1] - 0.2, q[2] + 0.1));
    REQUIRE(a);
    // At p itself p - X is rounding noise, whose angle with the normal no test can judge: the
    // orthogonality check may call the end degenerate.
    CHECK((a->summary.status == Status::converged || a->summary.status == Status::degenerate));
    CHECK(a->distance <= 1e-15);
    CHECK(a->summary.iterations <= 5);
    const auto e = trace_errors(*a);
    double worst = 0.0;
    for (std::size_t k = 0; k + 1 < e.size(); ++k)
      if (e[k + 1] > 1e-12) worst = std::max(worst, e[k + 1] / (e[k] * e[k]));
    MESSAGE("hu_wallner from a point of the surface: " << a->summary.iterations
                                                       << " iterations, max e_{k+1}/e_k^2 " << worst);
    CHECK(worst <= 10.0);
  }
}

TEST_CASE("implicit surface hu_wallner: from p on an ellipsoid and a torus") {
  const std::array<FromP, 2> f = from_p_on_ellipsoid_and_torus("hu_wallner");
  // On the ellipsoid the section toward p misses the foot off its planes of symmetry: linear
  // convergence, tens of steps. The torus' meridian planes hold p and its foot: its tube circle is
  // the normal section, found in one step.
  CHECK(f[0].converged() == f[0].total);
  CHECK(f[0].iterations.back() <= 100);
  CHECK(f[0].sum() <= 40 * f[0].converged());
  CHECK(f[1].converged() == f[1].total);
  CHECK(f[1].iterations.back() <= 3);
}

TEST_CASE("implicit surface: a product of factors is the union of the factor surfaces") {
  // Closed forms: the distance to the unit sphere is ||p| - 1|, to the plane z = c it is |z - c|
  // (its foot (x, y, c) lies in the box for every p drawn), to the union the least of the two.
  struct Union {
    const char* equation;
    double plane;
  };
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-2.5, 2.5);
  for (const Union& c : {Union{"(x^2+y^2+z^2-1)*(z-2)", 2.0}, Union{"(x^2+y^2+z^2-1)*(2*z-1)", 0.5},
                         Union{"(x^2+y^2+z^2-1)^2*(z-2)^3", 2.0}}) {
    CAPTURE(c.equation);
    const auto g = implicit_surface_of(c.equation, -3, 3, -3, 3);
    const auto& s = dynamic_cast<const ImplicitSurface&>(*g);
    CHECK(s.pieces().size() == 2);
    for (int i = 0; i < 40; ++i) {
      const double p[3] = {u(rng), u(rng), u(rng)};
      const double r = std::hypot(p[0], p[1], p[2]);
      const double to_sphere = std::fabs(r - 1.0), to_plane = std::fabs(p[2] - c.plane);
      const auto a = g->project(p, "auto", {});
      REQUIRE(a);
      CHECK(a->summary.status == Status::converged);
      CHECK(std::fabs(a->distance - std::min(to_sphere, to_plane)) <= 1e-13);
      CHECK(a->summary.certificate.certified);
      CHECK(a->summary.certificate.lower_bound <= std::min(to_sphere, to_plane));
      const std::array<double, 3> foot = to_sphere < to_plane
                                             ? std::array<double, 3>{p[0] / r, p[1] / r, p[2] / r}
                                             : std::array<double, 3>{p[0], p[1], c.plane};
      for (int k = 0; k < 3; ++k) CHECK(std::fabs(a->foot[static_cast<std::size_t>(k)] - foot[k]) <= 1e-12);
      // A local method's certificate bounds both factor surfaces.
      Options certify;
      certify.certify = true;
      const auto n = g->project(p, "lagrange_newton", certify);
      if (n->summary.status == Status::converged && n->summary.certificate.certified)
        CHECK(n->distance <= std::min(to_sphere, to_plane) * (1.0 + 1e-9) + 1e-15);
    }
  }
  // Equidistant from the sphere and the plane z = 2: two feet, tied.
  const auto g = implicit_surface_of("(x^2+y^2+z^2-1)*(z-2)", -3, 3, -3, 3);
  const double mid[3] = {0.0, 0.0, 1.5};
  const auto t = g->project(mid, "auto", {});
  CHECK(std::fabs(t->distance - 0.5) <= 1e-15);
  CHECK(t->summary.multiplicity.kind == Multiplicity::tied);
  CHECK(t->summary.multiplicity.count == 2);
  Options all;
  all.all_minima = true;
  const auto m = g->project(mid, "auto", all);
  CHECK(m->minima.size() >= 2);
  // The plane z = 1 touches the sphere at (0, 0, 1): the foot of (0, 0, 3) on both, where the
  // product's gradient vanishes.
  const auto touching = implicit_surface_of("(x^2+y^2+z^2-1)*(z-1)", -3, 3, -3, 3);
  const double above[3] = {0.0, 0.0, 3.0};
  const auto a = touching->project(above, "auto", {});
  CHECK(std::fabs(a->distance - 2.0) <= 1e-15);
  CHECK(a->summary.location == Location::singular_point);
  CHECK(a->summary.multiplicity.kind == Multiplicity::unique);
  CHECK(a->summary.certificate.certified);
  // A factor with no point in the box is dropped: the plane z = 5 lies outside it.
  const auto outside = implicit_surface_of("(x^2+y^2+z^2-1)*(z-5)", -3, 3, -3, 3);
  CHECK(dynamic_cast<const ImplicitSurface&>(*outside).pieces().size() == 1);
}

TEST_CASE("implicit surface errors: empty_surface, geometry_too_complex, wrong shape") {
  auto code_of = [](const std::string& equation, double lo, double hi) {
    try {
      implicit_surface_of(equation, lo, hi, lo, hi);
    } catch (const GeometryError& e) {
      return e.code;
    }
    return std::string("none");
  };
  CHECK(code_of("x^2+y^2+z^2+1", -2, 2) == "empty_surface");
  CHECK(code_of("x^2+y^2+z^2-1", 2, 3) == "empty_surface");
  CHECK(code_of("sin(40*x)*cos(40*y)+sin(40*y)*cos(40*z)+sin(40*z)*cos(40*x)", -3, 3) ==
        "geometry_too_complex");
  CHECK(code_of("x^2+y^2+z^2-1", -2, 2) == "none");
  // The unit sphere in a box of 1e300: the cells that may hold it are too large for Newton to land
  // from their centres (x^2 overflows), which is said, not taken for an empty box.
  CHECK(code_of("x^2+y^2+z^2-1", -1e300, 1e300) == "geometry_too_complex");
  CHECK(code_of("0*x", -1, 1) == "geometry_too_complex");  // every cell holds the "surface"
  GeometryDefinition def;
  def.type = GeometryType::implicit_surface;
  def.formulas = {{"equation", "x+y"}};
  def.domain = {{"x", {0, 1}}, {"y", {0, 1}}};
  CHECK_THROWS_AS(compile_geometry(def), GeometryError);
}

TEST_CASE("implicit surface: a sphere of radius 1e-10 is found, and its centre is no singular point") {
  const auto tiny = implicit_surface_of("x^2+y^2+z^2-1e-20", -1, 1, -1, 1);
  const auto& s = dynamic_cast<const ImplicitSurface&>(*tiny);
  CHECK(s.cells().singular_points.empty());  // grad f = 0 at the centre, but f = -1e-20 there
  const double p[3] = {0.5, 0.5, 0.5};
  const auto r = tiny->project(p, "auto", {});
  REQUIRE(r);
  CHECK(r->summary.status == Status::converged);
  CHECK(r->distance == doctest::Approx(std::sqrt(0.75) - 1e-10).epsilon(1e-15));
  CHECK(r->summary.location == Location::interior);
}

TEST_CASE("implicit surface: canonical form and id round trip") {
  GeometryDefinition def;
  def.type = GeometryType::implicit_surface;
  def.formulas = {{"equation", "x^2 + y^2 - z^2"}};
  def.domain = {{"x", {-1, 1}}, {"y", {-1, 1}}, {"z", {0, 1}}};
  CHECK(def.canonical() ==
        "footpoint/1;type=implicit_surface;equation=x^2+y^2-z^2;domain.x=[-1,1];"
        "domain.y=[-1,1];domain.z=[0,1]");
  const GeometryDefinition back = parse_canonical(def.canonical());
  CHECK(back.id() == def.id());
  CHECK(back.type == GeometryType::implicit_surface);
}

TEST_CASE(
    "implicit surface: answers at the box's corners and edges are certified; a kink answers degenerate") {
  // The triangle x + y + z = 1 in the unit cube: from points around it the foot is often a
  // corner or on an edge, where the Lagrangian's multiplier is chosen to give the box's
  // multipliers their signs; elsewhere on the lines where it meets the faces.
  const auto plane = implicit_surface_of("x+y+z-1", 0, 1, 0, 1);
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> u(-1.0, 2.0);
  int corners = 0, faces = 0;
  for (int i = 0; i < 200; ++i) {
    const double p[3] = {u(rng), u(rng), u(rng)};
    const auto r = plane->project(p, "auto", {});
    REQUIRE(r);
    CAPTURE(p[0]);
    CAPTURE(p[1]);
    CAPTURE(p[2]);
    CHECK(r->summary.certificate.certified);
    CHECK(std::fabs(r->foot[0] + r->foot[1] + r->foot[2] - 1.0) <= 1e-15);
    corners += r->summary.location == Location::box_corner ? 1 : 0;
    faces += r->summary.location == Location::box_face ? 1 : 0;
  }
  CHECK(corners > 10);
  CHECK(faces > 10);
  // The octahedron |x| + |y| + |z| = 1: from (-2.197, -2.182, -0.2927) the foot lies on a kink,
  // where neither Newton's nor Hartmann's step is defined: a point of the surface, degenerate.
  const auto octahedron = implicit_surface_of("abs(x)+abs(y)+abs(z)-1", -2, 2, -2, 2);
  const double p[3] = {-2.197, -2.182, -0.2927};
  const auto r = octahedron->project(p, "auto", {});
  REQUIRE(r);
  CHECK(r->summary.status == Status::degenerate);
  REQUIRE(std::isfinite(r->distance));
  CHECK(std::fabs(std::fabs(r->foot[0]) + std::fabs(r->foot[1]) + std::fabs(r->foot[2]) - 1.0) <= 1e-12);
  CHECK(r->summary.certificate.lower_bound <= r->distance);
}

TEST_CASE("implicit surface auto all_minima: the local minima of the distance, the answer first") {
  // From the centre of the ellipsoid x^2/4 + y^2 + 4 z^2 = 1 the distance is stationary at the six
  // vertices: minima at (0, 0, +-1/2), saddles at (0, +-1, 0), maxima at (+-2, 0, 0).
  const auto ellipsoid = implicit_surface_of("x^2/4+y^2+4*z^2-1", -3, 3, -3, 3);
  const double centre[3] = {0.0, 0.0, 0.0};
  Options o;
  o.all_minima = true;
  const auto r = ellipsoid->project(centre, "auto", o);
  REQUIRE(r);
  REQUIRE(r->minima.size() == 2);
  for (const Minimum& m : r->minima) {
    CHECK(m.distance == doctest::Approx(0.5).epsilon(1e-14));
    CHECK(std::fabs(m.foot[0]) <= 1e-14);
    CHECK(std::fabs(m.foot[1]) <= 1e-14);
    CHECK(std::fabs(std::fabs(m.foot[2]) - 0.5) <= 1e-14);
  }
  CHECK(r->minima[0].foot[2] * r->minima[1].foot[2] < 0.0);
  CHECK(r->minima[0].foot[2] == doctest::Approx(r->foot[2]).epsilon(1e-14));
  // From a point inside the unit sphere its one local minimum is the nearest point.
  const auto sphere = implicit_surface_of("x^2+y^2+z^2-1", -2, 2, -2, 2);
  const double inside[3] = {0.3, 0.2, 0.1};
  const auto s = sphere->project(inside, "auto", o);
  REQUIRE(s);
  REQUIRE(s->minima.size() == 1);
  CHECK(s->minima[0].distance == doctest::Approx(1.0 - std::sqrt(0.14)).epsilon(1e-14));
  o.max_minima = 1;
  CHECK(ellipsoid->project(centre, "auto", o)->minima_truncated);
}
