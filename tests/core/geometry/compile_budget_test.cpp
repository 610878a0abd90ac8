// CompileBudget's own rules: what it counts, its bound on bytes, its deadline. A compile's use of
// it (each geometry type's compiler stopped in time and at its size) is in
// tests/cases/core/compile_budget_test.cpp, which needs the compiled layer.
#include "geometry/compile_budget.hpp"

#include <doctest/doctest.h>

#include <chrono>
#include <cstddef>
#include <string>

#include "geometry/geometry_error.hpp"

using namespace footpoint;

TEST_CASE("CompileBudget: counts what grows, stops past its bound and past its deadline") {
  CompileBudget unbounded;
  unbounded.grow(std::size_t{1} << 40);
  for (int k = 0; k < 1000; ++k) unbounded.check();
  CHECK(unbounded.grown() == std::size_t{1} << 40);

  CompileBudget bytes(CompileBudget::clock::time_point::max(), 100);
  bytes.grow(60);
  bytes.grow(40);  // at the bound: still allowed
  CHECK(bytes.grown() == 100);
  CHECK_THROWS_AS(bytes.grow(1), GeometryError);
  CHECK(bytes.grown() == 101);

  // Past the deadline: the clock is read once every 64 checks, so the 64th throws at the latest.
  CompileBudget late(CompileBudget::clock::now() - std::chrono::seconds(1));
  std::string code;
  int checks = 0;
  try {
    for (; checks < 64; ++checks) late.check();
  } catch (const GeometryError& e) {
    code = e.code;
  }
  CHECK(code == "compile_timeout");
  CHECK(checks < 64);
}
