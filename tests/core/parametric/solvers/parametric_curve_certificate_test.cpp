// The certificate of a parametric curve's answer (parametric/solvers/parametric_curve_certificate.hpp):
//  - an answer given as it is (a local method's with options.certify): a local minimum that is
//    not the global one is never certified and is refuted by a nearer point; the global one is
//    certified - on a helix, whose windings give many local minima;
//  - the cusps (t^2, t^3), (t^2, t^5), (t^3, t^5): a point 1e-4 from the cusp on the curve itself
//    is answered there (the samples' nearest point is the cusp, where c' = 0 and the distance's
//    derivative vanishes: only the certificate's bounds see that a nearer point exists next to it).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "compiled/compiled_geometry.hpp"
#include "compiled/parametric_curve_geometry.hpp"
#include "parametric/solvers/parametric_curve_certificate.hpp"

using namespace footpoint;

namespace {

std::shared_ptr<const ParametricCurve> make_curve(const char* x, const char* y, const char* z, double t0,
                                                  double t1) {
  GeometryDefinition def;
  def.type = GeometryType::parametric_curve;
  def.formulas = {{"x", x}, {"y", y}};
  if (z) def.formulas.push_back({"z", z});
  def.domain = {{"t", {t0, t1}}};
  return std::dynamic_pointer_cast<const ParametricCurve>(compile_geometry(def));
}

}  // namespace

TEST_CASE("curves: a local minimum given as the answer is refuted, the global one certified") {
  const auto helix = make_curve("cos(t)", "sin(t)", "0.2*t", 0.0, 12.566370614359172);
  int worse = 0, refuted = 0, certified = 0;
  for (const Vec3 p :
       {Vec3{1.5, 0.3, 0.7}, Vec3{0.2, 0.1, 1.3}, Vec3{-0.9, 0.4, 1.9}, Vec3{0.5, -1.2, 0.2}}) {
    const ProjectionResult best = helix->project(&p.x, "auto", Options{}).value();
    REQUIRE(best.summary.certificate.certified);
    // every local minimum of the distance: descents from a fine grid of starts
    std::vector<curve::CurveMinimum> minima;
    for (int i = 0; i <= 200; ++i) {
      const auto m =
          curve::descend_on_interval(helix->formulas(), helix->domain(), p, 12.566370614359172 * i / 200);
      bool seen = false;
      for (const auto& q : minima) seen = seen || std::abs(q.t - m.t) < 1e-6;
      if (!seen) minima.push_back(m);
    }
    for (const auto& m : minima) {
      const Certificate c =
          curve::certify_curve_answer(helix->cells(), helix->formulas(), helix->domain(), p, m.t);
      REQUIRE(c.computed);
      CHECK(c.lower_bound <= best.distance * (1.0 + 1e-15));
      if (m.distance > best.distance * (1.0 + 1e-6)) {
        ++worse;
        CHECK_FALSE(c.certified);
        refuted += c.reason == CertificateReason::nearer_point;
      } else {
        certified += c.certified;
      }
    }
  }
  CHECK(worse >= 6);
  CHECK(refuted == worse);
  CHECK(certified >= 4);
}

TEST_CASE("curves: a point next to a cusp on the curve is answered on the curve, not at the cusp") {
  struct Case {
    const char *x, *y;
    double t;
  };
  for (const Case& k : {Case{"t^2", "t^3", 0.01}, Case{"t^2", "t^3", -0.01}, Case{"t^2", "t^5", 0.01},
                        Case{"t^3", "t^5", 0.01}, Case{"t^3", "t^5", -0.02}}) {
    const auto g = make_curve(k.x, k.y, nullptr, -1.0, 1.0);
    const Vec3 on = g->formulas().point(k.t);
    const double p[2] = {on.x, on.y};
    const ProjectionResult r = g->project(p, "auto", Options{}).value();
    INFO(k.x << ", " << k.y << " at t = " << k.t << ": d = " << r.distance << " at t = " << r.params[0]);
    // p is the double nearest c(t): within an ulp of |p| of the curve
    CHECK(r.distance <= 4.0 * 0x1p-52 * norm(on));
    CHECK(std::abs(r.params[0] - k.t) <= 1e-9);
    CHECK(r.summary.certificate.certified);
  }
}

namespace {

// The distance from p to x = sqrt(t - 0.5), y = t over t in [0.5, 1] (where it is finite), by
// brute force on the closed form: 200,000 samples, then the best refined by a shrinking pattern
// search. Returns {t, distance}.
std::pair<double, double> brute_half_parabola(double px, double py) {
  auto d2 = [&](double t) {
    const double x = std::sqrt(t - 0.5) - px, y = t - py;
    return x * x + y * y;
  };
  double bt = 0.5, best = d2(0.5);
  constexpr int n = 200000;
  for (int i = 0; i <= n; ++i) {
    const double t = 0.5 + 0.5 * i / n, d = d2(t);
    if (d < best) best = d, bt = t;
  }
  for (double h = 0.5 / n; h > 1e-16; h *= 0.5)
    for (bool moved = true; moved;) {
      moved = false;
      for (const double step : {h, -h}) {
        const double t = std::clamp(bt + step, 0.5, 1.0), d = d2(t);
        if (d < best) best = d, bt = t, moved = true;
      }
    }
  return {bt, std::sqrt(best)};
}

}  // namespace

TEST_CASE("a curve defined on part of its domain: the nearest point of that part, certified") {
  // x = sqrt(t - 0.5) is finite for t >= 0.5 only; the same curve over [0.5, 1] for comparison
  const auto part = make_curve("sqrt(t-0.5)", "t", nullptr, 0.0, 1.0);
  const auto whole = make_curve("sqrt(t-0.5)", "t", nullptr, 0.5, 1.0);
  for (const auto& [px, py] : {std::pair{0.5, 0.7}, std::pair{0.2, 0.9}, std::pair{-1.0, 0.4},
                               std::pair{0.3, 0.1}, std::pair{1.5, 1.5}, std::pair{0.6, 0.55}}) {
    const double x = px, y = py;
    INFO("p = (" << x << ", " << y << ")");
    const double p[2] = {x, y};
    const ProjectionResult r = part->project(p, "auto", Options{}).value();
    const auto [t_ref, d_ref] = brute_half_parabola(x, y);
    CHECK(r.summary.status == Status::converged);
    CHECK(r.distance == doctest::Approx(d_ref).epsilon(1e-9));
    CHECK(r.params[0] == doctest::Approx(t_ref).epsilon(1e-6));
    CHECK(r.summary.certificate.certified);
    const ProjectionResult w = whole->project(p, "auto", Options{}).value();
    CHECK(r.distance == doctest::Approx(w.distance).epsilon(1e-12));
    CHECK(r.summary.location == w.summary.location);  // the part's end is an endpoint
  }
  // The point: distance 0.0358 at t = 0.726.
  const double p[2] = {0.5, 0.7};
  const ProjectionResult r = part->project(p, "auto", Options{}).value();
  CHECK(r.distance == doctest::Approx(0.0358).epsilon(1e-3));
  CHECK(r.params[0] == doctest::Approx(0.726).epsilon(1e-3));
  // Beyond about 1.3e154 squared distances overflow: no answer, as on a surface.
  for (const auto& c : {part, whole}) {
    const double far[2] = {1e160, 0.0};
    const ProjectionResult f = c->project(far, "auto", Options{}).value();
    CHECK(f.summary.status == Status::non_finite);
    CHECK(std::isnan(f.distance));
  }
}

TEST_CASE("a curve finite nowhere in its domain: non_finite, no answer") {
  const auto nowhere = make_curve("sqrt(-1-t^2)", "t", nullptr, 0.0, 1.0);
  const double p[2] = {0.5, 0.5};
  const ProjectionResult r = nowhere->project(p, "auto", Options{}).value();
  CHECK(r.summary.status == Status::non_finite);
  CHECK(std::isnan(r.distance));
}
