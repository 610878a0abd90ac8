// Small fixed-size vectors for the geometry (3-D points, tangents, normals).
#pragma once
#include <cmath>

namespace footpoint {

struct Vec3 {
  double x = 0.0, y = 0.0, z = 0.0;
  double& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }
  double operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
};

inline Vec3 operator+(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline Vec3 operator-(Vec3 a) { return {-a.x, -a.y, -a.z}; }
inline Vec3 operator*(double s, Vec3 a) { return {s * a.x, s * a.y, s * a.z}; }
inline Vec3 operator*(Vec3 a, double s) { return s * a; }
inline Vec3 operator/(Vec3 a, double s) { return {a.x / s, a.y / s, a.z / s}; }
inline Vec3& operator+=(Vec3& a, Vec3 b) {
  a = a + b;
  return a;
}
inline Vec3& operator-=(Vec3& a, Vec3 b) {
  a = a - b;
  return a;
}
inline double dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Vec3 cross(Vec3 a, Vec3 b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double norm(Vec3 a) { return std::sqrt(dot(a, a)); }
inline double norm2(Vec3 a) { return dot(a, a); }
// a / |a|, or 0 where |a| is 0 or not finite (no direction).
inline Vec3 unit(Vec3 a) {
  const double length = norm(a);
  return length > 0.0 && std::isfinite(length) ? a / length : Vec3{};
}
// 0 x is 0 for a finite x and NaN for an infinite or NaN one: one test for the three (no
// branch per coordinate).
inline bool is_finite(Vec3 a) { return (0.0 * a.x + 0.0 * a.y) + 0.0 * a.z == 0.0; }

}  // namespace footpoint
