// implicit/solvers/paper_iteration: the loop of the spatial-curve paper's methods and the result it
// ends in, driven by maps whose behaviour is known (a contraction to a chosen point, a blow-up, a
// NaN, no step), on the circle of implicit_fixtures.hpp.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "implicit/solvers/paper_iteration.hpp"
#include "implicit_fixtures.hpp"

using namespace footpoint;
using namespace footpoint::test;
using curve::Landing;
using curve::PaperGoal;

namespace {

const Vec3 kPaperPoint{3.0, 1.0, 2.0};
const Box3 kBox{{-3, -3, -3}, {3, 3, 3}};

// X_{n+1} = X_n + (target - X_n) / 2.
auto halfway_to(Vec3 target) {
  return [target](Vec3 x, Vec3& x1) {
    x1 = x + 0.5 * (target - x);
    return true;
  };
}

curve::IterationControl control(int max_iterations, std::vector<std::array<double, 3>>* trace = nullptr) {
  curve::IterationControl c = curve::make_control(Options{}, max_iterations, nullptr);
  c.trace = trace;
  return c;
}

}  // namespace

TEST_CASE("paper_start: P - (0.1, 0.1, 0.1), in the plane for planar curves, or options.initial") {
  const Vec3 s = curve::paper_start({1, 2, 3}, Options{}, false);
  CHECK(norm(s - Vec3{0.9, 1.9, 2.9}) == 0.0);
  CHECK(norm(curve::paper_start({1, 2, 0}, Options{}, true) - Vec3{0.9, 1.9, 0.0}) == 0.0);
  Options o;
  o.initial = std::array<double, 3>{4, 5, 6};
  CHECK(norm(curve::paper_start({1, 2, 3}, o, true) - Vec3{4, 5, 0}) == 0.0);
}

TEST_CASE("iterate_paper_map: a contraction to the foot point converges there, every increment traced") {
  const Vec3 foot = circle_foot(kPaperPoint);
  const Vec3 x0 = circle_point(std::atan2(kPaperPoint.y, kPaperPoint.x) + 0.2);
  std::vector<std::array<double, 3>> trace;
  const Landing l = curve::iterate_paper_map(circle(), PaperGoal::foot_of(kPaperPoint), x0, 1e12,
                                             control(1000, &trace), halfway_to(foot));
  CHECK(l.status == Status::converged);
  CHECK(norm(l.x - foot) <= 1e-15 * 4);
  CHECK(l.iterations == static_cast<int>(trace.size()));
  CHECK(l.iterations < 70);  // halving from ~0.35 to the last bits: ~55 steps
  Vec3 x = x0;
  for (const auto& t : trace) x += Vec3{t[0], t[1], t[2]};
  CHECK(norm(x - l.x) <= 1e-15 * 4);
  CHECK(l.step == doctest::Approx(norm(Vec3{trace.back()[0], trace.back()[1], trace.back()[2]})));
}

TEST_CASE("iterate_paper_map: the goal decides where a settled iteration may stop") {
  // A contraction to a point of the circle that is not p's foot: on the curve, not orthogonal.
  const Vec3 target = circle_point(1.0);
  const Landing on = curve::iterate_paper_map(circle(), PaperGoal::on_curve(), circle_point(1.3), 1e12,
                                              control(1000), halfway_to(target));
  CHECK(on.status == Status::converged);
  const Landing foot = curve::iterate_paper_map(circle(), PaperGoal::foot_of(kPaperPoint), circle_point(1.3),
                                                1e12, control(300), halfway_to(target));
  CHECK(foot.status == Status::max_iterations);  // it stopped moving, but is no foot point
  CHECK(foot.iterations == 300);
}

TEST_CASE("iterate_paper_map: divergence, NaN, no step, and a test before the step end the loop") {
  const ImplicitEquations eq = circle();
  const Vec3 x0 = circle_point(0.5);
  const Landing far = curve::iterate_paper_map(eq, PaperGoal::foot_of(kPaperPoint), x0, 1e3, control(1000),
                                               [](Vec3 x, Vec3& x1) {
                                                 x1 = 2.0 * x;
                                                 return true;
                                               });
  CHECK(far.status == Status::diverged);
  CHECK(norm(far.x) > 1e3);
  CHECK(far.iterations == 9);  // |x0| = 2: 2^9 * 2 > 1000 first at the 9th step
  const Landing nan = curve::iterate_paper_map(eq, PaperGoal::foot_of(kPaperPoint), x0, 1e12, control(1000),
                                               [](Vec3, Vec3& x1) {
                                                 x1 = Vec3{std::numeric_limits<double>::quiet_NaN(), 0, 0};
                                                 return true;
                                               });
  CHECK(nan.status == Status::non_finite);
  CHECK(norm(nan.x - x0) == 0.0);  // the non-finite iterate is not taken
  const Landing none = curve::iterate_paper_map(eq, PaperGoal::foot_of(kPaperPoint), x0, 1e12, control(1000),
                                                [](Vec3, Vec3&) { return false; });
  CHECK(none.status == Status::degenerate);
  CHECK(none.iterations == 0);
  struct StopAtOnce {
    std::optional<Status> stop_before(Vec3) const { return Status::converged; }
    bool operator()(Vec3, Vec3&) const { return false; }
  };
  const Landing stopped =
      curve::iterate_paper_map(eq, PaperGoal::on_curve(), x0, 1e12, control(1000), StopAtOnce{});
  CHECK(stopped.status == Status::converged);
  CHECK(stopped.iterations == 0);
}

TEST_CASE("paper_result: converged only for a foot point in the box; on the curve alone is not_orthogonal") {
  const ImplicitEquations eq = circle();
  const curve::IterationControl c = control(100);
  const Landing at_foot{circle_foot(kPaperPoint), 12, 1e-16, Status::converged};
  const ProjectionResult r = curve::paper_result(eq, kBox, kPaperPoint, "simplified", at_foot, c,
                                                 PaperGoal::foot_of(kPaperPoint), {{1, 2, 3}});
  CHECK(r.summary.status == Status::converged);
  CHECK(r.summary.method == "simplified");
  CHECK(r.summary.iterations == 12);
  CHECK(r.summary.step_norm == 1e-16);
  CHECK(r.trace.size() == 1);
  CHECK(r.distance == doctest::Approx(norm(kPaperPoint - circle_foot(kPaperPoint))).epsilon(1e-15));

  const Landing on_curve{circle_point(1.0), 3, 0.0, Status::converged};
  CHECK(curve::paper_result(eq, kBox, kPaperPoint, "steepest_descent", on_curve, c, PaperGoal::on_curve(), {})
            .summary.status == Status::not_orthogonal);
  CHECK(curve::paper_result(eq, kBox, kPaperPoint, "simplified", on_curve, c, PaperGoal::foot_of(kPaperPoint),
                            {})
            .summary.status == Status::degenerate);
  const Box3 small{{-1, -1, -3}, {1, 1, 3}};  // the foot point (x = 1.64) lies outside it
  CHECK(curve::paper_result(eq, small, kPaperPoint, "simplified", at_foot, c, PaperGoal::foot_of(kPaperPoint),
                            {})
            .summary.status == Status::outside_domain);
  curve::IterationControl near = c;
  near.max_distance = 0.5;
  CHECK(curve::paper_result(eq, kBox, kPaperPoint, "simplified", at_foot, near,
                            PaperGoal::foot_of(kPaperPoint), {})
            .summary.status == Status::beyond_max_distance);
  const Landing spent{circle_foot(kPaperPoint), 100, 1e-3, Status::max_iterations};
  CHECK(
      curve::paper_result(eq, kBox, kPaperPoint, "simplified", spent, c, PaperGoal::foot_of(kPaperPoint), {})
          .summary.status == Status::max_iterations);
}
