// The unit normal at the foot and the signed distance (ProjectionResult::normal, signed_distance)
// against closed forms: a sphere (s_u x s_v points inwards for this parametrisation, so the signed
// distance is R - |p|), a tilted plane (n = (-a, -b, 1) / sqrt(1 + a^2 + b^2), the signed distance
// (z - a x - b y) / sqrt(1 + a^2 + b^2)), a circle as an implicit curve (grad f = 2 (x, y) points
// outwards: |p| - 1) and as a parametric curve ((-y', x') points inwards: 1 - |p|); none on a space
// curve or at a singular point. Then the batch statistics of deviations (batch/deviation.hpp) on
// values whose count, extremes, mean, RMS, histogram and band are counted by hand.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "batch/batch.hpp"
#include "batch/deviation.hpp"
#include "batch/thread_pool.hpp"
#include "compile_definition.hpp"
#include "compiled/compiled_geometry.hpp"

using namespace footpoint;

namespace {

ProjectionResult project_auto(const CompiledGeometry& g, std::array<double, 3> p) {
  return g.project(p.data(), "auto", {}).value();
}

}  // namespace

TEST_CASE("deviation: the sphere's normal is -foot/R and the signed distance R - |p|") {
  const double pi = std::acos(-1.0);
  const auto sphere =
      test::compile_definition(GeometryType::parametric_surface,
                               {{"x", "2*sin(v)*cos(u)"}, {"y", "2*sin(v)*sin(u)"}, {"z", "2*cos(v)"}},
                               {{"u", {0, 2 * pi}}, {"v", {0, pi}}});
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> angle(0.3, 2.8), radius(0.5, 3.5);
  for (int i = 0; i < 40; ++i) {
    const double u = angle(rng) * 2, v = angle(rng), r = radius(rng);
    const std::array<double, 3> p{r * std::sin(v) * std::cos(u), r * std::sin(v) * std::sin(u),
                                  r * std::cos(v)};
    const ProjectionResult res = project_auto(*sphere, p);
    INFO("point " << p[0] << " " << p[1] << " " << p[2]);
    REQUIRE(res.summary.status == Status::converged);
    REQUIRE(res.has_normal());
    for (int k = 0; k < 3; ++k) CHECK(res.normal[k] == doctest::Approx(-p[k] / r).epsilon(1e-12));
    CHECK(res.signed_distance == doctest::Approx(2.0 - r).epsilon(1e-12));
  }
}

TEST_CASE("deviation: a tilted plane's normal and signed distance") {
  const double a = 0.5, b = -0.25, s = std::sqrt(1 + a * a + b * b);
  const auto plane = test::compile_definition(GeometryType::parametric_surface,
                                              {{"x", "u"}, {"y", "v"}, {"z", "0.5*u-0.25*v"}},
                                              {{"u", {-10, 10}}, {"v", {-10, 10}}});
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> c(-3, 3);
  for (int i = 0; i < 40; ++i) {
    const std::array<double, 3> p{c(rng), c(rng), c(rng)};
    const ProjectionResult res = project_auto(*plane, p);
    REQUIRE(res.has_normal());
    CHECK(res.normal[0] == doctest::Approx(-a / s).epsilon(1e-14));
    CHECK(res.normal[1] == doctest::Approx(-b / s).epsilon(1e-14));
    CHECK(res.normal[2] == doctest::Approx(1 / s).epsilon(1e-14));
    CHECK(res.signed_distance == doctest::Approx((p[2] - a * p[0] - b * p[1]) / s).epsilon(1e-12));
  }
}

TEST_CASE("deviation: a circle, implicit (outward gradient) and parametric (turned tangent, inward)") {
  const double pi = std::acos(-1.0);
  const auto implicit = test::compile_definition(
      GeometryType::implicit_curve, {{"equations[0]", "x^2+y^2-1"}}, {{"x", {-2, 2}}, {"y", {-2, 2}}});
  const auto parametric = test::compile_definition(GeometryType::parametric_curve,
                                                   {{"x", "cos(t)"}, {"y", "sin(t)"}}, {{"t", {0, 2 * pi}}});
  for (const double r : {0.25, 0.9, 1.0, 1.3, 1.9}) {
    for (const double theta : {0.1, 1.7, 3.0, 4.4, 5.9}) {
      const std::array<double, 3> p{r * std::cos(theta), r * std::sin(theta), 0};
      INFO("r " << r << " theta " << theta);
      const ProjectionResult f = project_auto(*implicit, p);
      REQUIRE(f.has_normal());
      CHECK(f.normal[0] == doctest::Approx(std::cos(theta)).epsilon(1e-12));
      CHECK(f.normal[1] == doctest::Approx(std::sin(theta)).epsilon(1e-12));
      CHECK(f.signed_distance == doctest::Approx(r - 1).epsilon(1e-12));
      const ProjectionResult c = project_auto(*parametric, p);
      REQUIRE(c.has_normal());
      CHECK(c.normal[0] == doctest::Approx(-std::cos(theta)).epsilon(1e-12));
      CHECK(c.normal[1] == doctest::Approx(-std::sin(theta)).epsilon(1e-12));
      CHECK(c.signed_distance == doctest::Approx(1 - r).epsilon(1e-12));
    }
  }
}

TEST_CASE("deviation: no normal on a space curve, at a singular point or without an answer") {
  const auto helix = test::compile_definition(
      GeometryType::parametric_curve, {{"x", "cos(t)"}, {"y", "sin(t)"}, {"z", "t/4"}}, {{"t", {0, 12}}});
  const ProjectionResult h = project_auto(*helix, {2, 0.5, 1});
  CHECK(std::isfinite(h.distance));
  CHECK_FALSE(h.has_normal());
  CHECK(std::isnan(h.signed_distance));

  // Bernoulli's lemniscate: its node at the origin is a singular point of the curve.
  const auto lemniscate =
      test::compile_definition(GeometryType::implicit_curve, {{"equations[0]", "(x^2+y^2)^2-2*(x^2-y^2)"}},
                               {{"x", {-2, 2}}, {"y", {-2, 2}}});
  const ProjectionResult node = project_auto(*lemniscate, {0, 0, 0});
  INFO("location " << to_string(node.summary.location));
  CHECK(node.distance < 1e-12);
  CHECK_FALSE(node.has_normal());
  CHECK(std::isnan(node.signed_distance));

  Options far;
  far.max_distance = 0.1;
  const auto sphere_far =
      test::compile_definition(GeometryType::parametric_surface, {{"x", "u"}, {"y", "v"}, {"z", "0"}},
                               {{"u", {-1, 1}}, {"v", {-1, 1}}});
  const std::array<double, 3> p{0, 0, 5};
  const ProjectionResult beyond = sphere_far->project(p.data(), "auto", far).value();
  CHECK(beyond.summary.status == Status::beyond_max_distance);
  CHECK_FALSE(beyond.has_normal());
}

TEST_CASE("deviation: a batch keeps the normals, and its statistics are the closed form's") {
  // Points at signed distances -0.3 + 0.1 k (k = 0..6) from the plane z = 0 over [-1, 1]^2.
  const auto plane =
      test::compile_definition(GeometryType::parametric_surface, {{"x", "u"}, {"y", "v"}, {"z", "0"}},
                               {{"u", {-1, 1}}, {"v", {-1, 1}}});
  std::vector<double> points;
  std::vector<double> expected;
  for (int k = 0; k < 7; ++k) {
    const double d = -0.3 + 0.1 * k;
    points.insert(points.end(), {0.1 * k - 0.3, 0.05 * k, d});
    expected.push_back(d);
  }
  ThreadPool pool(2);
  BatchRequest request{plane->method("auto").value()};
  request.points = points.data();
  request.count = expected.size();
  const std::vector<ProjectionResult> results = project_batch(pool, request);
  for (std::size_t i = 0; i < results.size(); ++i)
    CHECK(results[i].signed_distance == doctest::Approx(expected[i]).epsilon(1e-12));

  DeviationOptions options;
  options.histogram_bins = 3;
  options.tolerance_band = std::array<double, 2>{-0.15, 0.25};
  const DeviationStats s = deviation_stats(results, options);
  CHECK(s.count == 7);
  CHECK(s.signed_count == 7);
  CHECK(s.min == doctest::Approx(-0.3));
  CHECK(s.max == doctest::Approx(0.3));
  CHECK(std::fabs(s.mean) < 1e-15);
  CHECK(s.rms == doctest::Approx(std::sqrt(0.28 / 7)));  // (0.09 + 0.04 + 0.01) * 2 / 7
  REQUIRE(s.edges.size() == 4);
  CHECK(s.edges[1] == doctest::Approx(-0.1));
  CHECK(s.edges[2] == doctest::Approx(0.1));
  // [-0.3, -0.1): -0.3, -0.2; [-0.1, 0.1): -0.1 (at the edge, rounded either side), 0, 0.1 may sit
  // on the next edge: the counts add up and the outer bins hold two each.
  CHECK(s.counts[0] + s.counts[1] + s.counts[2] == 7);
  CHECK(s.counts[0] >= 2);
  CHECK(s.counts[2] >= 2);
  CHECK(s.within_band == 4);  // -0.1, 0, 0.1, 0.2
}

TEST_CASE("deviation: unsigned distances count where no normal is, points without an answer do not") {
  std::vector<ProjectionResult> results(5);
  results[0].distance = 0.5;  // a space curve's: no normal, counted unsigned
  results[1].distance = 0.25;
  results[1].signed_distance = -0.25;
  results[1].normal = {0, 0, 1};
  results[2].distance = 1.0;
  results[2].signed_distance = 1.0;
  results[2].normal = {0, 0, 1};
  // results[3], results[4]: no answer (NaN distance)
  DeviationOptions options;
  options.histogram_bins = 5;
  const DeviationStats s = deviation_stats(results, options);
  CHECK(s.count == 3);
  CHECK(s.signed_count == 2);
  CHECK(s.min == -0.25);
  CHECK(s.max == 1.0);
  CHECK(s.mean == doctest::Approx((0.5 - 0.25 + 1.0) / 3));
  CHECK(s.rms == doctest::Approx(std::sqrt((0.25 + 0.0625 + 1.0) / 3)));
  // edges -0.25, 0, 0.25, 0.5, 0.75, 1: -0.25 in bin 0, 0.5 in bin 3, 1 (the closed end) in bin 4
  CHECK(s.counts == std::vector<std::size_t>{1, 0, 0, 1, 1});
  CHECK(deviation_stats({}, options).count == 0);
  // all equal: one bin of width 0
  const DeviationStats one = deviation_stats({results[2]}, options);
  CHECK(one.edges == std::vector<double>{1.0, 1.0});
  CHECK(one.counts == std::vector<std::size_t>{1});
}

TEST_CASE(
    "deviation: one pass over many deviations keeps the moments exact and the histogram within its "
    "resolution") {
  // 300,000 deviations that start in [-0.01, 0.01] and reach out to [-3, 5] later (the fine
  // range widens both ways several times), against counts made here from the edges.
  const std::size_t n = 300000;
  std::vector<double> values(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) / n;
    const double reach = 0.01 + (t < 0.5 ? 0.0 : 8.0 * (t - 0.5) * (t - 0.5) * 4.0);
    const double s = std::sin(12.9898 * static_cast<double>(i));
    values[i] = s >= 0 ? s * reach * 1.25 : s * reach * 0.75;
  }
  for (const int bins : {1, 7, 20, 500}) {
    DeviationOptions options;
    options.histogram_bins = bins;
    options.tolerance_band = std::array<double, 2>{-0.5, 0.25};
    DeviationAccumulator a(options);
    for (std::size_t i = 0; i < n; ++i) a.add(values[i], i % 3 != 0);
    const DeviationStats s = a.stats();
    double lo = values[0], hi = values[0], sum = 0, squares = 0;
    std::size_t band = 0;
    for (const double d : values) {
      lo = std::min(lo, d);
      hi = std::max(hi, d);
      sum += d;
      squares += d * d;
      band += d >= -0.5 && d <= 0.25;
    }
    INFO("bins " << bins);
    CHECK(s.count == n);
    CHECK(s.signed_count == n - (n + 2) / 3);
    CHECK(s.min == lo);
    CHECK(s.max == hi);
    CHECK(s.mean == doctest::Approx(sum / n).epsilon(1e-12));
    CHECK(s.rms == doctest::Approx(std::sqrt(squares / n)).epsilon(1e-12));
    CHECK(s.within_band == band);
    REQUIRE(s.counts.size() == static_cast<std::size_t>(bins));
    // resolution: positive, and a fine bin's share of a few times [min, max] (the fine range
    // doubles from one end or the other until it holds every value)
    const double fine_bins = static_cast<double>(
        std::max(DeviationAccumulator::kMinFineBins, DeviationAccumulator::kFineBinsPerBin * bins));
    CHECK(s.histogram_resolution > 0);
    CHECK(s.histogram_resolution <= 8 * (hi - lo) / fine_bins);
    std::size_t total = 0;
    for (int k = 0; k < bins; ++k) {
      const double e0 = lo + (hi - lo) * k / bins, e1 = k + 1 == bins ? hi : lo + (hi - lo) * (k + 1) / bins;
      std::size_t exact = 0, near_edge = 0;
      for (const double d : values) {
        exact += d >= e0 && (d < e1 || (k + 1 == bins && d <= e1));
        near_edge += (k > 0 && std::fabs(d - e0) <= s.histogram_resolution) ||
                     (k + 1 < bins && std::fabs(d - e1) <= s.histogram_resolution);
      }
      INFO("bin " << k << " exact " << exact << " counted " << s.counts[k] << " near an edge " << near_edge);
      CHECK(static_cast<double>(s.counts[k]) >= static_cast<double>(exact) - static_cast<double>(near_edge));
      CHECK(static_cast<double>(s.counts[k]) <= static_cast<double>(exact) + static_cast<double>(near_edge));
      total += s.counts[k];
    }
    CHECK(total == n);
  }
  // up to kExactValues the histogram is exact: the two-pass batch statistics' counts
  std::vector<ProjectionResult> results(1000);
  DeviationOptions options;
  options.histogram_bins = 9;
  DeviationAccumulator a(options);
  for (std::size_t i = 0; i < results.size(); ++i) {
    results[i].distance = std::fabs(values[n - 1 - i]);
    results[i].signed_distance = values[n - 1 - i];
    a.add(results[i]);
  }
  const DeviationStats one_pass = a.stats(), two_pass = deviation_stats(results, options);
  CHECK(one_pass.histogram_resolution == 0);
  CHECK(one_pass.counts == two_pass.counts);
  CHECK(one_pass.edges == two_pass.edges);
}
