// Prints every output of every method on a fixed, sizeable set of points, as hex floats: a
// regression check that a change leaves the results bitwise unchanged. Build it on both trees
// and compare the outputs:
//   build/tests/projection_dump tests/data [more_cases.json] > after.txt
//   cmp before.txt after.txt
// The geometries: every reference geometry of tests/data/*.json (surfaces and curves), the
// shapes of the brute-force sweep (tests/cases/surface/auto_stress_test.cpp) and, when given, the cases of a
// file in the format of tests/data/curve_*_cases.json or the papers' public cases. The points:
// each file's own, 48 uniform in the box twice the geometry's size, and 48 within 2 % of its
// size from the foot points of those. Every method runs with default options, and with a start,
// trace, all_minima and max_distance on a fixed subset of the points.
#include <algorithm>
#include <array>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "compiled/compiled_geometry.hpp"

using namespace footpoint;
using nlohmann::json;

namespace {

constexpr int kBoxPoints = 48;
constexpr int kNearPoints = 48;

struct Case {
  std::string name;
  GeometryDefinition def;
  std::vector<std::array<double, 3>> points;
};

// A double in a deterministic stream (the same on every build: the bits of a 64-bit generator).
struct Stream {
  std::mt19937_64 rng{20261122};
  double uniform() { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }
};

GeometryDefinition surface(const std::string& x, const std::string& y, const std::string& z,
                           std::array<double, 2> u, std::array<double, 2> v) {
  GeometryDefinition d;
  d.type = GeometryType::parametric_surface;
  d.formulas = {{"x", x}, {"y", y}, {"z", z}};
  d.domain = {{"u", u}, {"v", v}};
  return d;
}

std::array<double, 2> range(const json& j) { return {j[0].get<double>(), j[1].get<double>()}; }

bool finish_case(const json& c, Case k, std::vector<Case>& out);

// A case of tests/data/curve_*_cases.json, surface_implicit_cases.json or of the papers' public
// cases file.
bool add_case(const json& c, std::vector<Case>& out) {
  Case k;
  k.name = c.at("id").get<std::string>();
  const std::string kind = c.at("kind");
  const json& d = c.contains("domain") ? c.at("domain") : c.at("box");
  if (kind == "implicit_surface") {  // tests/data/surface_implicit_cases.json: one equation
    k.def.type = GeometryType::implicit_surface;
    k.def.formulas = {{"equation", c.at("equation")}};
    k.def.domain = {{"x", range(d["x"])}, {"y", range(d["y"])}, {"z", range(d["z"])}};
    return finish_case(c, std::move(k), out);
  }
  const json& f = c.at("formulas");
  if (kind == "surface") {
    k.def = surface(f["x"], f["y"], f["z"], range(d["u"]), range(d["v"]));
  } else if (kind == "paramcurve") {
    k.def.type = GeometryType::parametric_curve;
    k.def.formulas = {{"x", f["x"]}, {"y", f["y"]}};
    if (f.contains("z")) k.def.formulas.push_back({"z", f["z"]});
    k.def.domain = {{"t", range(d["t"])}};
  } else if (kind == "implicit2d") {
    k.def.type = GeometryType::implicit_curve;
    k.def.formulas = {{"equations[0]", f["f"]}};
    k.def.domain = {{"x", range(d["x"])}, {"y", range(d["y"])}};
  } else if (kind == "curve3d" || kind == "curve3d_implicit") {
    k.def.type = GeometryType::implicit_curve;
    k.def.formulas = {{"equations[0]", f["f1"]}, {"equations[1]", f["f2"]}};
    k.def.domain = {{"x", range(d["x"])}, {"y", range(d["y"])}, {"z", range(d["z"])}};
  } else {
    return false;
  }
  return finish_case(c, std::move(k), out);
}

// The case's points (objects with "p", or bare coordinates), and the case into `out`.
bool finish_case(const json& c, Case k, std::vector<Case>& out) {
  if (c.contains("points"))
    for (const json& p : c["points"]) {
      const json& q = p.is_object() ? p.at("p") : p;
      k.points.push_back({q[0].get<double>(), q[1].get<double>(), q.size() > 2 ? q[2].get<double>() : 0.0});
    }
  out.push_back(std::move(k));
  return true;
}

std::vector<Case> read_cases(const std::string& data_dir, const std::string& extra) {
  std::vector<Case> cases;
  std::vector<std::filesystem::path> files;
  for (const auto& e : std::filesystem::directory_iterator(data_dir))
    if (e.path().extension() == ".json") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  if (!extra.empty()) files.push_back(extra);
  for (const auto& path : files) {
    std::ifstream in(path);
    const json j = json::parse(in);
    if (j.contains("formulas") && j.contains("domain") && j["formulas"].contains("x") &&
        j["domain"].contains("u")) {  // tests/data/surface_*.json
      Case k;
      k.name = path.stem().string();
      const json& f = j["formulas"];
      k.def = surface(f["x"], f["y"], f["z"], range(j["domain"]["u"]), range(j["domain"]["v"]));
      for (const json& p : j["points"]) k.points.push_back(p.at("p").get<std::array<double, 3>>());
      cases.push_back(std::move(k));
    } else if (j.contains("cases")) {
      for (const json& c : j["cases"])
        if (c.is_object() && c.contains("kind")) add_case(c, cases);
    }
  }
  // The brute-force sweep's shapes (tests/cases/surface/auto_stress_test.cpp).
  const double tau = 6.283185307179586, half_pi = 1.5707963267948966;
  const std::vector<Case> stress = {
      {"stress_S1", surface("u+v", "sin(u)+2*cos(v)", "sin(u+v)", {-3, 3}, {-3, 3}), {}},
      {"stress_S2", surface("u^4*v^3+u*v+u", "u^3+v^3", "u+v", {-2, 2}, {-2, 2}), {}},
      {"stress_S3",
       surface("u^6+u^5*v+v^6-u^2*v^3+u*v^4-v^5+u^4+u^3*v+v^4+u^3-u*v^2+v^3+u*v+v^2+1",
               "u^6+2*u^4*v^2-v^6+u^5+u^2*v^3+v^5+u^4-u*v^3+u^3-2*u*v^2+v^3+4*u*v+2*v^2+2*u+2*v+1",
               "u^6+u*v^5+u^4*v+u^2*v^3+u^3*v+2*u^2*v^2+v^4+u^3+2*u*v+u", {0, 2}, {0, 2}),
       {}},
      {"stress_torus",
       surface("(2+0.5*cos(v))*cos(u)", "(2+0.5*cos(v))*sin(u)", "0.5*sin(v)", {0, tau}, {0, tau}),
       {}},
      {"stress_A1", surface("u+v", "sin(u)+2*cos(v)", "sin(u+v)", {-25, 25}, {-25, 25}), {}},
      {"stress_fold",
       surface("u+0.3*sin(4*v)", "v+0.3*cos(3*u)", "0.4*sin(2*u)*cos(3*v)", {-4, 4}, {-4, 4}),
       {}},
      {"stress_fold_near",
       surface("u+0.5*sin(3*v)", "v+0.5*cos(2*u)", "0.3*sin(3*u)*cos(2*v)", {-3, 3}, {-3, 3}),
       {}},
      {"stress_wavy", surface("u", "v", "0.2*sin(7*u)*sin(5*v)", {-4, 4}, {-4, 4}), {}},
      {"stress_ripple", surface("u", "v", "0.05*sin(20*u)*sin(17*v)", {-1, 1}, {-1, 1}), {}},
      {"stress_cone", surface("v*cos(u)", "v*sin(u)", "v", {0, tau}, {0, 1}), {}},
      {"stress_sphere",
       surface("cos(u)*cos(v)", "sin(u)*cos(v)", "sin(v)", {0, tau}, {-half_pi, half_pi}),
       {}},
      {"stress_saddle", surface("u", "v", "u*u*u-3*u*v*v+0.5*sin(4*u*v)", {-2, 2}, {-2, 2}), {}},
      {"stress_enneper", surface("u-u^3/3+u*v^2", "v-v^3/3+v*u^2", "u^2-v^2", {-2, 2}, {-2, 2}), {}},
  };
  cases.insert(cases.end(), stress.begin(), stress.end());
  return cases;
}

void hex(double x) { std::printf(" %a", x); }

void print(const ProjectionResult& r) {
  std::printf(" dim %d np %d foot", r.dim, r.num_params);
  for (double x : r.foot) hex(x);
  std::printf(" params");
  for (double x : r.params) hex(x);
  std::printf(" d");
  hex(r.distance);
  const Summary& s = r.summary;
  std::printf(" | %s %s it %d step", s.method.c_str(), to_string(s.status), s.iterations);
  hex(s.step_norm);
  std::printf(" orth");
  for (double x : s.orthogonality) hex(x);
  std::printf(" eq");
  for (double x : s.equation_residual) hex(x);
  std::printf(" starts %d %s %d", s.starts, to_string(s.location), s.on_boundary ? 1 : 0);
  if (!r.minima.empty()) {
    std::printf(" | minima %zu", r.minima.size());
    for (const Minimum& m : r.minima) {
      std::printf(" [");
      for (double x : m.foot) hex(x);
      for (double x : m.params) hex(x);
      hex(m.distance);
      std::printf(" %s]", to_string(m.location));
    }
  }
  if (!r.trace.empty()) {
    // Traces run to thousands of steps: their bits, folded (FNV-1a), and the last step.
    std::uint64_t h = 1469598103934665603ull;
    for (const auto& t : r.trace)
      for (double x : t) {
        std::uint64_t bits;
        std::memcpy(&bits, &x, sizeof bits);
        h = (h ^ bits) * 1099511628211ull;
      }
    std::printf(" | trace %zu %016" PRIx64 " last", r.trace.size(), h);
    for (double x : r.trace.back()) hex(x);
  }
  std::printf("\n");
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || argc > 3) {
    std::fprintf(stderr, "usage: %s DATA_DIR [CASES.json]\n", argv[0]);
    return 2;
  }
  const std::vector<Case> cases = read_cases(argv[1], argc == 3 ? argv[2] : "");
  Stream stream;
  for (const Case& c : cases) {
    std::shared_ptr<const CompiledGeometry> g;
    try {
      g = compile_geometry(c.def);
    } catch (const GeometryError& e) {
      std::printf("%s: %s %s\n", c.name.c_str(), e.code.c_str(), e.what());
      continue;
    }
    const int dim = g->point_dim();
    // The geometry's size: the box around the feet of a coarse grid of points over the box of
    // its own points and their feet (the definition's box for implicit curves).
    std::vector<std::array<double, 3>> points = c.points;
    std::array<double, 3> lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
    auto grow = [&](const std::array<double, 3>& x) {
      for (int k = 0; k < dim; ++k) lo[k] = std::min(lo[k], x[k]), hi[k] = std::max(hi[k], x[k]);
    };
    std::array<double, 3> glo{0, 0, 0}, ghi{0, 0, 0};
    if (c.def.type == GeometryType::implicit_curve) {
      for (int k = 0; k < dim; ++k) glo[k] = c.def.domain[k].second[0], ghi[k] = c.def.domain[k].second[1];
    } else {
      for (const auto& p : points) grow(p);
      if (points.empty()) lo = {-1, -1, -1}, hi = {1, 1, 1};
      glo = lo, ghi = hi;
    }
    lo = {1e300, 1e300, 1e300}, hi = {-1e300, -1e300, -1e300};
    for (int i = 0; i <= 4; ++i)
      for (int j = 0; j <= 4; ++j)
        for (int l = 0; l <= (dim == 3 ? 4 : 0); ++l) {
          const std::array<double, 3> q{glo[0] + (ghi[0] - glo[0]) * i / 4,
                                        glo[1] + (ghi[1] - glo[1]) * j / 4,
                                        dim == 3 ? glo[2] + (ghi[2] - glo[2]) * l / 4 : 0.0};
          const ProjectionResult r = g->project(q.data(), "auto", Options{}).value();
          if (std::isfinite(r.distance)) grow(r.foot);
        }
    double size = 0.0;
    for (int k = 0; k < dim; ++k) size = std::max(size, hi[k] - lo[k]);
    std::vector<std::array<double, 3>> box_points;
    for (int n = 0; n < kBoxPoints; ++n) {
      std::array<double, 3> p{0, 0, 0};
      for (int k = 0; k < dim; ++k)
        p[k] = 0.5 * (lo[k] + hi[k]) + (stream.uniform() - 0.5) * 2.0 * (hi[k] - lo[k]);
      box_points.push_back(p);
    }
    points.insert(points.end(), box_points.begin(), box_points.end());
    for (int n = 0; n < kNearPoints; ++n) {
      const ProjectionResult r = g->project(box_points[n % kBoxPoints].data(), "auto", Options{}).value();
      std::array<double, 3> p = r.foot;
      for (int k = 0; k < dim; ++k) p[k] += (stream.uniform() - 0.5) * 0.04 * size;
      points.push_back(p);
    }

    std::printf("== %s: %s, %zu points\n", c.name.c_str(), g->definition().canonical().c_str(),
                points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
      const double* p = points[i].data();
      for (const MethodInfo& m : g->methods()) {
        std::printf("%zu %s default", i, std::string(m.name).c_str());
        print(g->project(p, m.name, Options{}).value());
        if (i % 4 == 1) {  // a start: parameters in the domain, or a point near p
          Options o;
          std::array<double, 3> s{0, 0, 0};
          for (int k = 0; k < g->num_params(); ++k) {
            const auto& r = c.def.domain[k].second;
            s[k] = r[0] + (r[1] - r[0]) * stream.uniform();
          }
          if (g->num_params() == 0)
            for (int k = 0; k < dim; ++k) s[k] = p[k] + (stream.uniform() - 0.5) * 0.2 * size;
          o.initial = s;
          std::printf("%zu %s initial", i, std::string(m.name).c_str());
          print(g->project(p, m.name, o).value());
        }
        if (i % 5 == 2) {
          Options o;
          o.trace = true;
          o.all_minima = true;
          std::printf("%zu %s trace+minima", i, std::string(m.name).c_str());
          print(g->project(p, m.name, o).value());
        }
        if (i % 7 == 3) {
          Options o;
          o.max_distance = 0.01 * size;
          o.tolerance = 1e-10;
          std::printf("%zu %s max_distance+tolerance", i, std::string(m.name).c_str());
          print(g->project(p, m.name, o).value());
        }
      }
    }
  }
  return 0;
}
