// The certified share of `auto` on the test suite's surface reference sets (tests/data/surface_*.json:
// the formulas, the domain and the points with their independent references): per set the points
// certified, and every point left uncertified with the certificate's reason, the answer's status,
// multiplicity and location, and whether the answer's distance agrees with the reference (1e-9
// relative). What stays uncertified is listed by reason at the end.
//
// Usage: certified_share_bench [tests/data directory, default the source tree's]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "compiled/compiled_geometry.hpp"

using namespace footpoint;
using json = nlohmann::json;

#ifndef FOOTPOINT_SOURCE_DATA
#define FOOTPOINT_SOURCE_DATA FOOTPOINT_OCCT_DIR "/../../tests/data"
#endif

int main(int argc, char** argv) {
  if (argc > 1 && (!std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h"))) {
    std::printf("usage: certified_share_bench [tests/data directory]\n");
    return 0;
  }
  const std::filesystem::path dir = argc > 1 ? argv[1] : FOOTPOINT_SOURCE_DATA;
  std::vector<std::filesystem::path> files;
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (name.rfind("surface_", 0) == 0 && e.path().extension() == ".json") files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  int total = 0, certified = 0;
  std::map<std::string, int> by_reason;
  for (const auto& file : files) {
    std::ifstream in(file);
    const json set = json::parse(in);
    // a parametric surface's set (the implicit surfaces' file holds cases of another shape)
    if (!set.is_object() || !set.contains("formulas") || !set["formulas"].contains("z") ||
        !set.contains("points"))
      continue;
    GeometryDefinition def;
    def.type = GeometryType::parametric_surface;
    for (const char* c : {"x", "y", "z"}) def.formulas.push_back({c, set["formulas"][c].get<std::string>()});
    for (const char* v : {"u", "v"})
      def.domain.push_back({v, {set["domain"][v][0].get<double>(), set["domain"][v][1].get<double>()}});
    if (set.contains("periodic")) def.periodic = set["periodic"].get<std::vector<std::string>>();
    if (set.contains("constants"))
      for (const auto& [k, v] : set["constants"].items()) def.constants[k] = v.get<double>();
    const auto g = compile_geometry(def, {});
    const GeometryMethod m = g->method("auto").value();
    int n = 0, ok = 0;
    for (const json& point : set["points"]) {
      const double p[3] = {point["p"][0].get<double>(), point["p"][1].get<double>(),
                           point["p"][2].get<double>()};
      const ProjectionResult r = m.project(p, Options{});
      ++n;
      if (r.summary.certificate.certified) {
        ++ok;
        continue;
      }
      const double want = point["oracle"]["distance"].get<double>();
      const bool agrees = std::abs(r.distance - want) <= 1e-9 * std::max(1.0, want);
      const std::string reason = to_string(r.summary.certificate.reason);
      ++by_reason[reason];
      std::printf("  %-22s p = (%g, %g, %g): %s, status %s, %s, location %s, distance %s the reference\n",
                  file.stem().string().c_str(), p[0], p[1], p[2], reason.c_str(), to_string(r.summary.status),
                  to_string(r.summary.multiplicity.kind), to_string(r.summary.location),
                  agrees ? "equals" : "differs from");
    }
    std::printf("%-24s %3d of %3d certified\n", file.stem().string().c_str(), ok, n);
    total += n;
    certified += ok;
  }
  std::printf("all surface reference sets: %d of %d certified (%.1f %%)\n", certified, total,
              total > 0 ? 100.0 * certified / total : 0.0);
  for (const auto& [reason, count] : by_reason) std::printf("  uncertified, %s: %d\n", reason.c_str(), count);
  return 0;
}
