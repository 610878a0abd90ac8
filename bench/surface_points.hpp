// The surfaces and point sets of the surface benchmarks. Point sets: `box` points uniform in the box centred
// on the surface's bounding box with twice its extent (the bounding box from a 201 x 201 grid of the domain),
// and `near` points within 1 % of its diagonal of a point of the surface at uniformly random parameters (a
// uniformly random direction, a uniformly random distance up to 1 %).
#pragma once

#include <algorithm>
#include <array>
#include <random>
#include <string>
#include <vector>

#include "compiled/parametric_surface_geometry.hpp"

namespace footpoint::bench {

// The surfaces of the benchmarks: S1-S3 of the Open CASCADE comparison (bench/occt/surfaces.json),
// [GSA] Example 1 over [-25,25]^2 (A1), and two closed ones.
struct SurfaceSpec {
  std::string name;
  std::string x, y, z;
  std::array<double, 2> u, v;
};

inline const char* const kS3x = "u^6+u^5*v+v^6-u^2*v^3+u*v^4-v^5+u^4+u^3*v+v^4+u^3-u*v^2+v^3+u*v+v^2+1";
inline const char* const kS3y =
    "u^6+2*u^4*v^2-v^6+u^5+u^2*v^3+v^5+u^4-u*v^3+u^3-2*u*v^2+v^3+4*u*v+2*v^2+2*u+2*v+1";
inline const char* const kS3z = "u^6+u*v^5+u^4*v+u^2*v^3+u^3*v+2*u^2*v^2+v^4+u^3+2*u*v+u";

inline const SurfaceSpec kSurfaces[] = {
    {"S1", "u+v", "sin(u)+2*cos(v)", "sin(u+v)", {-3, 3}, {-3, 3}},
    {"S2", "u^4*v^3+u*v+u", "u^3+v^3", "u+v", {-2, 2}, {-2, 2}},
    {"S3", kS3x, kS3y, kS3z, {0, 2}, {0, 2}},
    {"A1", "u+v", "sin(u)+2*cos(v)", "sin(u+v)", {-25, 25}, {-25, 25}},
    // closed: a seam each way; a seam and two poles
    {"torus",
     "(3+cos(v))*cos(u)",
     "(3+cos(v))*sin(u)",
     "sin(v)",
     {0, 6.283185307179586},
     {0, 6.283185307179586}},
    {"sphere",
     "cos(u)*cos(v)",
     "sin(u)*cos(v)",
     "sin(v)",
     {0, 6.283185307179586},
     {-1.5707963267948966, 1.5707963267948966}},
};

struct SurfacePoints {
  std::vector<Vec3> box, near;
  double size = 0.0;  // diagonal of the surface's bounding box
};

inline SurfacePoints make_surface_points(const ParametricSurface& g, int box_count, int near_count,
                                         unsigned seed) {
  const ParamBox& b = g.domain();
  Vec3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  for (int i = 0; i <= 200; ++i)
    for (int j = 0; j <= 200; ++j) {
      const Vec3 s =
          g.formulas().point(b.umin + (b.umax - b.umin) * i / 200.0, b.vmin + (b.vmax - b.vmin) * j / 200.0);
      for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], s[k]), hi[k] = std::max(hi[k], s[k]);
    }
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  SurfacePoints ps;
  for (int i = 0; i < box_count; ++i) {
    Vec3 p;
    for (int k = 0; k < 3; ++k) p[k] = lo[k] + (hi[k] - lo[k]) * (2.0 * U(rng) - 0.5);
    ps.box.push_back(p);
  }
  ps.size = norm(hi - lo);
  std::normal_distribution<double> N(0.0, 1.0);
  for (int i = 0; i < near_count; ++i) {
    const Vec3 s =
        g.formulas().point(b.umin + (b.umax - b.umin) * U(rng), b.vmin + (b.vmax - b.vmin) * U(rng));
    Vec3 d{N(rng), N(rng), N(rng)};
    ps.near.push_back(s + d * (0.01 * ps.size * U(rng) / norm(d)));
  }
  return ps;
}

}  // namespace footpoint::bench
