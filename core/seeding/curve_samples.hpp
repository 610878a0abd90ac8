// Points on a curve, linked along it: what `auto` precomputes once per curve and reuses for every
// projected point. The spacing h bounds the arc length between linked neighbours, so every point of
// the curve (between a box face crossing, a singular point or a parameter end and the next) lies
// within arc length, hence distance, h/2 of a sample. That bound is what makes `auto` global: the
// nearest point X* of the curve has a sample s with |p - s| <= |p - X*| + h/2.
#pragma once
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "geometry/vec.hpp"

namespace footpoint {

enum class SampleKind : std::uint8_t {
  regular,         // an ordinary point of the curve
  endpoint,        // c(tmin) or c(tmax) of a parametric curve
  box_face,        // where an implicit curve crosses a face of its box (exact crossing point)
  singular_point,  // grad f1 x grad f2 = 0 (planar: grad f = 0), refined by Newton
};

struct CurveSamples {
  std::vector<Vec3> points;
  std::vector<std::int32_t> prev;  // neighbour before along the curve, -1 when none
  std::vector<std::int32_t> next;  // neighbour after along the curve, -1 when none
  std::vector<SampleKind> kind;
  std::vector<double> params;  // parametric curves: t of each sample; empty for implicit curves
  double spacing = 0.0;        // h: largest arc length between linked neighbours

  std::int32_t add(Vec3 x, SampleKind k = SampleKind::regular) {
    points.push_back(x);
    prev.push_back(-1);
    next.push_back(-1);
    kind.push_back(k);
    return static_cast<std::int32_t>(points.size() - 1);
  }
  void link(std::int32_t a, std::int32_t b) {  // b follows a along the curve
    next[static_cast<std::size_t>(a)] = b;
    prev[static_cast<std::size_t>(b)] = a;
  }
  std::size_t size() const { return points.size(); }
  // What add() stores per sample (a point, two links, a kind), params aside.
  static constexpr std::size_t kBytesPerSample = sizeof(Vec3) + 2 * sizeof(std::int32_t) + sizeof(SampleKind);
  std::size_t memory_bytes() const {
    return points.capacity() * sizeof(Vec3) + (prev.capacity() + next.capacity()) * sizeof(std::int32_t) +
           kind.capacity() + params.capacity() * sizeof(double);
  }
};

}  // namespace footpoint
