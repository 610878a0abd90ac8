// implicit/seeding/curve_arc_samples: the samples along the proved arcs, linked into the curve's pieces.
// Checked against the curves' parametrisations: the pieces (a circle is one loop, two circles two,
// the box-clipped circle one path between its exact face crossings, Viviani's curve two paths
// between the four ends next to its double point); every sample on the curve; every link at most
// max_step long with tangents (worked out by hand) turning at most max_turn; every point of the
// curve within half an arc of a sample, so within 0.5005 max_step (an arc turning by at most 0.15
// rad is at most 0.1 % longer than its chord); the thinning keeps far fewer samples than the
// cells' crossings; a past deadline stops it.
#include <doctest/doctest.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "closed_form_curves.hpp"
#include "geometry/geometry_error.hpp"
#include "implicit/seeding/curve_arc_samples.hpp"
#include "implicit_fixtures.hpp"

using namespace footpoint;
using namespace footpoint::test;

namespace curve_arc_samples_test {

const Box3 kPlane{{-2, -2, 0}, {2, 2, 0}};
const Box3 kSpace{{-3, -3, -3}, {3, 3, 3}};

struct Sampled {
  CurveCells cells;
  CurveSamples samples;
  ArcPieces pieces;
};

Sampled sample(const ImplicitEquations& eq, const Box3& box, double max_step) {
  Sampled s;
  s.cells = subdivided_cells(eq, box);
  CompileBudget budget;
  s.pieces = sample_proved_arcs(eq, box, s.cells, {max_step}, s.samples, budget);
  return s;
}

// The points among `points` farther than `reach` from every sample.
int uncovered(const CurveSamples& s, const std::vector<Vec3>& points, double reach) {
  int out = 0;
  for (const Vec3& x : points) {
    double d = std::numeric_limits<double>::infinity();
    for (const Vec3& y : s.points) d = std::min(d, norm(x - y));
    out += d > reach;
  }
  return out;
}

// The links longer than max_step or whose unit tangents (tangent(x), by hand) turn by more than
// max_turn; and the links that are not mutual (prev of next).
int bad_links(const CurveSamples& s, const ArcSampling& settings, Vec3 (*tangent)(Vec3)) {
  int bad = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const std::int32_t n = s.next[i];
    if (n < 0) continue;
    const Vec3 a = s.points[i], b = s.points[static_cast<std::size_t>(n)];
    const Vec3 ta = tangent(a), tb = tangent(b);
    const double turn = std::acos(std::min(1.0, std::fabs(dot(ta, tb)) / (norm(ta) * norm(tb))));
    bad += norm(b - a) > settings.max_step || turn > settings.max_turn + 1e-12 ||
           s.prev[static_cast<std::size_t>(n)] != static_cast<std::int32_t>(i);
  }
  return bad;
}

std::vector<Vec3> points_of(const ParamCurve& curve, const Box3& box, int n) {
  std::vector<Vec3> out;
  for (int i = 0; i < n; ++i) {
    const Vec3 x = curve.c(curve.t0 + (curve.t1 - curve.t0) * i / n);
    if (box.contains(x)) out.push_back(x);
  }
  return out;
}

// The pieces, loops, box-face ends and ends next to unproved boxes counted.
void check_pieces(const ArcPieces& got, int pieces, int closed, int face_crossings, int open_ends) {
  CHECK(got.pieces == pieces);
  CHECK(got.closed == closed);
  CHECK(got.face_crossings == face_crossings);
  CHECK(got.open_ends == open_ends);
}

Vec3 circle_tangent(Vec3 x) { return {-x.y, x.x, 0.0}; }
// T = grad f1 x grad f2 / 4 = (-yz, z (x - 1), y) on Viviani's curve.
Vec3 viviani_tangent(Vec3 x) { return {-x.y * x.z, x.z * (x.x - 1.0), x.y}; }

TEST_CASE("sample_proved_arcs: the unit circle is one loop of samples, max_step and max_turn apart") {
  for (const double step : {0.1, 0.5}) {
    CAPTURE(step);
    const Sampled s = sample(planar_equations("x^2+y^2-1"), kPlane, step);
    check_pieces(s.pieces, 1, 1, 0, 0);
    // Following `next` from the first sample visits every sample once and comes back.
    std::size_t n = 0;
    std::int32_t i = 0;
    do {
      i = s.samples.next[static_cast<std::size_t>(i)];
      ++n;
    } while (i > 0 && n <= s.samples.size());
    CHECK(i == 0);
    CHECK(n == s.samples.size());
    int off = 0;
    for (const Vec3& x : s.samples.points) off += std::fabs(norm(x) - 1.0) > 1e-14;
    CHECK(off == 0);
    const ArcSampling settings{step};
    CHECK(bad_links(s.samples, settings, circle_tangent) == 0);
    // Every point of the circle within half the longest arc between neighbours: the limit on the
    // chord is max_step, or 2 sin(max_turn / 2) where the turn is the limit (unit curvature).
    const double chord = std::min(step, 2.0 * std::sin(0.5 * settings.max_turn));
    CHECK(uncovered(s.samples, points_of(ellipse_curve(1.0, 1.0), kPlane, 4000), 0.5005 * chord) == 0);
    // Thinned: about 2 pi / chord samples (kept chords within a tenth of the limit but where the
    // turn stops them), where the cells' crossings number ~250.
    CHECK(s.samples.size() <= 1.25 * 2.0 * std::numbers::pi / chord);
    CHECK(s.cells.crossings.size() > 3 * s.samples.size());
  }
}

TEST_CASE("sample_proved_arcs: two circles are two loops") {
  const Sampled s = sample(planar_equations("(x^2+y^2-1)*((x-3)^2+y^2-1)"), {{-2, -2, 0}, {5, 2, 0}}, 0.1);
  check_pieces(s.pieces, 2, 2, 0, 0);
  std::vector<Vec3> points = points_of(ellipse_curve(1.0, 1.0), kPlane, 2000);
  for (const Vec3& x : points_of(ellipse_curve(1.0, 1.0), kPlane, 2000)) points.push_back(x + Vec3{3, 0, 0});
  CHECK(uncovered(s.samples, points, 0.5005 * 0.1) == 0);
}

TEST_CASE("sample_proved_arcs: a circle clipped by its box is one path between its exact face crossings") {
  // x <= 0.5 cuts x^2 + y^2 = 1 at (0.5, +-sqrt 0.75): the path's two ends, samples of kind box_face.
  const Box3 box{{-2, -2, 0}, {0.5, 2, 0}};
  const Sampled s = sample(planar_equations("x^2+y^2-1"), box, 0.1);
  check_pieces(s.pieces, 1, 0, 2, 0);
  int ends = 0, faces = 0;
  for (std::size_t i = 0; i < s.samples.size(); ++i) {
    const bool end = s.samples.prev[i] < 0 || s.samples.next[i] < 0;
    const bool face = s.samples.kind[i] == SampleKind::box_face;
    ends += end;
    faces += face;
    CHECK(end == face);
    if (face) {
      CHECK(s.samples.points[i].x == 0.5);
      CHECK(std::fabs(std::fabs(s.samples.points[i].y) - std::sqrt(0.75)) <= 1e-15);
    }
  }
  CHECK(ends == 2);
  CHECK(faces == 2);
  CHECK(bad_links(s.samples, {0.1}, circle_tangent) == 0);
  CHECK(uncovered(s.samples, points_of(ellipse_curve(1.0, 1.0), box, 4000), 0.5005 * 0.1) == 0);
}

TEST_CASE("sample_proved_arcs: Viviani's curve, two paths from its double point and back") {
  // The double point (2, 0, 0) stays in unproved boxes (implicit/seeding/curve_cells): the two lobes
  // are paths whose four ends are next to it. Samples are kept close to those ends, where the
  // tangents do not tell the curvature.
  const Sampled s = sample(spatial_equations("x^2+y^2+z^2-4", "(x-1)^2+y^2-1"), kSpace, 0.2);
  check_pieces(s.pieces, 2, 0, 0, 4);
  int off = 0, ends = 0;
  for (std::size_t i = 0; i < s.samples.size(); ++i) {
    const Vec3 x = s.samples.points[i];
    off += std::fabs(norm2(x) - 4.0) > 1e-13 || std::fabs(norm2(x - Vec3{1, 0, 0}) - x.z * x.z - 1.0) > 1e-13;
    if (s.samples.prev[i] >= 0 && s.samples.next[i] >= 0) continue;
    ++ends;
    CHECK(norm(x - Vec3{2, 0, 0}) <= 2e-5);
    // Within max_step of the end: many samples, down to the scale of the end's distance.
    int near = 0;
    double length = 0.0;
    for (std::int32_t j = static_cast<std::int32_t>(i);;) {
      const std::int32_t k = s.samples.prev[i] < 0 ? s.samples.next[static_cast<std::size_t>(j)]
                                                   : s.samples.prev[static_cast<std::size_t>(j)];
      if (k < 0) break;
      length +=
          norm(s.samples.points[static_cast<std::size_t>(k)] - s.samples.points[static_cast<std::size_t>(j)]);
      if (length > 0.2) break;
      ++near;
      j = k;
    }
    CHECK(near >= 8);
  }
  CHECK(off == 0);
  CHECK(ends == 4);
  CHECK(bad_links(s.samples, {0.2}, viviani_tangent) == 0);
  CHECK(uncovered(s.samples, points_of(viviani_curve(), kSpace, 4000), 0.5005 * 0.2) == 0);
}

TEST_CASE("sample_proved_arcs: a deadline already past stops it with compile_timeout") {
  const ImplicitEquations eq = planar_equations("x^2+y^2-1");
  const CurveCells cells = subdivided_cells(eq, kPlane);
  CurveSamples samples;
  CompileBudget late(CompileBudget::clock::now() - std::chrono::seconds(1));
  try {
    sample_proved_arcs(eq, kPlane, cells, {0.01}, samples, late);
    FAIL("expected compile_timeout");
  } catch (const GeometryError& e) {
    CHECK(e.code == "compile_timeout");
  }
}

}  // namespace curve_arc_samples_test
