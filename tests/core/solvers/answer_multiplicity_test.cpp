// The one multiplicity rule of auto's answers (solvers/answer_multiplicity.hpp): the tie rule on
// distances and feet worked out by hand, the continuum's conditions, and auto on each of the four
// geometries that use it, at points whose nearest points are known: the centre of a circle or a
// sphere (every point is nearest), the centre of an ellipse or an ellipsoid with semi-axes 2, 1
// (its two nearest points (0, ±1, 0), at distance 1), a point off the centre (one nearest point).
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "compiled/compiled_geometry.hpp"
#include "solvers/answer_multiplicity.hpp"

using namespace footpoint;

namespace {

ProjectionResult answer_at(Vec3 foot, double distance) {
  ProjectionResult r;
  r.foot = {foot.x, foot.y, foot.z};
  r.distance = distance;
  r.summary.location = Location::interior;
  return r;
}

struct Item {
  Vec3 foot;
  double distance;
};

std::shared_ptr<const CompiledGeometry> compile(
    GeometryType type, std::vector<formula::NamedFormula> formulas,
    std::vector<std::pair<std::string, std::array<double, 2>>> domain,
    std::vector<std::string> periodic = {}) {
  GeometryDefinition def;
  def.type = type;
  def.formulas = std::move(formulas);
  def.domain = std::move(domain);
  def.periodic = std::move(periodic);
  return compile_geometry(def);
}

AnswerMultiplicity auto_multiplicity(const CompiledGeometry& g, std::array<double, 3> p) {
  const ProjectionResult r = g.project(p.data(), "auto", {}).value();
  CHECK(r.summary.status == Status::converged);
  return r.summary.multiplicity;
}

// The two nearest points (0, ±1, 0) of an ellipse or ellipsoid with semi-axes 2, 1 (, 1/2) from
// its centre, in either order.
void check_two_feet(const AnswerMultiplicity& m) {
  CHECK(m.computed);
  REQUIRE(m.kind == Multiplicity::tied);
  CHECK(m.count == 2);
  REQUIRE(m.feet.size() == 2);
  CHECK(std::abs(m.feet[0][1] * m.feet[1][1] + 1.0) <= 1e-12);
  for (const auto& f : m.feet) {
    CHECK(std::abs(f[0]) <= 1e-12);
    CHECK(std::abs(f[2]) <= 1e-12);
  }
}

}  // namespace

TEST_CASE("a distance ties within the certificate's gap of the answer's") {
  // d = 1 at a foot of size 1 from p = 0: the gap is max(1e-9 d, 512 u) = 1e-9
  const ProjectionResult r = answer_at({1, 0, 0}, 1.0);
  const TiedFeet ties(r, {0, 0, 0}, {1, 0, 0});
  CHECK(ties.gap() == 1e-9);
  CHECK(ties.ties(1.0 + 0.9e-9));
  CHECK(ties.ties(1.0 - 0.9e-9));
  CHECK_FALSE(ties.ties(1.0 + 1.1e-9));
  CHECK_FALSE(ties.ties(std::nan("")));
  // at d = 0 the absolute gap 512 u max|coordinate| of p and the foot: 512 * 2^-53 * 4
  const TiedFeet at_zero(answer_at({4, 0, 0}, 0.0), {4, 0, 0}, {4, 0, 0});
  CHECK(at_zero.gap() == 2048.0 * 0x1p-53);
}

TEST_CASE("tied feet are told apart at 1e-8 (1 + |foot|), the answer's first") {
  const ProjectionResult r = answer_at({1, 0, 0}, 1.0);
  TiedFeet ties(r, {0, 0, 0}, {1, 0, 0});
  ties.add({1, 1e-8, 0});  // 1e-8 from the answer, within 1e-8 (1 + sqrt(1 + 1e-16)): the same foot
  ties.add({0, -1, 0});
  ties.add({0, -1, 1.9e-8});  // within 2e-8 of (0, -1, 0): the same foot
  ties.add({-1, 0, 0});
  const AnswerMultiplicity m = ties.settle();
  CHECK(m.computed);
  CHECK(m.kind == Multiplicity::tied);
  CHECK(m.count == 3);
  REQUIRE(m.feet.size() == 3);
  CHECK(m.feet[0] == std::array<double, 3>{1, 0, 0});
  CHECK(m.feet[1] == std::array<double, 3>{0, -1, 0});
  CHECK(m.feet[2] == std::array<double, 3>{-1, 0, 0});
}

TEST_CASE("one foot is unique, with no list") {
  TiedFeet ties(answer_at({1, 0, 0}, 1.0), {0, 0, 0}, {1, 0, 0});
  ties.add({1, 0, 0});
  const AnswerMultiplicity m = ties.settle();
  CHECK(m.computed);
  CHECK(m.kind == Multiplicity::unique);
  CHECK(m.count == 1);
  CHECK(m.feet.empty());
}

TEST_CASE("tied_feet evaluates the feet of the items that tie only") {
  const ProjectionResult r = answer_at({1, 0, 0}, 1.0);
  const std::vector<Item> reached = {{{0, 1, 0}, 1.0}, {{0, 2, 0}, 2.0}, {{-1, 0, 0}, 1.0 + 5e-10}};
  int evaluated = 0;
  const AnswerMultiplicity m = tied_feet(r, {0, 0, 0}, reached, [&](const Item& i) {
    ++evaluated;
    return i.foot;
  });
  CHECK(evaluated == 2);
  CHECK(m.kind == Multiplicity::tied);
  CHECK(m.count == 3);
  const std::vector<ReachedFoot> feet = {{{0, 1, 0}, 1.0}, {{0, 2, 0}, 2.0}};
  const AnswerMultiplicity n = tied_feet(r, {0, 0, 0}, feet);
  CHECK(n.kind == Multiplicity::tied);
  CHECK(n.count == 2);
}

TEST_CASE("a continuum needs an interior foot, p off the geometry and a flat distance") {
  const std::vector<Item> reached = {{{-1, 0, 0}, 1.0}};
  const auto foot = [](const Item& i) { return i.foot; };
  int asked = 0;
  const auto flat = [&] {
    ++asked;
    return true;
  };
  ProjectionResult r = answer_at({1, 0, 0}, 1.0);
  CHECK(answer_multiplicity(r, {0, 0, 0}, flat, reached, foot).kind == Multiplicity::continuum);
  CHECK(asked == 1);
  // not flat: the ties decide
  CHECK(answer_multiplicity(
            r, {0, 0, 0}, [] { return false; }, reached, foot)
            .kind == Multiplicity::tied);
  // on an edge, or with p on the geometry, the flatness is not asked
  r.summary.location = Location::edge;
  CHECK(answer_multiplicity(r, {0, 0, 0}, flat, reached, foot).kind == Multiplicity::tied);
  r = answer_at({0, 0, 0}, 0.0);
  CHECK(answer_multiplicity(r, {0, 0, 0}, flat, std::vector<Item>{}, foot).kind == Multiplicity::unique);
  CHECK(asked == 1);
}

TEST_CASE("auto's multiplicity on a parametric curve: circle, ellipse") {
  const double pi = std::acos(-1.0);
  const auto circle = compile(GeometryType::parametric_curve, {{"x", "cos(t)"}, {"y", "sin(t)"}, {"z", "0"}},
                              {{"t", {0, 2 * pi}}}, {"t"});
  CHECK(auto_multiplicity(*circle, {0, 0, 0}).kind == Multiplicity::continuum);
  CHECK(auto_multiplicity(*circle, {0.3, 0.1, 0}).kind == Multiplicity::unique);
  const auto ellipse = compile(GeometryType::parametric_curve,
                               {{"x", "2*cos(t)"}, {"y", "sin(t)"}, {"z", "0"}}, {{"t", {0, 2 * pi}}}, {"t"});
  check_two_feet(auto_multiplicity(*ellipse, {0, 0, 0}));
}

TEST_CASE("auto's multiplicity on an implicit curve: circle, ellipse") {
  const auto circle =
      compile(GeometryType::implicit_curve, {{"equations[0]", "x^2+y^2-1"}, {"equations[1]", "z"}},
              {{"x", {-2, 2}}, {"y", {-2, 2}}, {"z", {-1, 1}}});
  CHECK(auto_multiplicity(*circle, {0, 0, 0}).kind == Multiplicity::continuum);
  CHECK(auto_multiplicity(*circle, {0.3, 0.1, 0}).kind == Multiplicity::unique);
  const auto ellipse =
      compile(GeometryType::implicit_curve, {{"equations[0]", "x^2/4+y^2-1"}, {"equations[1]", "z"}},
              {{"x", {-3, 3}}, {"y", {-2, 2}}, {"z", {-1, 1}}});
  check_two_feet(auto_multiplicity(*ellipse, {0, 0, 0}));
}

TEST_CASE("auto's multiplicity on an implicit surface: sphere, ellipsoid") {
  const auto sphere = compile(GeometryType::implicit_surface, {{"equation", "x^2+y^2+z^2-1"}},
                              {{"x", {-2, 2}}, {"y", {-2, 2}}, {"z", {-2, 2}}});
  CHECK(auto_multiplicity(*sphere, {0, 0, 0}).kind == Multiplicity::continuum);
  CHECK(auto_multiplicity(*sphere, {0.3, 0.1, 0.2}).kind == Multiplicity::unique);
  const auto ellipsoid = compile(GeometryType::implicit_surface, {{"equation", "x^2/4+y^2+4*z^2-1"}},
                                 {{"x", {-3, 3}}, {"y", {-3, 3}}, {"z", {-3, 3}}});
  // semi-axes 2, 1, 1/2: the nearest points of the centre are (0, 0, ±1/2)
  const AnswerMultiplicity m = auto_multiplicity(*ellipsoid, {0, 0, 0});
  REQUIRE(m.kind == Multiplicity::tied);
  REQUIRE(m.feet.size() == 2);
  CHECK(std::abs(m.feet[0][2] * m.feet[1][2] + 0.25) <= 1e-12);
}

TEST_CASE("auto's multiplicity on a parametric surface: sphere, ellipsoid") {
  const double pi = std::acos(-1.0);
  const auto sphere = compile(GeometryType::parametric_surface,
                              {{"x", "cos(u)*cos(v)"}, {"y", "sin(u)*cos(v)"}, {"z", "sin(v)"}},
                              {{"u", {0, 2 * pi}}, {"v", {-pi / 2, pi / 2}}}, {"u"});
  CHECK(auto_multiplicity(*sphere, {0, 0, 0}).kind == Multiplicity::continuum);
  CHECK(auto_multiplicity(*sphere, {0.3, 0.1, 0.2}).kind == Multiplicity::unique);
  const auto ellipsoid = compile(GeometryType::parametric_surface,
                                 {{"x", "2*cos(u)*cos(v)"}, {"y", "sin(u)*cos(v)"}, {"z", "2*sin(v)"}},
                                 {{"u", {0, 2 * pi}}, {"v", {-pi / 2, pi / 2}}}, {"u"});
  check_two_feet(auto_multiplicity(*ellipsoid, {0, 0, 0}));
}
