// `auto`'s options and summary: all_minima against the oracle's local minima, max_distance,
// location (interior / edge / corner), the Summary fields, trace; the methods' list; failures
// reported through the status (poles, formulas undefined on part of the domain).
#include <doctest/doctest.h>

#include <cmath>
#include <stdexcept>

#include "surface_fixtures.hpp"

using namespace footpoint;
using namespace footpoint::test;

namespace {
std::shared_ptr<const ParametricSurface> from_case(const nlohmann::json& c) {
  const auto& f = c.at("formulas");
  return make_surface(f.at("x"), f.at("y"), f.at("z"), c.at("domain").at("u").get<std::array<double, 2>>(),
                      c.at("domain").at("v").get<std::array<double, 2>>());
}
}  // namespace

TEST_CASE("all_minima finds every local minimum the oracle lists, best first, told apart by foot point") {
  const nlohmann::json cases = read_json(FOOTPOINT_CASES_FILE);
  for (const auto& c : cases.at("cases")) {
    if (c.at("kind") != "surface") continue;
    SUBCASE(c.at("id").get<std::string>().c_str()) {
      const auto g = from_case(c);
      const auto& point = c.at("points").at(0);
      Options o;
      o.all_minima = true;
      const ProjectionResult r = project(*g, point.at("p").get<std::array<double, 3>>(), "auto", o);
      REQUIRE(!r.minima.empty());
      CHECK(r.minima.front().distance == doctest::Approx(r.distance).epsilon(1e-15));
      for (std::size_t i = 1; i < r.minima.size(); ++i) {
        CHECK(r.minima[i - 1].distance <= r.minima[i].distance);
        CHECK(dist3(r.minima[i - 1].foot, r.minima[i].foot) > 1e-8);
      }
      for (const auto& m : point.at("oracle").at("local_minima")) {
        const double d = m.at("distance").get<double>();
        const auto foot = m.at("foot").get<std::array<double, 3>>();
        INFO("oracle minimum d = " << d << " (" << m.at("type").get<std::string>() << ")");
        bool found = false;
        for (const Minimum& ours : r.minima)
          if (std::abs(ours.distance - d) <= 1e-10 * std::max(1.0, d) &&
              dist3(ours.foot, foot) <= 1e-8 * std::max(1.0, d)) {
            found = true;
            CHECK(m.at("type").get<std::string>().rfind(to_string(ours.location), 0) == 0);
          }
        CHECK(found);
      }
    }
  }
}

TEST_CASE("location and on_boundary: corner (C3), edge (C4), interior (C2)") {
  const auto c3 = make_surface("u", "v", "cos(u+v)", {0, 2}, {0, 2});
  const auto c4 = make_surface("u", "v", "sin(u^2+v^2)", {0, 2}, {0, 2});
  const auto c2 = make_surface("u", "v", "sin(u+v)", {0, 2}, {0, 2});
  const ProjectionResult r3 = project(*c3, {4, 5, 6}, "auto");
  const ProjectionResult r4 = project(*c4, {4, 5, 6}, "auto");
  const ProjectionResult r2 = project(*c2, {3, 4, 5}, "auto");
  CHECK(r3.summary.location == Location::corner);
  CHECK(r3.summary.on_boundary);
  CHECK(r3.params == std::array<double, 2>{2.0, 2.0});
  CHECK(r4.summary.location == Location::edge);
  CHECK(r4.summary.on_boundary);
  CHECK(r4.params[1] == 2.0);
  CHECK(r2.summary.location == Location::interior);
  CHECK_FALSE(r2.summary.on_boundary);
  // The residuals are the KKT conditions': along a free direction the orthogonality, across a held
  // bound only a wrong sign of its multiplier; at these right answers all vanish.
  CHECK(r3.summary.orthogonality[0] <= 1e-14);
  CHECK(r3.summary.orthogonality[1] <= 1e-14);
  CHECK(r4.summary.orthogonality[0] < 1e-14);
  CHECK(r4.summary.orthogonality[1] <= 1e-14);
}

TEST_CASE("Summary fields of auto and of the papers' methods") {
  const auto g = make_surface("u", "v", "sin(u+v)", {0, 2}, {0, 2});
  const ProjectionResult a = project(*g, {3, 4, 5}, "auto");
  CHECK(a.summary.method == "auto");
  CHECK(a.summary.status == Status::converged);
  CHECK(a.summary.starts >= 1);
  CHECK(a.summary.iterations >= 1);
  CHECK(std::isfinite(a.summary.step_norm));
  CHECK(a.summary.orthogonality[0] < 1e-14);
  CHECK(a.summary.orthogonality[1] < 1e-14);
  CHECK(a.summary.residual() < 1e-14);
  CHECK(a.dim == 3);
  CHECK(a.num_params == 2);
  CHECK(a.trace.empty());
  CHECK(a.minima.empty());
  for (const char* m : {"gsa", "first_order", "hybrid", "newton"}) {
    const ProjectionResult r = project(*g, {3, 4, 5}, m, start_at(0.6, 1.6));
    CHECK(r.summary.method == m);
    CHECK(r.summary.starts == 1);
    CHECK(r.summary.iterations >= 1);
  }
  // without a start the methods of [GSA] and [Hybrid] start from the domain's centre (1, 1): hybrid converges
  const ProjectionResult h = project(*g, {3, 4, 5}, "hybrid");
  CHECK(h.summary.status == Status::converged);
  CHECK(h.params[0] == doctest::Approx(0.5921398354615897).epsilon(1e-12));
  // a looser tolerance stops earlier
  Options loose;
  loose.tolerance = 1e-6;
  loose.initial = std::array<double, 3>{1, 1, 0};
  const ProjectionResult l = project(*g, {3, 4, 5}, "hybrid", loose);
  CHECK(l.summary.iterations <= h.summary.iterations);
  // max_iterations is honoured and reported
  Options capped = start_at(1, 1);
  capped.max_iterations = 3;
  const ProjectionResult c = project(*g, {3, 4, 5}, "first_order", capped);
  CHECK(c.summary.status == Status::max_iterations);
  CHECK(c.summary.iterations == 3);
}

TEST_CASE("auto's trace holds the steps of the local solve that gave the answer") {
  const auto g = make_surface("u+v", "sin(u)+2*cos(v)", "sin(u+v)", {-3, 3}, {-3, 3});
  Options o;
  o.trace = true;
  const ProjectionResult r = project(*g, {1, 2, 2}, "auto", o);
  CHECK(static_cast<int>(r.trace.size()) == r.summary.iterations);
  for (const auto& t : r.trace) CHECK(t[2] == 0.0);
}

TEST_CASE("max_distance: points farther than it get beyond_max_distance and no foot point, quickly") {
  const auto g = make_surface("u", "v", "cos(u+v)", {0, 2}, {0, 2});  // C3: d = 7.5677588117922
  Options o;
  o.max_distance = 8.0;
  CHECK(project(*g, {4, 5, 6}, "auto", o).summary.status == Status::converged);
  o.max_distance = 7.5;
  const ProjectionResult near_miss = project(*g, {4, 5, 6}, "auto", o);
  CHECK(near_miss.summary.status == Status::beyond_max_distance);
  CHECK(std::isnan(near_miss.distance));
  CHECK(std::isnan(near_miss.foot[0]));
  CHECK(std::isnan(near_miss.params[0]));
  // the certificate says that no point is within max_distance
  const Certificate& c = near_miss.summary.certificate;
  CHECK(c.certified);
  CHECK(Certificate::meets_gap(7.5, c.lower_bound, c.absolute_gap));
  // far beyond: every cell's box is farther, so no local solve at all
  o.max_distance = 1.0;
  const ProjectionResult far = project(*g, {400, 500, 600}, "auto", o);
  CHECK(far.summary.status == Status::beyond_max_distance);
  CHECK(far.summary.starts == 0);
  CHECK(std::isnan(far.distance));
}

TEST_CASE("methods(), and an unknown method") {
  const auto g = make_surface("u", "v", "0", {0, 1}, {0, 1});
  std::vector<std::string> names;
  for (const MethodInfo& m : g->methods()) {
    names.emplace_back(m.name);
    CHECK(!m.description.empty());
  }
  CHECK(names == std::vector<std::string>{"auto", "gsa", "first_order", "hybrid", "newton"});
  CHECK(g->method("gsa").has_value());
  CHECK(g->method("gsa")->info().name == "gsa");
  // An unknown name is an error value naming the methods there are, not an exception.
  const std::array<double, 3> p{0, 0, 1};
  const auto unknown = g->project(p.data(), "bisection", {});
  REQUIRE(!unknown.has_value());
  CHECK(unknown.error().message ==
        "unknown method 'bisection' for a parametric_surface (auto, gsa, first_order, hybrid, newton)");
  CHECK(!g->method("").has_value());
  CHECK(g->point_dim() == 3);
  CHECK(g->num_params() == 2);
  CHECK(g->memory_bytes() > sizeof(ParametricSurface));
}

TEST_CASE("failures are reported through the status") {
  const auto sphere = make_surface("cos(u)*cos(v)", "sin(u)*cos(v)", "sin(v)", {0, 6.283185307179586},
                                   {-1.5707963267948966, 1.5707963267948966});
  // GSA and the first-order method need s_u x s_v, which vanishes at a cone's apex (v = 0)
  const auto cone = make_surface("v*cos(u)", "v*sin(u)", "v", {0, 6.283185307179586}, {0, 1});
  for (const char* m : {"gsa", "first_order"}) {
    const ProjectionResult apex = project(*cone, {0.1, 0.2, -1}, m, start_at(1.0, 0.0));
    CHECK(apex.summary.status == Status::degenerate);
    CHECK(apex.distance == doctest::Approx(std::sqrt(1.05)).epsilon(1e-15));
  }
  // auto: the apex is the nearest point (a corner of the parameter domain in v, any u)
  const ProjectionResult ca = project(*cone, {0.1, 0.2, -1}, "auto");
  CHECK(ca.summary.status == Status::converged);
  CHECK(ca.distance == doctest::Approx(std::sqrt(1.05)).epsilon(1e-14));
  // auto is right at the pole: the nearest point of the sphere to (0, 0, 2) is (0, 0, 1)
  const ProjectionResult a = project(*sphere, {0, 0, 2}, "auto");
  CHECK(a.summary.status == Status::converged);
  CHECK(a.distance == doctest::Approx(1.0).epsilon(1e-14));
  CHECK(a.params[1] == 1.5707963267948966);

  // z = sqrt(u) is undefined for u < 0: auto answers from the part where it is defined
  const auto half = make_surface("u", "v", "sqrt(u)", {-1, 1}, {-1, 1});
  const ProjectionResult h = project(*half, {0.5, 0.25, 2}, "auto");
  CHECK(h.summary.status == Status::converged);
  CHECK(std::isfinite(h.distance));
  CHECK(h.params[0] >= 0.0);
  // a paper method started where the formulas are undefined says so
  const ProjectionResult n = project(*half, {0.5, 0.25, 2}, "newton", start_at(-0.5, 0));
  CHECK(n.summary.status == Status::non_finite);
}
