// The surfaces and point sets of the Open CASCADE comparison (bench/occt/data/<NAME>.json, written
// by bench/occt/make_data.py), read for bench/occt/occt_compare.cpp and surface_bench --peer, and
// the accuracy both print against the sets' 50-digit references.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

namespace footpoint::bench {

struct Reference {
  double distance = 0.0;
  std::array<double, 2> params{};
  std::string where;  // interior, edge or corner
};

struct PointSet {
  std::string name;  // box: uniform in twice the bounding box; near: within 1% of the surface
  std::vector<std::array<double, 3>> points;
  std::vector<Reference> references;
};

struct ComparisonSurface {
  std::string name;
  std::string x, y, z;  // muparser formulas in u, v; empty for a B-spline surface
  // the bspline_surface definition (issue 35's JSON: degree, knots, control_points[i][j] with i
  // along u, optional weights), null for a formula surface
  std::shared_ptr<const nlohmann::json> bspline;
  // surfaces.json's "footpoint" (default true): false where footpoint's side is not measured yet
  bool footpoint = true;
  std::array<double, 2> u{}, v{};
  // Open CASCADE's form: Bezier poles [k][l] on (s, t) in [0,1]^2, u = u0 + (u1 - u0) s, or a torus
  std::vector<std::vector<std::array<double, 3>>> bezier_poles;
  double torus_major = 0.0, torus_minor = 0.0;
  std::vector<PointSet> sets;
};

// The surface NAME of the comparison in DIR: DIR/data/NAME.json with DIR/surfaces.json's flags.
inline ComparisonSurface read_comparison_surface(const std::string& dir, const std::string& name) {
  const std::string path = dir + "/data/" + name + ".json";
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path + " (bench/occt/make_data.py writes it)");
  const nlohmann::json j = nlohmann::json::parse(in);
  ComparisonSurface s;
  s.name = j.at("name");
  if (j.contains("bspline")) {
    s.bspline = std::make_shared<const nlohmann::json>(j["bspline"]);
  } else {
    s.x = j.at("formulas").at("x");
    s.y = j.at("formulas").at("y");
    s.z = j.at("formulas").at("z");
  }
  std::ifstream list(dir + "/surfaces.json");
  if (!list) throw std::runtime_error("cannot read " + dir + "/surfaces.json");
  const nlohmann::json surfaces = nlohmann::json::parse(list);
  for (const nlohmann::json& e : surfaces.at("surfaces"))
    if (e.at("name") == name) s.footpoint = e.value("footpoint", true);
  s.u = j.at("domain").at("u").get<std::array<double, 2>>();
  s.v = j.at("domain").at("v").get<std::array<double, 2>>();
  if (j.contains("bezier")) s.bezier_poles = j["bezier"]["poles"].get<decltype(s.bezier_poles)>();
  if (j.contains("torus")) {
    s.torus_major = j["torus"]["R"];
    s.torus_minor = j["torus"]["r"];
  }
  for (const char* name : {"box", "near"}) {
    const nlohmann::json& set = j.at("sets").at(name);
    PointSet ps;
    ps.name = name;
    ps.points = set.at("points").get<std::vector<std::array<double, 3>>>();
    for (const nlohmann::json& r : set.at("references"))
      ps.references.push_back({r.at("distance"), r.at("params").get<std::array<double, 2>>(), r.at("where")});
    s.sets.push_back(std::move(ps));
  }
  return s;
}

// The surface names of bench/occt/surfaces.json, in its order.
inline std::vector<std::string> comparison_surface_names(const std::string& dir) {
  std::ifstream in(dir + "/surfaces.json");
  if (!in) throw std::runtime_error("cannot read " + dir + "/surfaces.json");
  const nlohmann::json surfaces = nlohmann::json::parse(in);
  std::vector<std::string> names;
  for (const nlohmann::json& s : surfaces.at("surfaces")) names.push_back(s.at("name"));
  return names;
}

// One answer of a method for one point: no answer, or the distance it reports.
struct Answer {
  bool ok = false;
  double distance = 0.0;
};

// How the answers of a method compare with the references: a point is global when its distance
// is within 1e-9 relative of the reference (the references are exact to 50 digits).
struct Accuracy {
  int points = 0, no_answer = 0, not_global = 0;
  double max_relative_error = 0.0;  // over the global answers: |d - d_ref| / d_ref
};

inline Accuracy accuracy(const std::vector<Answer>& answers, const std::vector<Reference>& refs) {
  Accuracy a;
  for (std::size_t i = 0; i < answers.size(); ++i) {
    ++a.points;
    if (!answers[i].ok) {
      ++a.no_answer;
      continue;
    }
    const double ref = refs[i].distance;
    const double rel = (answers[i].distance - ref) / std::max(ref, 1e-300);
    if (rel > 1e-9) {
      ++a.not_global;
    } else {
      a.max_relative_error = std::max(a.max_relative_error, std::fabs(rel));
    }
  }
  return a;
}

}  // namespace footpoint::bench
