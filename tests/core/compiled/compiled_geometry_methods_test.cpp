// The method tables say what each method does (GET /v1/methods lists them): every status a method
// reports, on points near and far, with tight budgets, from far starts and under max_distance, is
// one its row lists; an option its row does not list changes none of its answers; a paper's
// method cites the paper in full.
#include <doctest/doctest.h>

#include <bit>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "compiled/compiled_geometry.hpp"
#include "sweep_length.hpp"

using namespace footpoint;

namespace {

// One geometry of each kind of table, with a point generator around it.
struct MethodTableSubject {
  const char* name;
  GeometryDefinition def;
  double radius;  // points are drawn from [-radius, radius]^dim
};

std::vector<MethodTableSubject> method_table_subjects() {
  using T = GeometryType;
  return {
      {"surface",
       {T::parametric_surface,
        {{"x", "u+v"}, {"y", "sin(u)+2*cos(v)"}, {"z", "sin(u+v)"}},
        {{"u", {-3, 3}}, {"v", {-3, 3}}},
        {},
        {}},
       5},
      {"spatial parametric curve",
       {T::parametric_curve, {{"x", "cos(t)"}, {"y", "sin(t)"}, {"z", "t/4"}}, {{"t", {0, 12}}}, {}, {}},
       3},
      {"planar parametric curve",
       {T::parametric_curve, {{"x", "3*cos(t)"}, {"y", "sin(t)"}}, {{"t", {0, 6}}}, {}, {}},
       4},
      {"planar implicit curve",
       {T::implicit_curve, {{"equations[0]", "x^2/4+y^2-1"}}, {{"x", {-3, 3}}, {"y", {-2, 2}}}, {}, {}},
       3},
      {"spatial implicit curve",
       {T::implicit_curve,
        {{"equations[0]", "x^2+y^2+z^2-4"}, {"equations[1]", "(x-1)^2+y^2-1"}},
        {{"x", {-2.5, 2.5}}, {"y", {-2.5, 2.5}}, {"z", {-2.5, 2.5}}},
        {},
        {}},
       3},
      {"implicit surface",
       {T::implicit_surface,
        {{"equation", "x^2/4+y^2+4*z^2-1"}},
        {{"x", {-3, 3}}, {"y", {-3, 3}}, {"z", {-3, 3}}},
        {},
        {}},
       3},
  };
}

// The option settings a test varies, each changing one option from its default.
struct Variant {
  std::uint32_t option;
  Options options;
  bool with_all_minima = false;  // compared with the answer under all_minima alone (max_minima)
};

std::vector<Variant> variants(int num_params, int dim) {
  std::vector<Variant> v;
  Options o;
  o.tolerance = 1e-4;
  v.push_back({option_tolerance, o});
  o = {};
  o.max_iterations = 1;
  v.push_back({option_max_iterations, o});
  o = {};
  o.initial = num_params == 2   ? std::array<double, 3>{2.5, -2.5, 0}
              : num_params == 1 ? std::array<double, 3>{5, 0, 0}
                                : std::array<double, 3>{1.5, 0.5, dim == 3 ? 1.0 : 0.0};
  v.push_back({option_initial, o});
  o = {};
  o.all_minima = true;
  v.push_back({option_all_minima, o});
  o = {};
  o.trace = true;
  v.push_back({option_trace, o});
  o = {};
  o.max_distance = 0.3;
  v.push_back({option_max_distance, o});
  o = {};
  o.all_minima = true;
  o.max_minima = 1;
  v.push_back({option_max_minima, o, true});
  return v;
}

bool same_answer(const ProjectionResult& a, const ProjectionResult& b) {
  auto same = [](double x, double y) { return x == y || (std::isnan(x) && std::isnan(y)); };
  for (int k = 0; k < 3; ++k)
    if (!same(a.foot[k], b.foot[k])) return false;
  return same(a.distance, b.distance) && a.summary.status == b.summary.status &&
         a.summary.iterations == b.summary.iterations && a.minima.size() == b.minima.size() &&
         a.trace.size() == b.trace.size();
}

}  // namespace

TEST_CASE("every status a method reports is one its row lists; an option it does not list changes nothing") {
  std::mt19937 rng(19);
  for (const auto& subject : method_table_subjects()) {
    CAPTURE(subject.name);
    const auto geometry = compile_geometry(subject.def);
    const int dim = geometry->point_dim();
    std::uniform_real_distribution<double> coordinate(-subject.radius, subject.radius);
    // (a sixth of them under AddressSanitizer: sweep_length.hpp)
    std::vector<std::array<double, 3>> points(static_cast<std::size_t>(test::sweep_length(60)));
    for (auto& p : points) p = {coordinate(rng), coordinate(rng), dim == 3 ? coordinate(rng) : 0.0};
    points.push_back({0.0, 0.0, 0.0});  // on an axis of symmetry: degenerate for some methods
    for (const MethodInfo& info : geometry->methods()) {
      CAPTURE(info.name);
      const auto method = geometry->method(info.name);
      REQUIRE(method);
      std::uint32_t seen = 0;
      for (const auto& p : points) {
        const ProjectionResult plain = method->project(p.data(), Options{});
        seen |= 1u << static_cast<unsigned>(plain.summary.status);
        Options all_minima;
        all_minima.all_minima = true;
        const ProjectionResult listing = method->project(p.data(), all_minima);
        for (const Variant& v : variants(geometry->num_params(), dim)) {
          CAPTURE(option_name(static_cast<std::uint32_t>(std::countr_zero(v.option))));
          const ProjectionResult r = method->project(p.data(), v.options);
          seen |= 1u << static_cast<unsigned>(r.summary.status);
          if (!(info.options & v.option)) CHECK(same_answer(r, v.with_all_minima ? listing : plain));
        }
      }
      std::string observed;
      for (unsigned s = 0; s < 32; ++s)
        if (seen & (1u << s)) (observed += observed.empty() ? "" : " ") += to_string(static_cast<Status>(s));
      MESSAGE(std::string(subject.name) << ", " << info.name << ": " << observed);
      for (unsigned s = 0; s < 32; ++s)
        if (seen & (1u << s)) {
          CAPTURE(to_string(static_cast<Status>(s)));
          CHECK((info.statuses & (1u << s)) != 0);
        }
      CHECK((info.statuses & statuses({Status::deadline_exceeded})) != 0);  // every method, by the batch
      CHECK((info.statuses & statuses({Status::converged})) != 0);
      // A method of a paper cites it in full; a method of our own cites nothing.
      CHECK(info.paper.empty() == info.citations[0].empty());
      if (!info.paper.empty()) CHECK(info.citations[0].size() > 60);
    }
  }
}
