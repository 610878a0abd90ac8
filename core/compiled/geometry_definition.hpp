// Geometry definitions: what a client posts (the formulas, the domain or box, user constants, the
// parameter directions it declares periodic), in a canonical text form whose SHA-256 hash is the
// geometry's id.
#pragma once
#include <array>
#include <map>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "compiled/expected.hpp"
#include "formula/program.hpp"
#include "geometry/geometry_error.hpp"

namespace footpoint {

enum class GeometryType {
  parametric_surface,
  parametric_curve,
  implicit_curve,
  implicit_surface,
  bspline_surface,
  bspline_curve
};
inline constexpr GeometryType kGeometryTypes[] = {
    GeometryType::parametric_surface, GeometryType::parametric_curve, GeometryType::implicit_curve,
    GeometryType::implicit_surface,   GeometryType::bspline_surface,  GeometryType::bspline_curve};
const char* to_string(GeometryType t);

// A B-spline or NURBS as posted (parametric/geometry/nurbs.hpp checks it): one degree per parameter,
// the full knot vectors (u, then v), the control points in rows (a curve: one row of points of 2 or
// 3 coordinates; a surface: control_points[i][j] = P_ij, i along u) and the weights in the same
// rows (empty: every weight 1, non-rational).
struct BSplineNet {
  std::vector<int> degree;
  std::vector<std::vector<double>> knots;
  std::vector<std::vector<std::vector<double>>> control_points;
  std::vector<std::vector<double>> weights;
};

struct GeometryDefinition {
  GeometryType type = GeometryType::parametric_surface;
  // parametric_surface: x, y, z (in u, v); parametric_curve: x, y[, z] (in t);
  // implicit_curve: equations[0][, equations[1]] (in x, y[, z]); implicit_surface: equation (in
  // x, y, z).
  std::vector<formula::NamedFormula> formulas;
  // Parameter domain (surfaces: u, v; curves: t) or box (implicit: x, y[, z]), in that order.
  std::vector<std::pair<std::string, std::array<double, 2>>> domain;
  std::map<std::string, double> constants;
  // Parameters declared periodic (parametric/geometry/surface_closure.hpp, curve_closure.hpp): "u", "v" of a
  // surface, "t" of a curve; none for implicit curves. Any order; repeats count once.
  std::vector<std::string> periodic;
  // `periodic` sorted, each name once: as the canonical form and the JSON form list them.
  std::vector<std::string> periodic_parameters() const;
  // bspline_curve and bspline_surface: the net (no formulas, domain or constants: the domain is
  // [knots[p], knots[n]] of each parameter). Last, with a default, so that the definitions of the
  // other types are written as before.
  BSplineNet bspline{};

  // Deterministic text form: same definition -> same text (formula whitespace removed, numbers
  // in shortest round-trip form, periodic names sorted, once each and only when there are any, so
  // that the texts and ids of definitions without them are what they always were). id() is a
  // SHA-256 content hash of it (32 hex digits), so every replica computes the same id for the
  // same definition.
  std::string canonical() const;
  std::string id() const;
};

// A bound of a domain interval written as a constant expression in the formula syntax ("2*_pi",
// "R+1" with the definition's `constants`), evaluated once, before the id is computed: the
// definition holds the value, so "2*_pi" and 6.283185307179586 give the same id. Or why it has
// none: a GeometryError naming `field` ("domain.t[1]") with the code, the character position and
// a suggestion as for a formula (bad_domain when the value is not finite).
Expected<double, GeometryError> evaluate_bound(const std::string& field, const std::string& expression,
                                               const std::map<std::string, double>& constants);

// The inverse of canonical(): the definition whose canonical text is `text`, with the formula
// names and domain variables a posted definition of its type has (a shared registry stores
// canonical texts; a replica compiles from them). canonical(parse_canonical(t)) == t for every
// text accepted; any other text throws GeometryError with code "bad_canonical".
GeometryDefinition parse_canonical(std::string_view text);

}  // namespace footpoint
