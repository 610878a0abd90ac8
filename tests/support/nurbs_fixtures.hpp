// The rational circle and sphere and a roof as B-spline definitions, shared by the tests of the compiled
// NURBS (tests/core/compiled/bspline_geometry_test.cpp) and of their meshes
// (tests/core/mesh/bspline_mesh_test.cpp).
#pragma once
#include <cmath>
#include <vector>

#include "compiled/geometry_definition.hpp"

namespace footpoint::test {

inline const double kHalfRoot2 = std::sqrt(0.5);

// The full circle of radius r in the plane, degree 2 with nine control points ([PieglTiller]
// Fig. 7.16 / eq. (7.x): the square's corners weighted √2/2).
inline void circle_points(double r, std::vector<std::vector<double>>& points, std::vector<double>& weights) {
  const double xs[9][2] = {{1, 0}, {1, 1}, {0, 1}, {-1, 1}, {-1, 0}, {-1, -1}, {0, -1}, {1, -1}, {1, 0}};
  for (int i = 0; i < 9; ++i) {
    points.push_back({r * xs[i][0], r * xs[i][1]});
    weights.push_back(i % 2 ? kHalfRoot2 : 1.0);
  }
}
inline const std::vector<double> kCircleKnots = {0, 0, 0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1, 1, 1};

inline GeometryDefinition nurbs_circle(double r) {
  GeometryDefinition def;
  def.type = GeometryType::bspline_curve;
  def.bspline.degree = {2};
  def.bspline.knots = {kCircleKnots};
  std::vector<std::vector<double>> points;
  std::vector<double> weights;
  circle_points(r, points, weights);
  def.bspline.control_points = {points};
  def.bspline.weights = {weights};
  return def;
}

// The unit sphere: the circle in u (around z) times the half circle from the south pole to the
// north pole in v, weights the products.
inline GeometryDefinition nurbs_sphere() {
  GeometryDefinition def;
  def.type = GeometryType::bspline_surface;
  def.bspline.degree = {2, 2};
  def.bspline.knots = {kCircleKnots, {0, 0, 0, 0.5, 0.5, 1, 1, 1}};
  std::vector<std::vector<double>> circle;
  std::vector<double> cw;
  circle_points(1.0, circle, cw);
  // the half circle in the (rho, z) plane: (0,-1) (1,-1) (1,0) (1,1) (0,1)
  const double half[5][2] = {{0, -1}, {1, -1}, {1, 0}, {1, 1}, {0, 1}};
  const double hw[5] = {1, kHalfRoot2, 1, kHalfRoot2, 1};
  for (int i = 0; i < 9; ++i) {
    std::vector<std::vector<double>> row;
    std::vector<double> wrow;
    for (int j = 0; j < 5; ++j) {
      row.push_back({circle[i][0] * half[j][0], circle[i][1] * half[j][0], half[j][1]});
      wrow.push_back(cw[i] * hw[j]);
    }
    def.bspline.control_points.push_back(row);
    def.bspline.weights.push_back(wrow);
  }
  return def;
}

// A roof of two planes meeting in a C0 ridge: z = 1 - |x - 1| over [0, 2] x [0, 1] (x = u, y = v),
// degree 1 with the ridge at the knot u = 1.
inline GeometryDefinition nurbs_roof() {
  GeometryDefinition def;
  def.type = GeometryType::bspline_surface;
  def.bspline.degree = {1, 1};
  def.bspline.knots = {{0, 0, 1, 2, 2}, {0, 0, 1, 1}};
  def.bspline.control_points = {{{0, 0, 0}, {0, 1, 0}}, {{1, 0, 1}, {1, 1, 1}}, {{2, 0, 0}, {2, 1, 0}}};
  return def;
}

}  // namespace footpoint::test
