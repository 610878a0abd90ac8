// solvers/auto_result: how the curve searches keep distinct minima and finish their answer.
#include <doctest/doctest.h>

#include <vector>

#include "solvers/auto_result.hpp"

using namespace footpoint;

TEST_CASE("add_distinct_minimum: minima are told apart by foot point") {
  std::vector<Minimum> minima;
  curve::add_distinct_minimum(minima, {1, 0, 0}, 1e-8, {{1, 0, 0}, {0, 0}, 2.0, Location::interior});
  curve::add_distinct_minimum(minima, {1 + 1e-9, 0, 0}, 1e-8,
                              {{1 + 1e-9, 0, 0}, {0, 0}, 2.0, Location::interior});
  CHECK(minima.size() == 1);
  curve::add_distinct_minimum(minima, {0, 1, 0}, 1e-8, {{0, 1, 0}, {0, 0}, 1.5, Location::endpoint});
  CHECK(minima.size() == 2);
}

TEST_CASE(
    "finish_auto_result: status from the residuals and max_distance; minima best first; trace on request") {
  const std::vector<Minimum> minima{{{1, 0, 0}, {0, 0}, 2.0, Location::interior},
                                    {{0, 1, 0}, {0, 0}, 1.5, Location::endpoint}};
  ProjectionResult r;
  r.distance = 1.5;
  Options o;
  curve::finish_auto_result(r, true, 4, 1e-16, 3, o, minima, {{1, 2, 3}});
  CHECK(r.summary.status == Status::converged);
  CHECK(r.summary.iterations == 4);
  CHECK(r.summary.step_norm == 1e-16);
  CHECK(r.summary.starts == 3);
  CHECK(r.minima.empty());
  CHECK(r.trace.empty());
  o.all_minima = true;
  o.trace = true;
  curve::finish_auto_result(r, false, 4, 1e-16, 3, o, minima, {{1, 2, 3}});
  CHECK(r.summary.status == Status::degenerate);
  REQUIRE(r.minima.size() == 2);
  CHECK(r.minima[0].distance == 1.5);
  CHECK(r.trace.size() == 1);
  o.max_distance = 1.0;
  curve::finish_auto_result(r, true, 4, 1e-16, 3, o, minima, {});
  CHECK(r.summary.status == Status::beyond_max_distance);
}
