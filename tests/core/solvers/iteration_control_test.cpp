// solvers/iteration_control: how every method reads the Options (the surfaces' criteria
// included), how a step is classified (converged, at the rounding floor, running) and how Options
// become a control.
#include <doctest/doctest.h>

#include <vector>

#include "parametric/solvers/surface_convergence.hpp"
#include "solvers/iteration_control.hpp"

using namespace footpoint;
using curve::IterationControl;

TEST_CASE("step_tolerance and iteration_budget: the Options' values when given, else the defaults") {
  Options o;
  CHECK(step_tolerance(o) == 1e-15);
  CHECK(iteration_budget(o, 77) == 77);
  o.tolerance = -1.0;  // not given
  o.max_iterations = -3;
  CHECK(step_tolerance(o) == 1e-15);
  CHECK(iteration_budget(o, 77) == 77);
  o.tolerance = 1e-10;
  o.max_iterations = 5;
  CHECK(step_tolerance(o) == 1e-10);
  CHECK(iteration_budget(o, 77) == 5);
  // the surfaces' criteria read them so; their scale is the domain's, max(|bounds|, widths) = 5
  const ParamBox box{-2, 3, 0, 1};
  const surface::ConvergenceCriteria given = surface::convergence_criteria(o, box, 77);
  CHECK(given.tolerance == 1e-10);
  CHECK(given.max_iterations == 5);
  CHECK(given.scale == 5.0);
  const surface::ConvergenceCriteria defaults = surface::convergence_criteria(Options{}, box, 77);
  CHECK(defaults.tolerance == 1e-15);
  CHECK(defaults.max_iterations == 77);
}

TEST_CASE("progress: the step tolerance, the rounding floor that no longer shrinks, and running") {
  const IterationControl c;  // 1e-15, floor 100x
  double previous = curve::kInfinity;
  CHECK(c.progress(1e-3, 1.0, previous) == IterationControl::Progress::running);
  CHECK(previous == 1e-3);
  CHECK(c.progress(5e-14, 1.0, previous) == IterationControl::Progress::running);   // shrinking
  CHECK(c.progress(6e-14, 1.0, previous) == IterationControl::Progress::at_floor);  // not shrinking
  CHECK(c.progress(1e-15, 1.0, previous) == IterationControl::Progress::converged);
  // Relative to max(1, size): 1e-13 at size 1000 is below the tolerance 1e-12.
  previous = curve::kInfinity;
  CHECK(c.progress(1e-13, 1000.0, previous) == IterationControl::Progress::converged);
  CHECK(c.stop(1e-13, 1000.0, previous));
}

TEST_CASE("make_control: the method's budget unless options set one; a tolerance sets both") {
  std::vector<std::array<double, 3>> trace;
  Options o;
  IterationControl c = curve::make_control(o, 77, &trace);
  CHECK(c.max_iterations == 77);
  CHECK(c.trace == nullptr);  // only with options.trace
  CHECK(c.step_tolerance == 1e-15);
  CHECK(c.residual_tolerance == 1e-12);
  o.max_iterations = 5;
  o.tolerance = 1e-10;
  o.trace = true;
  o.max_distance = 2.0;
  c = curve::make_control(o, 77, &trace);
  CHECK(c.max_iterations == 5);
  CHECK(c.trace == &trace);
  CHECK(c.step_tolerance == 1e-10);
  CHECK(c.residual_tolerance == 1e-10);
  c.record(1, 2, 3);
  CHECK(trace.size() == 1);
  CHECK(curve::within_max_distance(Status::converged, 3.0, c) == Status::beyond_max_distance);
  CHECK(curve::within_max_distance(Status::converged, 1.0, c) == Status::converged);
  CHECK(curve::within_max_distance(Status::degenerate, 3.0, c) == Status::degenerate);
  o.tolerance = 1e-20;  // a tighter tolerance than the residuals can meet keeps the residual one
  CHECK(curve::make_control(o, 77, nullptr).residual_tolerance == 1e-12);
}
