// Shared by the surface tests: building a compiled surface and projecting one point.
#pragma once
#include <array>
#include <cmath>
#include <fstream>
#include <memory>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "compiled/compiled_geometry.hpp"
#include "compiled/parametric_surface_geometry.hpp"

namespace footpoint::test {

inline std::shared_ptr<const ParametricSurface> make_surface(const std::string& x, const std::string& y,
                                                             const std::string& z, std::array<double, 2> u,
                                                             std::array<double, 2> v) {
  GeometryDefinition def;
  def.type = GeometryType::parametric_surface;
  def.formulas = {{"x", x}, {"y", y}, {"z", z}};
  def.domain = {{"u", u}, {"v", v}};
  return std::dynamic_pointer_cast<const ParametricSurface>(compile_parametric_surface(def, {}));
}

// The [GSA] Example 1 surface over [-w,w]^2 (w = 25: 8 periods each way, folded; w = 3: S1).
inline GeometryDefinition example1(double half_width) {
  GeometryDefinition def;
  def.type = GeometryType::parametric_surface;
  def.formulas = {{"x", "u+v"}, {"y", "sin(u)+2*cos(v)"}, {"z", "sin(u+v)"}};
  def.domain = {{"u", {-half_width, half_width}}, {"v", {-half_width, half_width}}};
  return def;
}

// A parametric surface compiled with seeding options of its own (compile_parametric_surface
// uses the defaults).
inline ParametricSurface compile_with(const GeometryDefinition& def, const SurfaceSeedingOptions& seeding) {
  const auto u = def.domain[0].second, v = def.domain[1].second;
  CompileBudget unbounded;
  return ParametricSurface(def, compile_formulas(def, {"u", "v"}, {}), ParamBox{u[0], u[1], v[0], v[1]},
                           unbounded, seeding);
}

inline ProjectionResult project(const CompiledGeometry& g, std::array<double, 3> p, std::string_view method,
                                const Options& options = {}) {
  return g.project(p.data(), method, options).value();
}

inline Options start_at(double u, double v) {
  Options o;
  o.initial = std::array<double, 3>{u, v, 0.0};
  return o;
}

inline nlohmann::json read_json(const std::string& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

inline double dist3(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  return std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
}

// Printed to three significant digits: |x - printed| within 0.6 units of the third digit.
inline bool matches_3_digits(double x, double printed) {
  if (printed == 0.0) return std::abs(x) < 1e-15;
  const double unit = std::pow(10.0, std::floor(std::log10(std::abs(printed))) - 2);
  return std::abs(x - printed) <= 0.6 * unit;
}

}  // namespace footpoint::test

namespace footpoint::test {

// Asserts auto's answer for one oracle record ({"p": ..., "oracle": {...}}, the format of
// public_cases.json and tests/data/surface_*.json): distance within 1e-12 relative (1e-12 absolute
// on the surface), foot within 1e-9 of the oracle's (of any tied foot when ambiguous), the same
// kind of location, converged.
// The certificate of an answer whose true distance is `reference` (to the last bit, or an upper
// bound of it): its lower bound never exceeds it, and a certified answer meets the gap.
inline void check_certificate(const ProjectionResult& r, double reference) {
  const Certificate& c = r.summary.certificate;
  CHECK(c.computed);
  CHECK(c.lower_bound <= reference * (1.0 + 0x1p-51));
  if (c.certified) CHECK(r.distance - c.lower_bound <= std::max(1e-9 * r.distance, c.absolute_gap));
  CHECK(c.certified == (c.reason == CertificateReason::gap_met));
}

inline void check_auto_against_oracle(const ParametricSurface& g, const nlohmann::json& point) {
  const std::array<double, 3> p = point.at("p").get<std::array<double, 3>>();
  const nlohmann::json& o = point.at("oracle");
  const double d_ref = o.at("distance").get<double>();
  const ProjectionResult r = g.project(p.data(), "auto", Options{}).value();
  INFO("p = (" << p[0] << ", " << p[1] << ", " << p[2] << "), oracle d = " << d_ref << " type "
               << o.at("type").get<std::string>() << "; auto d = " << r.distance << " at (" << r.params[0]
               << ", " << r.params[1] << "), status " << std::string(to_string(r.summary.status))
               << ", starts " << r.summary.starts);
  CHECK(r.summary.status == Status::converged);
  CHECK(r.summary.method == "auto");
  // 1e-12 relative, and the rounding of p - s in the coordinates (a few ulps of |p|: 4e-12 at 2e4)
  const double coordinates = std::max({std::abs(p[0]), std::abs(p[1]), std::abs(p[2])});
  CHECK(std::abs(r.distance - d_ref) <= 1e-12 * std::max(d_ref, 1.0) + 4.0 * 0x1p-52 * coordinates);
  CHECK(std::abs(dist3(r.foot, p) - r.distance) <= 1e-14 * std::max(r.distance, 1.0));
  CHECK(g.domain().contains(r.params[0], r.params[1]));
  const std::array<double, 3> foot_ref = o.at("foot").get<std::array<double, 3>>();
  const double foot_tol = 1e-9 * std::max(1.0, std::hypot(foot_ref[0], foot_ref[1], foot_ref[2]));
  if (o.value("ambiguous", false)) {
    // a tie between distinct feet (sometimes a whole circle of them): the distance says it all,
    // the foot being s(params) at that distance
    return;
  }
  CHECK(dist3(r.foot, foot_ref) <= foot_tol);
  // where several parameter pairs give the foot (seams, poles, periodic surfaces) the location
  // depends on which pair is reported
  if (!o.value("params_nonunique", false)) {
    const std::string type = o.at("type").get<std::string>();
    CHECK(type.rfind(to_string(r.summary.location), 0) == 0);
  }
  // a pole is no boundary of the surface (nor is a seam: its answers are interior)
  CHECK(r.summary.on_boundary ==
        (r.summary.location == Location::edge || r.summary.location == Location::corner));
  check_certificate(r, d_ref);
}

}  // namespace footpoint::test
