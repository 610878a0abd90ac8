// Shared by the closure tests of this folder: the message of the GeometryError a closure's
// detection throws where a declared period does not hold (code not_periodic, field periodic).
#pragma once
#include <doctest/doctest.h>

#include <string>

#include "geometry/geometry_error.hpp"

namespace footpoint::test {

template <class Detect>
std::string closure_refusal(Detect detect) {
  try {
    detect();
  } catch (const GeometryError& e) {
    CHECK(e.code == "not_periodic");
    CHECK(e.field == "periodic");
    return e.what();
  }
  FAIL("no GeometryError");
  return {};
}

}  // namespace footpoint::test
