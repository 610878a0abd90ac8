// The compiled B-spline and NURBS curves and surfaces (definitions: compiled/geometry_definition.hpp
// BSplineNet; evaluation: parametric/geometry/nurbs.hpp, The NURBS Book's algorithms). Compiled
// into their Bézier pieces (parametric/geometry/nurbs_patches.hpp), each a parametric curve or
// surface of the engine over its knot span with its own cells; `auto` is the branch and bound over
// the pieces (solvers/piecewise_nearest.hpp) with every piece's certified `auto`, so its answer is
// the global nearest point over the whole domain with a certificate, as for formulas.
//
// Where the foot lies: on the domain's edges and corners (a curve's ends) as for formulas; a
// piece's edge inside the domain is interior, a seam of a closed direction too (the first and last
// pieces' boundary control points coincide), and a knot line where the two sides' normals (a
// curve's tangents) differ is a `kink` (a C0 joint that is not smooth; a knot of multiplicity =
// degree where the geometry stays smooth, as on the NURBS circle, is interior). Poles are found
// per piece (a degenerate edge of its Bézier net).
//
// The papers' local methods run on the piece holding their start (options.initial, else the
// domain's centre); a piece's polynomial continues beyond its span, so where the iteration
// converges outside the span but inside the domain, it runs again on the piece there from that
// point, until it converges inside the piece it runs on (or outside the domain: outside_domain).
// Asked to certify, their answer gets `auto`'s certificate of the whole geometry (refuted with
// nearer_point when `auto` finds a point nearer by more than the gap). `evaluate` and the normals
// use the NURBS itself (de Boor).
#pragma once
#include <array>
#include <cstddef>
#include <memory>
#include <optional>
#include <string_view>
#include <vector>

#include "compiled/compiled_geometry.hpp"
#include "compiled/parametric_curve_geometry.hpp"
#include "compiled/parametric_surface_geometry.hpp"
#include "geometry/box3.hpp"
#include "geometry/compile_budget.hpp"
#include "parametric/geometry/nurbs.hpp"
#include "parametric/solvers/bezier_patch_nearest.hpp"
#include "solvers/piecewise_nearest.hpp"

namespace footpoint {

class BSplineSurface final : public CompiledGeometry {
 public:
  BSplineSurface(GeometryDefinition def, nurbs::Surface surface, const formula::CompileLimits& limits,
                 CompileBudget& budget);

  int point_dim() const override { return 3; }
  int num_params() const override { return 2; }
  const std::vector<MethodInfo>& methods() const override;
  std::size_t memory_bytes() const override;
  bool evaluate(const double* t, Evaluation& out) const override;
  bool foot_normal(const ProjectionResult& r, std::array<double, 3>& n) const override;

  const nurbs::Surface& surface() const { return surface_; }
  std::size_t pieces() const { return pieces_.size(); }
  const Box3& hull(std::size_t k) const { return tree_.hull(k); }  // holds piece k
  // Whether u (0) and v (1) close: the first and last pieces meet along the domain's edges.
  const std::array<bool, 2>& closed() const { return closed_; }
  ProjectionResult project_auto(const Vec3& p, const Options& options) const;

 private:
  ProjectionResult project_with(std::size_t index, const double* p, const Options& options) const override;
  // The local method `name` of the pieces, moved from piece to piece (see above).
  ProjectionResult project_local(std::string_view name, const Vec3& p, const Options& options) const;
  // A foot piece k answered at one of its poles (its closure): located there, its parameters on
  // the edge, and one foot rather than the edge's continuum of parameters.
  void at_pole(std::size_t k, const Vec3& p, ProjectionResult& r) const;
  // Piece k's jet at its local (s, t): its Bézier patch's where it has one, else its formula's.
  SurfaceJet piece_jet(std::size_t k, double s, double t) const;
  // The location on the whole surface of a foot piece k answered at its local (s, t).
  Location locate(std::size_t k, Location piece_location, double s, double t) const;

  nurbs::Surface surface_;
  // Piece k: a parametric surface in its local (s, t) in [0, 1]^2 over the knot spans spans_[k].
  std::vector<std::unique_ptr<ParametricSurface>> pieces_;
  std::vector<ParamBox> spans_;
  // Piece k's Bézier patch (rational or not; none above its degree limit): its nearest point by
  // nearest_on_patch first.
  std::vector<std::optional<BezierPatch>> patches_;
  PieceTree tree_;                           // the pieces' boxes
  std::vector<MethodInfo> methods_;          // auto, then the pieces' local methods
  std::vector<double> breaks_u_, breaks_v_;  // the distinct knots of the domain, ends included
  std::array<bool, 2> closed_{};
};

class BSplineCurve final : public CompiledGeometry {
 public:
  BSplineCurve(GeometryDefinition def, nurbs::Curve curve, const formula::CompileLimits& limits,
               CompileBudget& budget);

  int point_dim() const override { return curve_.dimension; }
  int num_params() const override { return 1; }
  const std::vector<MethodInfo>& methods() const override;
  std::size_t memory_bytes() const override;
  bool evaluate(const double* t, Evaluation& out) const override;
  bool foot_normal(const ProjectionResult& r, std::array<double, 3>& n) const override;

  const nurbs::Curve& curve() const { return curve_; }
  std::size_t pieces() const { return pieces_.size(); }
  bool closed() const { return closed_; }  // c(tmin) = c(tmax)
  ProjectionResult project_auto(const Vec3& p, const Options& options) const;

 private:
  ProjectionResult project_with(std::size_t index, const double* p, const Options& options) const override;
  ProjectionResult project_local(std::string_view name, const Vec3& p, const Options& options) const;
  Location locate(std::size_t k, Location piece_location, double s) const;

  nurbs::Curve curve_;
  std::vector<std::unique_ptr<ParametricCurve>> pieces_;  // in the local s in [0, 1] of spans_[k]
  std::vector<ParamInterval> spans_;
  PieceTree tree_;  // the pieces' boxes
  std::vector<MethodInfo> methods_;
  std::vector<double> breaks_;  // the distinct knots of the domain, ends included
  bool closed_ = false;
};

// The definition's net checked (GeometryError bad_bspline naming the field) and compiled.
std::shared_ptr<const CompiledGeometry> compile_bspline_surface(const GeometryDefinition& def,
                                                                const formula::CompileLimits& limits);
std::shared_ptr<const CompiledGeometry> compile_bspline_curve(const GeometryDefinition& def,
                                                              const formula::CompileLimits& limits);
const std::vector<MethodInfo>& bspline_surface_methods();
const std::vector<MethodInfo>& bspline_curve_methods();

// The most control points a B-spline or NURBS definition may have (a surface's net counted whole).
inline constexpr std::size_t kMaxControlPoints = 4096;

}  // namespace footpoint
