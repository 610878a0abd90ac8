// Numerical honesty, as a property of every answer: for random points around the public cases'
// geometries (and one geometry of our own for each type they lack), the answer of `auto`
//  - names a point of the geometry: s(params) = foot with params in the domain (parametric), or
//    f_i(foot) = 0 with foot in the box (implicit), checked by evaluating the formulas here;
//  - states the distance of that point: distance = |p - foot|; together with the above, no
//    returned distance can be below the true minimum (it is the distance to a point of the set);
//  - is the global minimum: distance <= the minimum over a dense sampling of the geometry made
//    here (a grid of the domain; for implicit curves, points landed on the curve and traced
//    along it), which bounds the true minimum from above;
//  - is converged only if the residuals say so: the orthogonality of p - foot to the tangent(s)
//    at an interior foot point, recomputed here from exact derivatives, is at rounding level.
// Every other method of each geometry is held to the same honesty (a point of the geometry, its
// true distance, `converged` only when orthogonal), but not to globality: they are local methods.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <unordered_set>
#include <vector>

#include <nlohmann/json.hpp>

#include "compiled/compiled_geometry.hpp"
#include "formula/program.hpp"

using footpoint::compile_geometry;
using footpoint::CompiledGeometry;
using footpoint::GeometryDefinition;
using footpoint::GeometryType;
using footpoint::Location;
using footpoint::Options;
using footpoint::ProjectionResult;
using footpoint::Status;
using footpoint::formula::Jet2;
using footpoint::formula::Program;
using json = nlohmann::json;

namespace {

using P3 = std::array<double, 3>;

P3 sub(const P3& a, const P3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double dot(const P3& a, const P3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
double norm(const P3& a) { return std::sqrt(dot(a, a)); }
double norm_inf(const P3& a) { return std::max({std::fabs(a[0]), std::fabs(a[1]), std::fabs(a[2])}); }
P3 cross(const P3& a, const P3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
// |<a, t>| / (|a| |t|): 0 when a is orthogonal to t.
double cosine(const P3& a, const P3& t) { return std::fabs(dot(a, t)) / (norm(a) * norm(t)); }

// Bounds on the answers, relative to the size of the numbers involved (s = max(1, |p|, |foot|)):
// rounding of a handful of operations on numbers of that size, with room for formulas that
// cancel ([Hybrid]'s degree-6 polynomials).
constexpr double kSame = 1e-12;       // |s(params) - foot|, |distance - |p - foot||
constexpr double kOnCurve = 1e-10;    // |f_i(foot)| / |grad f_i(foot)|, a distance to f_i = 0
constexpr double kOrthogonal = 1e-8;  // the solvers' own largest accepted (stalled) residual

// A geometry under test: what the library compiled, the formulas compiled again here, and a dense
// sampling of its points.
struct Subject {
  std::string name;
  GeometryDefinition def;
  std::shared_ptr<const CompiledGeometry> compiled;
  Program program;  // the same formulas, evaluated independently of the solvers
  int dim = 3;      // point dimension
  std::vector<P3> samples;
  P3 lo{}, hi{};  // bounding box of the samples
};

GeometryDefinition definition(GeometryType type, std::vector<footpoint::formula::NamedFormula> formulas,
                              std::vector<std::pair<std::string, std::array<double, 2>>> domain) {
  GeometryDefinition d;
  d.type = type;
  d.formulas = std::move(formulas);
  d.domain = std::move(domain);
  return d;
}

std::vector<std::string> variables(const GeometryDefinition& def) {
  std::vector<std::string> v;
  for (const auto& [name, range] : def.domain) v.push_back(name);
  return v;
}

// ---- parametric: s(params) and a grid of the domain -------------------------------------------

P3 evaluate(const Subject& s, const double* params) {
  double out[3] = {0.0, 0.0, 0.0};
  s.program.values(params, out);
  return {out[0], out[1], out[2]};
}

void sample_parametric(Subject& s) {
  const auto& d = s.def.domain;
  if (d.size() == 2) {
    const int n = 700;  // 490,000 points of the surface
    for (int i = 0; i <= n; ++i)
      for (int j = 0; j <= n; ++j) {
        const double t[2] = {d[0].second[0] + (d[0].second[1] - d[0].second[0]) * i / n,
                             d[1].second[0] + (d[1].second[1] - d[1].second[0]) * j / n};
        s.samples.push_back(evaluate(s, t));
      }
  } else {
    const int n = 400000;
    for (int i = 0; i <= n; ++i) {
      const double t = d[0].second[0] + (d[0].second[1] - d[0].second[0]) * i / n;
      s.samples.push_back(evaluate(s, &t));
    }
  }
}

// ---- implicit: F = (f1, f2) with exact gradients; planar curves as f1(x, y), f2 = z ----------

struct Equations {
  std::array<double, 2> f{};
  std::array<P3, 2> grad{};
};

Equations equations(const Subject& s, const P3& x) {
  Equations e;
  if (s.dim == 2) {
    Jet2<2> j[1];
    s.program.jets2<2>(x.data(), j);
    e.f = {j[0].v, x[2]};
    e.grad = {P3{j[0].g[0], j[0].g[1], 0.0}, P3{0.0, 0.0, 1.0}};
  } else {
    Jet2<3> j[2];
    s.program.jets2<3>(x.data(), j);
    e.f = {j[0].v, j[1].v};
    e.grad = {P3{j[0].g[0], j[0].g[1], j[0].g[2]}, P3{j[1].g[0], j[1].g[1], j[1].g[2]}};
  }
  return e;
}

P3 box_lo(const Subject& s) {
  P3 lo{};
  for (std::size_t k = 0; k < s.def.domain.size(); ++k) lo[k] = s.def.domain[k].second[0];
  return lo;
}
P3 box_hi(const Subject& s) {
  P3 hi{};
  for (std::size_t k = 0; k < s.def.domain.size(); ++k) hi[k] = s.def.domain[k].second[1];
  return hi;
}
bool in_box(const Subject& s, const P3& x, double slack = 0.0) {
  const P3 lo = box_lo(s), hi = box_hi(s);
  for (int k = 0; k < 3; ++k)
    if (x[k] < lo[k] - slack || x[k] > hi[k] + slack) return false;
  return true;
}

// Largest |f_i| / |grad f_i|: to first order the distance from x to the surface f_i = 0.
double equation_residual(const Subject& s, const P3& x) {
  const Equations e = equations(s, x);
  return std::max(std::fabs(e.f[0]) / norm(e.grad[0]), std::fabs(e.f[1]) / norm(e.grad[1]));
}

// Gauss-Newton onto F = 0 with the minimum-norm step dx = -J^T (J J^T)^{-1} F (J has the rows
// grad f1, grad f2). True when x landed (residual at rounding level relative to `scale`).
bool land(const Subject& s, P3& x, double scale) {
  for (int it = 0; it < 30; ++it) {
    const Equations e = equations(s, x);
    const double a = dot(e.grad[0], e.grad[0]), b = dot(e.grad[0], e.grad[1]), c = dot(e.grad[1], e.grad[1]);
    const double det = a * c - b * b;
    if (!(det > 1e-300) || !std::isfinite(det)) return false;
    const double l0 = (c * e.f[0] - b * e.f[1]) / det, l1 = (a * e.f[1] - b * e.f[0]) / det;
    for (int k = 0; k < 3; ++k) x[k] -= l0 * e.grad[0][k] + l1 * e.grad[1][k];
    if (!std::isfinite(norm(x))) return false;
    if (norm_inf(P3{l0 * std::sqrt(a), l1 * std::sqrt(c), 0.0}) < 1e-15 * scale)
      return equation_residual(s, x) < 1e-13 * scale;
  }
  return equation_residual(s, x) < 1e-13 * scale;
}

// Points of an implicit curve: starts on a grid over `region` land on the curve, and from every
// landing not yet near a traced point the curve is followed both ways in steps of h (predictor
// along the tangent grad f1 x grad f2, corrector `land`) until it closes, leaves the box or the
// region, or turns singular. Consecutive samples are about h apart.
void sample_implicit(Subject& s, const P3& region_lo, const P3& region_hi) {
  const double scale = norm(sub(region_hi, region_lo));
  const double h = scale / 20000;
  const double cell = 4 * h;
  auto key = [&](const P3& x) {
    const auto q = [&](int k) { return static_cast<long long>(std::floor((x[k] - region_lo[k]) / cell)); };
    return (q(0) * 73856093LL) ^ (q(1) * 19349663LL) ^ (q(2) * 83492791LL);
  };
  std::unordered_set<long long> visited;
  auto near_visited = [&](const P3& x) {
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz)
          if (visited.count(key(P3{x[0] + dx * cell, x[1] + dy * cell, x[2] + dz * cell}))) return true;
    return false;
  };
  auto inside = [&](const P3& x) {
    for (int k = 0; k < 3; ++k)
      if (x[k] < region_lo[k] - 0.05 * scale || x[k] > region_hi[k] + 0.05 * scale) return false;
    return in_box(s, x);
  };
  auto add = [&](const P3& x) {
    s.samples.push_back(x);
    visited.insert(key(x));
  };
  // Returns true when the curve closed on itself.
  auto trace = [&](P3 x, double direction) {
    const P3 start = x;
    for (int step = 0; step < 400000; ++step) {
      const Equations e = equations(s, x);
      P3 t = cross(e.grad[0], e.grad[1]);
      const double nt = norm(t);
      if (!(nt > 0.0)) return false;
      for (auto& c : t) c *= direction * h / nt;
      P3 next = {x[0] + t[0], x[1] + t[1], x[2] + t[2]};
      if (!land(s, next, scale) || !inside(next)) return false;
      if (norm(sub(next, x)) > 3 * h) return false;  // jumped to another branch: stop here
      x = next;
      add(x);
      if (step > 10 && norm(sub(x, start)) < h) return true;
    }
    return false;
  };
  const int n = s.dim == 2 ? 60 : 24;
  const int nz = s.dim == 2 ? 0 : n;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j)
      for (int k = 0; k <= nz; ++k) {
        P3 x = {region_lo[0] + (region_hi[0] - region_lo[0]) * i / n,
                region_lo[1] + (region_hi[1] - region_lo[1]) * j / n,
                nz ? region_lo[2] + (region_hi[2] - region_lo[2]) * k / nz : 0.0};
        if (!land(s, x, scale) || !inside(x) || near_visited(x)) continue;
        add(x);
        if (!trace(x, 1.0)) trace(x, -1.0);
      }
}

void bound_samples(Subject& s) {
  REQUIRE(!s.samples.empty());
  s.lo = s.hi = s.samples[0];
  for (const auto& x : s.samples)
    for (int k = 0; k < 3; ++k) {
      s.lo[k] = std::min(s.lo[k], x[k]);
      s.hi[k] = std::max(s.hi[k], x[k]);
    }
}

Subject make_subject(const std::string& name, GeometryDefinition def, const json* curve_bbox = nullptr) {
  Subject s;
  s.name = name;
  s.def = std::move(def);
  s.compiled = compile_geometry(s.def);
  s.dim = s.compiled->point_dim();
  s.program = Program::compile(s.def.formulas, variables(s.def), s.def.constants);
  if (s.def.type == GeometryType::implicit_curve) {
    P3 lo = box_lo(s), hi = box_hi(s);
    if (curve_bbox)  // the reference's bounding box of the curve: where to look for it in a large box
      for (int k = 0; k < 3; ++k) {
        const double a = (*curve_bbox)[k][0], b = (*curve_bbox)[k][1], pad = 0.05 * (b - a) + 1e-3;
        lo[k] = std::max(lo[k], a - pad);
        hi[k] = std::min(hi[k], b + pad);
      }
    sample_implicit(s, lo, hi);
  } else {
    sample_parametric(s);
  }
  bound_samples(s);
  return s;
}

std::vector<Subject> make_subjects() {
  std::ifstream in(FOOTPOINT_CASES_FILE);
  REQUIRE_MESSAGE(in.good(), "cannot read " << FOOTPOINT_CASES_FILE);
  const json cases = json::parse(in)["cases"];
  std::vector<Subject> all;
  for (const auto& c : cases) {
    const std::string kind = c["kind"];
    if (kind == "surface") {
      all.push_back(make_subject(
          c["id"],
          definition(GeometryType::parametric_surface,
                     {{"x", c["formulas"]["x"]}, {"y", c["formulas"]["y"]}, {"z", c["formulas"]["z"]}},
                     {{"u", c["domain"]["u"]}, {"v", c["domain"]["v"]}})));
    } else if (kind == "curve3d_implicit") {
      all.push_back(make_subject(
          c["id"],
          definition(GeometryType::implicit_curve,
                     {{"equations[0]", c["formulas"]["f1"]}, {"equations[1]", c["formulas"]["f2"]}},
                     {{"x", c["box"]["x"]}, {"y", c["box"]["y"]}, {"z", c["box"]["z"]}}),
          &c["object_info"]["curve_bbox"]));
    } else {
      FAIL("a public case of an unknown kind: " << kind);
    }
  }
  // The types the public cases lack: a planar spiral (many local minima), a spatial helix, and a
  // planar hyperbola cut by its box (its nearest point can be an end on the box's face).
  all.push_back(
      make_subject("spiral", definition(GeometryType::parametric_curve,
                                        {{"x", "t*cos(t)"}, {"y", "t*sin(t)"}}, {{"t", {0.0, 12.0}}})));
  all.push_back(make_subject(
      "helix", definition(GeometryType::parametric_curve, {{"x", "cos(t)"}, {"y", "sin(t)"}, {"z", "0.2*t"}},
                          {{"t", {-10.0, 10.0}}})));
  all.push_back(
      make_subject("hyperbola", definition(GeometryType::implicit_curve, {{"equations[0]", "x^2-y^2-1"}},
                                           {{"x", {-2.0, 2.0}}, {"y", {-1.5, 1.5}}})));
  return all;
}

// Built once for both test cases (the sampling is the expensive part).
const std::vector<Subject>& subjects() {
  static const std::vector<Subject> all = make_subjects();
  return all;
}

std::string text(const P3& x) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "(%.17g, %.17g, %.17g)", x[0], x[1], x[2]);
  return buf;
}

// Random points around a geometry: near its points, inside its bounding box grown by half, and
// far away.
std::vector<P3> points_around(const Subject& s, std::mt19937_64& rng, int count) {
  const P3 centre = {(s.lo[0] + s.hi[0]) / 2, (s.lo[1] + s.hi[1]) / 2, (s.lo[2] + s.hi[2]) / 2};
  const double size = std::max(norm(sub(s.hi, s.lo)), 1e-3);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::uniform_int_distribution<std::size_t> pick(0, s.samples.size() - 1);
  std::vector<P3> points;
  for (int i = 0; i < count; ++i) {
    P3 p{};
    const P3& near = s.samples[pick(rng)];
    for (int k = 0; k < s.dim; ++k) {
      const double half = std::max((s.hi[k] - s.lo[k]) / 2, 1e-3);
      switch (i % 3) {
        case 0:
          p[k] = near[k] + 0.05 * size * unit(rng);
          break;
        case 1:
          p[k] = centre[k] + 1.5 * half * unit(rng);
          break;
        default:
          p[k] = centre[k] + 5.0 * size * unit(rng);
          break;
      }
    }
    points.push_back(p);
  }
  return points;
}

double brute_force_distance(const Subject& s, const P3& p) {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& x : s.samples) {
    const P3 d = sub(p, x);
    best = std::min(best, dot(d, d));
  }
  return std::sqrt(best);
}

// The tangents at the foot point whose orthogonality to p - foot a converged interior answer
// must satisfy: s_u, s_v (surfaces), c' (curves), grad f1 x grad f2 (implicit curves).
std::vector<P3> tangents(const Subject& s, const ProjectionResult& r) {
  if (s.def.type == GeometryType::implicit_curve) {
    const Equations e = equations(s, r.foot);
    return {cross(e.grad[0], e.grad[1])};
  }
  std::vector<P3> t;
  if (r.num_params == 2) {
    Jet2<2> j[3];
    s.program.jets2<2>(r.params.data(), j);
    t.push_back({j[0].g[0], j[1].g[0], j[2].g[0]});
    t.push_back({j[0].g[1], j[1].g[1], j[2].g[1]});
  } else {
    Jet2<1> j[3];
    s.program.jets2<1>(r.params.data(), j);
    t.push_back({j[0].g[0], j[1].g[0], s.dim == 3 ? j[2].g[0] : 0.0});
  }
  return t;
}

// The honesty of one answer (any method). Returns true when it gave a foot point.
bool check_honest(const Subject& s, const std::string& method, const P3& p, const ProjectionResult& r) {
  CAPTURE(s.name);
  CAPTURE(method);
  INFO("p = " << text(p) << ", foot = " << text(r.foot) << ", distance = " << r.distance << ", status "
              << std::string(footpoint::to_string(r.summary.status)) << ", residual " << r.summary.residual()
              << ", location " << std::string(footpoint::to_string(r.summary.location)));
  CHECK(r.dim == s.dim);
  CHECK(r.summary.converged() == (r.summary.status == Status::converged));
  const bool finite = std::isfinite(r.distance) && std::isfinite(norm(r.foot));
  if (r.summary.converged()) CHECK(finite);
  if (!finite) return false;
  const double scale = std::max({1.0, norm_inf(p), norm_inf(r.foot)});
  // The stated distance is the distance to the stated foot point.
  CHECK(std::fabs(r.distance - norm(sub(p, r.foot))) <= kSame * scale);
  if (s.dim == 2) CHECK(r.foot[2] == 0.0);
  // The foot point is a point of the geometry: on it always (even an unconverged answer names the
  // point where the method stopped), and inside the domain or box when converged (the paper
  // methods run unclamped and say outside_domain when they leave it).
  if (s.def.type == GeometryType::implicit_curve) {
    CHECK(r.num_params == 0);
    if (r.summary.converged()) CHECK(in_box(s, r.foot, kSame * scale));
    CHECK(equation_residual(s, r.foot) <= kOnCurve * scale);
  } else {
    CHECK(r.num_params == static_cast<int>(s.def.domain.size()));
    if (r.summary.converged())
      for (int k = 0; k < r.num_params; ++k) {
        CHECK(r.params[k] >= s.def.domain[k].second[0]);
        CHECK(r.params[k] <= s.def.domain[k].second[1]);
      }
    CHECK(norm_inf(sub(evaluate(s, r.params.data()), r.foot)) <= kSame * scale);
  }
  // Converged at an interior point: p - foot is orthogonal to the geometry there (unless p is on
  // the geometry, where no direction is defined).
  if (r.summary.converged() && r.summary.location == Location::interior && r.distance > 1e-9 * scale) {
    CHECK(r.summary.residual() <= kOrthogonal);
    for (const P3& t : tangents(s, r))
      if (norm(t) > 0.0) CHECK(cosine(sub(p, r.foot), t) <= kOrthogonal);
  }
  return true;
}

}  // namespace

TEST_CASE("auto: every answer is a point of the geometry at the stated distance, and the global one") {
  std::mt19937_64 rng(20240607);
  int answers = 0, converged = 0;
  for (const Subject& s : subjects()) {
    CAPTURE(s.name);
    CAPTURE(s.samples.size());
    // The sampling itself must cover the geometry: a few thousand points at least.
    REQUIRE(s.samples.size() > 2000);
    for (const P3& p : points_around(s, rng, 60)) {
      const ProjectionResult r = s.compiled->project(p.data(), "auto", Options{}).value();
      ++answers;
      if (!check_honest(s, "auto", p, r)) continue;
      if (!r.summary.converged()) continue;
      ++converged;
      // Global: no sampled point of the geometry is nearer than the answer.
      const double scale = std::max({1.0, norm_inf(p), norm_inf(r.foot)});
      const double sampled = brute_force_distance(s, p);
      INFO("p = " << text(p) << ", foot = " << text(r.foot) << ", sampled minimum " << sampled);
      CHECK(r.distance <= sampled + kSame * scale);
    }
  }
  MESSAGE(converged << " of " << answers << " auto answers converged");
  // `auto` is the global method: it converges on these geometries.
  CHECK(converged == answers);
}

TEST_CASE("every method: converged only when the answer is a foot point of the geometry") {
  std::mt19937_64 rng(977);
  for (const Subject& s : subjects()) {
    for (const auto& m : s.compiled->methods()) {
      if (m.name == "auto") continue;
      for (const P3& p : points_around(s, rng, 6)) {
        const ProjectionResult r = s.compiled->project(p.data(), m.name, Options{}).value();
        check_honest(s, std::string(m.name), p, r);
      }
    }
  }
}
